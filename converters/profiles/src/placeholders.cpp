#include "placeholders.hpp"

#include "mosb/error.hpp"

namespace mosb::converters::profile_internal {

namespace {

// Calls `name` for each placeholder and `literal` for the text between them (`{{` and `}}` as
// given); false on a lone brace.
template <class Name, class Literal>
bool scan(std::string_view word, Name&& name, Literal&& literal) {
  for (std::size_t i = 0; i < word.size(); ++i) {
    if (word.compare(i, 2, "{{") == 0 || word.compare(i, 2, "}}") == 0) {
      literal(word.substr(i, 2));
      ++i;
    } else if (word[i] == '{') {
      const auto close = word.find('}', i + 1);
      if (close == std::string_view::npos) return false;
      const auto inside = word.substr(i + 1, close - i - 1);
      if (inside.find('{') != std::string_view::npos) return false;
      name(std::string(inside));
      i = close;
    } else if (word[i] == '}') {
      return false;
    } else {
      literal(word.substr(i, 1));
    }
  }
  return true;
}

}  // namespace

std::optional<std::vector<std::string>> placeholder_names(std::string_view word) {
  std::vector<std::string> names;
  if (!scan(
          word, [&](std::string name) { names.push_back(std::move(name)); },
          [](std::string_view) {}))
    return std::nullopt;
  return names;
}

std::string fill_placeholders(std::string_view word, const PlaceholderValue& fill) {
  std::string out;
  scan(
      word,
      [&](const std::string& name) {
        const auto value = fill(name);
        if (!value) {
          out += "{" + name + "}";
          return;
        }
        for (const char c : *value) {
          out += c;
          if (c == '{' || c == '}') out += c;
        }
      },
      [&](std::string_view text) { out += text; });
  return out;
}

std::string expand_placeholders(std::string_view word, const PlaceholderValue& fill,
                                const std::string& what) {
  std::string out;
  std::string unknown;
  const bool whole = scan(
      word,
      [&](const std::string& name) {
        const auto value = fill(name);
        if (!value && unknown.empty()) unknown = name;
        if (value) out += *value;
      },
      [&](std::string_view text) { out += text.size() == 2 ? text.substr(0, 1) : text; });
  if (!whole)
    throw Error(ErrorCode::invalid_argument,
                what + ": a lone brace in '" + std::string(word) + "'");
  if (!unknown.empty())
    throw Error(ErrorCode::invalid_argument, what + ": unknown placeholder {" + unknown + "}");
  return out;
}

}  // namespace mosb::converters::profile_internal
