// GraphReader's views: the §7 view keys (parsed by view_keys) resolved to objective indices.
#include "mosb/graph_reader.hpp"

namespace mosb {

std::vector<std::string> GraphReader::view_names() const {
  std::vector<std::string> names;
  for (auto& keys : view_keys(metadata())) names.push_back(std::move(keys.name));
  return names;
}

std::optional<View> GraphReader::find_view(std::string_view name) const {
  for (auto& keys : view_keys(metadata())) {
    if (keys.name != name) continue;
    View view{std::move(keys.name), {}, std::move(keys.query_set)};
    for (const auto& objective : keys.objectives) {
      const auto index = find_objective(objective);
      if (!index)
        fail("view '" + view.name + "' names objective '" + objective +
             "', which is not a cost section");
      view.objectives.push_back(*index);
    }
    if (!view.query_set.empty() && !find(format::SectionKind::queries, view.query_set))
      fail("view '" + view.name + "' names query set '" + view.query_set +
           "', which is not a queries section");
    return view;
  }
  return std::nullopt;
}

View GraphReader::view(std::string_view name) const {
  if (auto found = find_view(name)) return std::move(*found);
  std::string names;
  for (const auto& n : view_names()) names += (names.empty() ? "" : ", ") + n;
  fail(ErrorCode::not_found, "no view '" + std::string(name) + "' (views: " +
                                 (names.empty() ? std::string("none") : names) + ")");
}

}  // namespace mosb
