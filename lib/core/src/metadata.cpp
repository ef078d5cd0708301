#include "mosb/metadata.hpp"

#include <algorithm>
#include <initializer_list>

#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/internal/utf8.hpp"

namespace mosb {

bool Metadata::is_valid_key(std::string_view key) {
  if (key.empty()) return false;
  for (char c : key)
    if (!format::is_name_char(c)) return false;
  return true;
}

void Metadata::set(std::string_view key, std::string_view value) {
  if (!is_valid_key(key)) throw Error("invalid metadata key '" + std::string(key) + "'");
  // What a reader refuses is never written (spec/FORMAT.md §7).
  if (!is_valid_utf8(value))
    throw Error("metadata value of '" + std::string(key) + "' is not valid UTF-8");
  entries_.insert_or_assign(std::string(key), std::string(value));
}

void Metadata::erase(std::string_view key) {
  if (const auto it = entries_.find(key); it != entries_.end()) entries_.erase(it);
}

std::optional<std::string> Metadata::get(std::string_view key) const {
  auto it = entries_.find(key);
  if (it == entries_.end()) return std::nullopt;
  return it->second;
}

std::string Metadata::serialize() const {
  std::string out;
  for (const auto& [key, value] : entries_) {
    out += key;
    out += '=';
    for (char c : value) {
      if (c == '\\')
        out += "\\\\";
      else if (c == '\n')
        out += "\\n";
      else
        out += c;
    }
    out += '\n';
  }
  return out;
}

Metadata Metadata::parse(std::string_view text) {
  Metadata result;
  std::string previous_key;
  std::size_t line_number = 0;
  while (!text.empty()) {
    ++line_number;
    const auto where = "metadata line " + std::to_string(line_number) + ": ";
    auto end = text.find('\n');
    if (end == std::string_view::npos) throw Error(where + "missing final newline");
    std::string_view line = text.substr(0, end);
    text.remove_prefix(end + 1);
    auto eq = line.find('=');
    if (eq == std::string_view::npos) throw Error(where + "no '=' in line");
    std::string_view key = line.substr(0, eq);
    if (!is_valid_key(key)) throw Error(where + "invalid key '" + std::string(key) + "'");
    if (line_number > 1 && key <= previous_key)
      throw Error(where + "key '" + std::string(key) + "' is not in sorted order or repeated");
    std::string value;
    for (std::size_t i = eq + 1; i < line.size(); ++i) {
      if (line[i] != '\\') {
        value += line[i];
        continue;
      }
      if (++i == line.size()) throw Error(where + "dangling '\\' at end of value");
      if (line[i] == '\\')
        value += '\\';
      else if (line[i] == 'n')
        value += '\n';
      else
        throw Error(where + "unknown escape '\\" + std::string(1, line[i]) + "'");
    }
    if (!is_valid_utf8(value))
      throw Error(where + "value of '" + std::string(key) + "' is not valid UTF-8");
    previous_key = std::string(key);
    result.entries_.emplace(previous_key, std::move(value));
  }
  return result;
}

}  // namespace mosb

namespace mosb {

std::vector<ViewKeys> view_keys(const Metadata& metadata) {
  constexpr std::string_view kPrefix = "view.", kObjectives = ".objectives", kQueries = ".queries";
  // By name: O(V log V) for V views (a file may hold tens of thousands).
  std::map<std::string, ViewKeys, std::less<>> views;
  auto entry = [&](std::string_view name) -> ViewKeys& {
    auto it = views.find(name);
    if (it == views.end())
      it = views.emplace(std::string(name), ViewKeys{std::string(name), {}, {}}).first;
    return it->second;
  };
  for (const auto& [key, value] : metadata.entries()) {
    std::string_view k = key;
    if (!k.starts_with(kPrefix)) continue;
    k.remove_prefix(kPrefix.size());
    // `view..objectives` is a view with an empty name: kept, for find_view_problem to refuse.
    if (k.ends_with(kObjectives)) {
      auto& view = entry(k.substr(0, k.size() - kObjectives.size()));
      for (std::string_view rest = value; !value.empty();) {
        const auto comma = rest.find(',');
        view.objectives.emplace_back(rest.substr(0, comma));
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
      }
    } else if (k.ends_with(kQueries)) {
      entry(k.substr(0, k.size() - kQueries.size())).query_set = value;
    }
  }
  std::vector<ViewKeys> sorted;
  sorted.reserve(views.size());
  for (auto& [name, view] : views) sorted.push_back(std::move(view));
  return sorted;
}

std::optional<std::string> find_view_problem(const Metadata& metadata,
                                             const std::vector<std::string>& objective_names,
                                             const std::vector<std::string>& query_set_names) {
  auto contains = [](const std::vector<std::string>& names, std::string_view name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  for (const auto& view : view_keys(metadata)) {
    const std::string key = "view." + view.name;
    const bool has_objectives = metadata.get(key + ".objectives").has_value();
    if (view.name.empty())
      return "metadata key '" + key + (has_objectives ? ".objectives" : ".queries") +
             "' names a view with an empty name";
    // A view is an objective list first (FORMAT.md §7): a query set alone selects no costs.
    if (!has_objectives)
      return "metadata key '" + key + ".queries' names a view without objectives (no '" + key +
             ".objectives')";
    if (view.objectives.empty()) return "metadata key '" + key + ".objectives' lists no objective";
    for (const auto& name : view.objectives)
      if (!contains(objective_names, name))
        return "metadata key '" + key + ".objectives' names objective '" + name +
               "', which is not a cost section";
    if (metadata.get(key + ".queries") && !contains(query_set_names, view.query_set))
      return "metadata key '" + key + ".queries' names query set '" + view.query_set +
             "', which is not a queries section";
  }
  return std::nullopt;
}

}  // namespace mosb

namespace mosb {

namespace {
// A key's defined value set, from spec/FORMAT.md §7 and spec/QUERIES.md.
struct ValueSet {
  std::string_view key_prefix,
      key_suffix;  // the key is prefix + (anything, for a set name) + suffix
  bool exact;      // true: the key is exactly key_prefix
  std::initializer_list<std::string_view> values;
};
const ValueSet kValueSets[] = {
    {"id_base", "", true, {"0", "1"}},
    {"family", "", true, {"road", "synthetic", "games", "robots"}},
    {"queries.", ".id_base", false, {"0", "1"}},
    {"queries.", ".allow_same", false, {"0", "1"}},
};
}  // namespace

std::optional<std::string> find_value_problem(const Metadata& metadata) {
  for (const auto& [key, value] : metadata.entries())
    for (const auto& set : kValueSets) {
      const bool applies = set.exact ? key == set.key_prefix
                                     : key.size() > set.key_prefix.size() + set.key_suffix.size() &&
                                           key.starts_with(set.key_prefix) &&
                                           key.ends_with(set.key_suffix);
      if (!applies) continue;
      if (std::find(set.values.begin(), set.values.end(), value) != set.values.end()) continue;
      std::string allowed;
      for (auto v : set.values) allowed += (allowed.empty() ? "" : ", ") + std::string(v);
      return "metadata key '" + key + "' is '" + escape_for_terminal(value) + "', not one of " +
             allowed;
    }
  return std::nullopt;
}

}  // namespace mosb
