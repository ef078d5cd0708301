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

// The two above, for lib/experiment.
SolverResolver solver_resolver();

}  // namespace mosb::converters
