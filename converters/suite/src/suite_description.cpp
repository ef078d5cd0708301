#include "suite_description.hpp"

#include "mosb/converters/suite.hpp"
#include "mosb/error.hpp"

namespace mosb::converters::suite_description {

namespace {

[[noreturn]] void bad(const std::string& what) {
  throw Error("spec/suite.json (built in): " + what);
}

const Json& field(const Json& object, const char* key) {
  if (!object.is_object() || !object.contains(key)) bad("missing field '" + std::string(key) + "'");
  return object.at(key);
}

std::uint32_t as_count(const Json& value, const char* key) {
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() > 0xFFFFFFFFu)
    bad("'" + std::string(key) + "' must be an unsigned 32-bit integer");
  return value.get<std::uint32_t>();
}

}  // namespace

const Json& root() {
  static const Json description = [] {
    try {
      return Json::parse(suite_description_json());
    } catch (const Json::exception& e) {
      bad(e.what());
    }
  }();
  return description;
}

const Json& generated(const std::string& generator) {
  for (const auto& entry : field(root(), "generated"))
    if (text(entry, "generator") == generator) return entry;
  bad("no generated entry for '" + generator + "'");
}

std::string text(const Json& object, const char* key) {
  const auto& value = field(object, key);
  if (!value.is_string()) bad("'" + std::string(key) + "' must be a string");
  return value.get<std::string>();
}

std::uint32_t count(const Json& object, const char* key) {
  return as_count(field(object, key), key);
}

std::vector<std::uint32_t> counts(const Json& object, const char* key) {
  const auto& value = field(object, key);
  if (!value.is_array()) bad("'" + std::string(key) + "' must be an array");
  std::vector<std::uint32_t> out;
  for (const auto& element : value) out.push_back(as_count(element, key));
  return out;
}

std::vector<std::string> texts(const Json& object, const char* key) {
  const auto& value = field(object, key);
  if (!value.is_array()) bad("'" + std::string(key) + "' must be an array");
  std::vector<std::string> out;
  for (const auto& element : value) {
    if (!element.is_string()) bad("'" + std::string(key) + "' must hold strings");
    out.push_back(element.get<std::string>());
  }
  return out;
}

std::string expand(std::string pattern,
                   const std::vector<std::pair<std::string, std::string>>& values) {
  for (const auto& [name, value] : values) {
    const auto placeholder = "{" + name + "}";
    for (auto at = pattern.find(placeholder); at != std::string::npos;
         at = pattern.find(placeholder, at + value.size()))
      pattern.replace(at, placeholder.size(), value);
  }
  if (pattern.find('{') != std::string::npos) bad("unexpanded placeholder in '" + pattern + "'");
  return pattern;
}

}  // namespace mosb::converters::suite_description
