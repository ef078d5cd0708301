// The one reader of a TOML table's keys for every TOML file mosb reads (solver profiles, spec/
// RUN.md §10; experiment files, spec/EXPERIMENT.md): each key read by type and marked known,
// refuse_unknown() refusing the others, so that a typo is never ignored. Every refusal is
// mosb::Error (invalid_argument), one line "FILE:LINE:COLUMN: key 'PATH': problem", PATH the
// key's dotted path from the root ("output.group", "solver[2].name").
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mosb/enum_names.hpp"

namespace mosb::converters {

// Where a node stands in its file: line and column, 1-based.
struct TomlPosition {
  std::size_t line = 0, column = 0;
};
TomlPosition position_of(const toml::node& node);

// `text` parsed as TOML; a syntax error is one line "FILE:LINE:COLUMN: problem" (toml++'s
// description, its line breaks and the indentation after them made "; ").
toml::table parse_toml(std::string_view text, const std::string& file);

class TomlTable {
 public:
  // `file` names the file in messages; `prefix` is the table's path with its dot ("" for the
  // root, "output.", "solver[1]."). `table` must outlive this reader.
  TomlTable(const toml::table& table, std::string file, std::string prefix);

  [[noreturn]] void fail(const toml::node& at, std::string_view key,
                         const std::string& problem) const;
  // A refusal at the table itself (a key that is missing, or keys that do not go together).
  [[noreturn]] void fail_here(std::string_view key, const std::string& problem) const;
  std::string path(std::string_view key) const { return prefix_ + std::string(key); }
  const std::string& file() const { return file_; }
  const toml::table& table_node() const { return table_; }

  // The node of `key`, or null; marks the key known.
  const toml::node* get(std::string_view key);
  // A string without control characters (`blanks`: tabs and line breaks allowed, a command's
  // words may span lines).
  std::optional<std::string> string(std::string_view key, bool blanks = false);
  // The string, refused when missing ("is missing") or, with `nonempty`, empty.
  std::string required_string(std::string_view key, bool blanks = false, bool nonempty = false);
  template <class Enum, std::size_t N>
  std::optional<Enum> choice(std::string_view key, const EnumNames<Enum, N>& names) {
    const auto text = string(key);
    if (!text) return std::nullopt;
    const auto value = names.parse(*text);
    if (!value) fail(*get(key), key, "'" + *text + "' is not one of " + names.choices_text());
    return value;
  }
  std::optional<bool> boolean(std::string_view key);
  std::optional<std::int64_t> integer(std::string_view key, std::int64_t min, std::int64_t max);
  std::optional<double> number(std::string_view key, double min, double max);
  const toml::table* table(std::string_view key);
  const toml::array* array(std::string_view key);
  const toml::array* array_of_tables(std::string_view key);
  // An array of strings (none when the key is absent), with each element's position.
  std::vector<std::pair<std::string, TomlPosition>> strings_at(std::string_view key);
  std::vector<std::string> strings(std::string_view key);
  // A string, number or boolean as text: a string as written, a number in its shortest
  // round-trip form, true or false.
  static std::string text_of(const toml::node& node);
  // Call last: refuses the first key nobody asked for.
  void refuse_unknown() const;

 private:
  const toml::table& table_;
  std::string file_;
  std::string prefix_;
  std::set<std::string, std::less<>> known_;
};

}  // namespace mosb::converters
