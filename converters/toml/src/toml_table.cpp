#include "mosb/converters/toml_table.hpp"

#include <cmath>

#include "mosb/error.hpp"
#include "mosb/internal/number_text.hpp"
#include "mosb/internal/source_error.hpp"

namespace mosb::converters {

namespace {

// toml++'s description of a syntax error may span lines: each line break (and the indentation
// after it) becomes "; ".
std::string joined_lines(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n' && text[i] != '\r') {
      out += text[i];
      continue;
    }
    while (i + 1 < text.size() && (text[i + 1] == '\n' || text[i + 1] == '\r' ||
                                   text[i + 1] == ' ' || text[i + 1] == '\t'))
      ++i;
    if (!out.empty() && i + 1 < text.size()) out += "; ";
  }
  return out;
}

bool control(char c, bool blanks) {
  const auto byte = static_cast<unsigned char>(c);
  return (byte < 0x20 || byte == 0x7f) && !(blanks && (c == '\n' || c == '\t'));
}

}  // namespace

TomlPosition position_of(const toml::node& node) {
  const auto& begin = node.source().begin;
  return {static_cast<std::size_t>(begin.line), static_cast<std::size_t>(begin.column)};
}

toml::table parse_toml(std::string_view text, const std::string& file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    const auto& begin = e.source().begin;
    throw Error(ErrorCode::invalid_argument,
                source_error(file, begin.line, begin.column, "", joined_lines(e.description())));
  }
}

TomlTable::TomlTable(const toml::table& table, std::string file, std::string prefix)
    : table_(table), file_(std::move(file)), prefix_(std::move(prefix)) {}

void TomlTable::fail(const toml::node& at, std::string_view key, const std::string& problem) const {
  const auto where = position_of(at);
  throw Error(ErrorCode::invalid_argument,
              source_error(file_, where.line, where.column, path(key), problem));
}

void TomlTable::fail_here(std::string_view key, const std::string& problem) const {
  fail(table_, key, problem);
}

const toml::node* TomlTable::get(std::string_view key) {
  known_.emplace(key);
  return table_.get(key);
}

std::optional<std::string> TomlTable::string(std::string_view key, bool blanks) {
  const auto* node = get(key);
  if (node == nullptr) return std::nullopt;
  if (!node->is_string()) fail(*node, key, "expected a string");
  auto value = *node->value<std::string>();
  for (const char c : value)
    if (control(c, blanks)) fail(*node, key, "a control character in the string");
  return value;
}

std::string TomlTable::required_string(std::string_view key, bool blanks, bool nonempty) {
  auto value = string(key, blanks);
  if (!value) fail_here(key, nonempty ? "is missing (a non-empty string)" : "is missing");
  if (nonempty && value->empty()) fail(*get(key), key, "is empty");
  return *value;
}

std::optional<bool> TomlTable::boolean(std::string_view key) {
  const auto* node = get(key);
  if (node == nullptr) return std::nullopt;
  if (!node->is_boolean()) fail(*node, key, "expected true or false");
  return node->value<bool>();
}

std::optional<std::int64_t> TomlTable::integer(std::string_view key, std::int64_t min,
                                               std::int64_t max) {
  const auto* node = get(key);
  if (node == nullptr) return std::nullopt;
  if (!node->is_integer()) fail(*node, key, "expected an integer");
  const auto value = *node->value<std::int64_t>();
  if (value < min || value > max)
    fail(*node, key,
         std::to_string(value) + " is not in [" + std::to_string(min) + ", " + std::to_string(max) +
             "]");
  return value;
}

std::optional<double> TomlTable::number(std::string_view key, double min, double max) {
  const auto* node = get(key);
  if (node == nullptr) return std::nullopt;
  if (!node->is_number()) fail(*node, key, "expected a number");
  const auto value = *node->value<double>();
  if (!std::isfinite(value) || value < min || value > max)
    fail(*node, key, "not a number in [" + shortest_text(min) + ", " + shortest_text(max) + "]");
  return value;
}

const toml::table* TomlTable::table(std::string_view key) {
  const auto* node = get(key);
  if (node == nullptr) return nullptr;
  if (!node->is_table()) fail(*node, key, "expected a table");
  return node->as_table();
}

const toml::array* TomlTable::array(std::string_view key) {
  const auto* node = get(key);
  if (node == nullptr) return nullptr;
  if (!node->is_array()) fail(*node, key, "expected an array");
  return node->as_array();
}

const toml::array* TomlTable::array_of_tables(std::string_view key) {
  const auto* node = get(key);
  if (node == nullptr) return nullptr;
  if (!node->is_array_of_tables())
    fail(*node, key, "expected an array of tables ([[" + std::string(key) + "]])");
  return node->as_array();
}

std::vector<std::pair<std::string, TomlPosition>> TomlTable::strings_at(std::string_view key) {
  std::vector<std::pair<std::string, TomlPosition>> out;
  const auto* node = get(key);
  if (node == nullptr) return out;
  const auto* list = node->as_array();
  if (list == nullptr) fail(*node, key, "expected an array of strings");
  for (const auto& item : *list) {
    if (!item.is_string()) fail(item, key, "expected an array of strings");
    const auto value = *item.value<std::string>();
    for (const char c : value)
      if (control(c, false)) fail(item, key, "a control character in the string");
    out.emplace_back(value, position_of(item));
  }
  return out;
}

std::vector<std::string> TomlTable::strings(std::string_view key) {
  std::vector<std::string> out;
  for (auto& [value, at] : strings_at(key)) out.push_back(std::move(value));
  return out;
}

std::string TomlTable::text_of(const toml::node& node) {
  if (const auto* v = node.as_string()) return v->get();
  if (const auto* v = node.as_integer()) return std::to_string(v->get());
  if (const auto* v = node.as_floating_point()) return shortest_text(v->get());
  if (const auto* v = node.as_boolean()) return v->get() ? "true" : "false";
  return "?";
}

void TomlTable::refuse_unknown() const {
  for (const auto& [key, node] : table_)
    if (!known_.contains(key.str())) {
      const auto& begin = key.source().begin;  // the key itself, not its value
      throw Error(ErrorCode::invalid_argument,
                  source_error(file_, begin.line, begin.column, path(key.str()), "unknown key"));
    }
}

}  // namespace mosb::converters
