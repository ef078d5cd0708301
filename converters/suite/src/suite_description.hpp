// spec/suite.json, parsed once: the fields the suite's builders read, each checked, so a mistake in
// the description is a one-line error naming the file and the field instead of a wrong suite.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace mosb::converters::suite_description {

using Json = nlohmann::json;

const Json& root();
// The entry of "generated" whose "generator" is `generator`.
const Json& generated(const std::string& generator);

std::string text(const Json& object, const char* key);
std::uint32_t count(const Json& object, const char* key);
std::vector<std::uint32_t> counts(const Json& object, const char* key);
std::vector<std::string> texts(const Json& object, const char* key);

// `pattern` with every "{name}" replaced by its value.
std::string expand(std::string pattern,
                   const std::vector<std::pair<std::string, std::string>>& values);

}  // namespace mosb::converters::suite_description
