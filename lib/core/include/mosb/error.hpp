#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mosb/enum_names.hpp"

namespace mosb {

// What kind of failure an Error reports, so that callers branch on it instead of on the text.
enum class ErrorCode {
  other,             // not classified (text input errors of the converters, among others)
  io,                // the file system refused: cannot open, map, read or write
  not_mosb,          // the bytes are not a mosb file (wrong magic, too short, not a regular file)
  version,           // a format major version or a required feature this reader does not know
  damaged,           // a mosb file that breaks a rule of spec/FORMAT.md §9 (checksums included)
  not_found,         // no objective, query set, view or metadata key of that name
  invalid_argument,  // a call the file cannot answer as asked: wrong element type, index out of
                     // range
  packed,            // a zstd-packed section, which cannot be mapped zero-copy
  no_memory,         // out of memory, or decoding would need more than the cap (max_memory) allows
};
// The enumerators' names (Python's mosb.Error.code).
inline constexpr auto kErrorCodeNames = enum_names<ErrorCode>({
    {ErrorCode::other, "other"},
    {ErrorCode::io, "io"},
    {ErrorCode::not_mosb, "not_mosb"},
    {ErrorCode::version, "version"},
    {ErrorCode::damaged, "damaged"},
    {ErrorCode::not_found, "not_found"},
    {ErrorCode::invalid_argument, "invalid_argument"},
    {ErrorCode::packed, "packed"},
    {ErrorCode::no_memory, "no_memory"},
});

// One piece of an error message: text, or a setting the caller gave, named by the library's name
// for it (an option's field, such as "shards"). The library names what is wrong; each front end
// spells the setting its own way (the CLI as the flag that sets it, see message_text).
struct MessagePart {
  MessagePart(std::string words) : text(std::move(words)) {}  // NOLINT: text converts implicitly
  MessagePart(const char* words) : text(words) {}             // NOLINT: text converts implicitly
  std::string text;
  bool is_setting = false;
};
// The part naming setting `name`; precondition: `name` is the library's name of a caller's option.
inline MessagePart setting(std::string name) {
  MessagePart part(std::move(name));
  part.is_setting = true;
  return part;
}

// A message as parts: what an Error says, and what a result keeps of a failure it records (a
// refused entry of a pull) for the front end to spell.
using Message = std::vector<MessagePart>;
// The text of `message`, each setting spelled by `spell` (nullptr: by the library's name).
inline std::string message_text(const Message& message,
                                std::string (*spell)(std::string_view setting) = nullptr) {
  std::string text;
  for (const auto& part : message) text += part.is_setting && spell ? spell(part.text) : part.text;
  return text;
}

// Every failure mosb reports to a user: the message is one line and names the file it concerns.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : Error(ErrorCode::other, what) {}
  explicit Error(const char* what) : Error(ErrorCode::other, what) {}
  Error(ErrorCode code, const std::string& what)
      : std::runtime_error(what), code_(code), message_(what), parts_{MessagePart(what)} {}
  // A message that names settings of the caller (see MessagePart).
  Error(ErrorCode code, Message parts)
      : std::runtime_error(message_text(parts)),
        code_(code),
        message_(message_text(parts)),
        parts_(std::move(parts)) {}  // the members in this order: parts_ is moved last

  ErrorCode code() const noexcept { return code_; }
  // The whole message, settings named by the library's names. what() is a C string and ends at
  // the first NUL, which a name read from a file may hold: what prints a message prints this one,
  // escaped (escape_for_terminal).
  const std::string& message() const noexcept { return message_; }
  // The message as parts, for a front end to spell (message_text).
  const Message& parts() const noexcept { return parts_; }
  // This error with `context` (a file and line, say) put before its message.
  Error with_context(const std::string& context) const {
    auto parts = parts_;
    parts.insert(parts.begin(), MessagePart(context));
    return {code_, std::move(parts)};
  }

 private:
  ErrorCode code_;
  std::string message_;
  Message parts_;
};

}  // namespace mosb
