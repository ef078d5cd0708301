// The name and unit a converter gives a cost column, and the one spelling of both on the command
// line and in `source.param.objectives`: `NAME[:UNIT]` (the unit is everything after the first
// ':').
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mosb::converters {

struct Objective {
  std::string name;
  std::string unit;
};

// Parses `NAME[:UNIT]`; throws mosb::Error "CONTEXT: objective 'SPEC' has an empty name" (naming
// the setting "objective").
Objective parse_objective(std::string_view spec, std::string_view context);

// `NAME` or `NAME:UNIT`, comma-separated: what `source.param.objectives` records.
std::string objective_list(const std::vector<Objective>& objectives);

}  // namespace mosb::converters
