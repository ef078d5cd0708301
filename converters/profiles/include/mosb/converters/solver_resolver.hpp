// The solver resolver (mosb/solver_spec.hpp): the one step from a solver as a user names it (a
// command template with its output format, or a solver profile with its executable and options)
// to the solver part of lib/run's RunConfig. `mosb run`, its SLURM tasks and `mosb experiment`
// all resolve their solvers here, so a solver is checked, named and bound in one way.
#pragma once

#include "mosb/solver_spec.hpp"

namespace mosb::converters {

// SolverResolver::check: a template (template_executable, the output format in the registry of
// solver_output.hpp) or a profile (check_profile_solver). Throws mosb::Error (invalid_argument).
ResolvedSolver check_solver(const SolverSpec& spec);

// SolverResolver::configure: the template and its output format's adapter, or apply_profile.
void configure_solver(RunConfig& config, const SolverSpec& spec);

// SolverResolver::check_cell: a profile's check_profile_cell; a template takes any objectives.
void check_solver_cell(const SolverSpec& spec, const CellObjectives& objectives);

// The three above, for lib/experiment.
SolverResolver solver_resolver();

}  // namespace mosb::converters
