#pragma once

#include <stdexcept>
#include <string>

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

// Every failure mosb reports to a user: the message is one line and names the file it concerns.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : Error(ErrorCode::other, what) {}
  explicit Error(const char* what) : Error(ErrorCode::other, what) {}
  Error(ErrorCode code, const std::string& what)
      : std::runtime_error(what), code_(code), message_(what) {}

  ErrorCode code() const noexcept { return code_; }
  // The whole message. what() is a C string and ends at the first NUL, which a name read from a
  // file may hold: what prints a message prints this one, escaped (escape_for_terminal).
  const std::string& message() const noexcept { return message_; }

 private:
  ErrorCode code_;
  std::string message_;
};

}  // namespace mosb
