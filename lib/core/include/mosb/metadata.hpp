// The metadata section: sorted, unique `key=value` lines (spec/FORMAT.md §7).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace mosb {

class Metadata {
 public:
  void set(std::string_view key, std::string_view value);
  std::optional<std::string> get(std::string_view key) const;
  void erase(std::string_view key);  // nothing when absent
  const std::map<std::string, std::string, std::less<>>& entries() const { return entries_; }

  std::string serialize() const;
  // Throws mosb::Error("metadata line N: ...") on text that breaks §7.
  static Metadata parse(std::string_view text);

  // 1 or more of the name alphabet (format::is_name_char); section names add a length limit
  // (format::is_valid_section_name).
  static bool is_valid_key(std::string_view key);

 private:
  std::map<std::string, std::string, std::less<>> entries_;
};

}  // namespace mosb

#include <vector>

namespace mosb {

// The §7 `view.<view>.objectives` / `view.<view>.queries` keys of one view, as written: the one
// parser of those keys (GraphReader::view resolves the names to indices).
struct ViewKeys {
  std::string name;
  std::vector<std::string> objectives;  // empty when the view has no `objectives` key
  std::string query_set;                // empty when the view has no `queries` key
};
// Every view the metadata mentions, sorted by name.
std::vector<ViewKeys> view_keys(const Metadata& metadata);

// The first view (§7 `view.*` keys) that names a missing objective or query set, as a message;
// nullopt when every view is sound.
std::optional<std::string> find_view_problem(const Metadata& metadata,
                                             const std::vector<std::string>& objective_names,
                                             const std::vector<std::string>& query_set_names);

// The first key whose value lies outside the value set the spec defines for it, as a message;
// nullopt when every such key is sound. Keys with a defined set (spec/FORMAT.md §7,
// spec/QUERIES.md): `id_base` and `queries.<set>.id_base` in {0, 1}; `family` in {road, synthetic,
// games, robots}; `queries.<set>.allow_same` in {0, 1}. Other keys are free text (the set of
// `queries.<set>.source` values grows with the commands that write query sets).
std::optional<std::string> find_value_problem(const Metadata& metadata);

}  // namespace mosb
