#include "mosb/converters/objective.hpp"

#include "mosb/error.hpp"

namespace mosb::converters {

Objective parse_objective(std::string_view spec, std::string_view context) {
  const auto colon = spec.find(':');
  Objective objective{std::string(spec.substr(0, colon)),
                      colon == std::string_view::npos ? "" : std::string(spec.substr(colon + 1))};
  if (objective.name.empty())
    throw Error(ErrorCode::other, {std::string(context) + ": ", setting("objective"),
                                   " '" + std::string(spec) + "' has an empty name"});
  return objective;
}

std::string objective_list(const std::vector<Objective>& objectives) {
  std::string list;
  for (std::size_t j = 0; j < objectives.size(); ++j)
    list += (j ? "," : "") + objectives[j].name +
            (objectives[j].unit.empty() ? "" : ":" + objectives[j].unit);
  return list;
}

}  // namespace mosb::converters
