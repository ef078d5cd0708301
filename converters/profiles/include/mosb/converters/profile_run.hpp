// A solver profile applied to a run (spec/RUN.md §10): the text input prepared (through the
// export cache), the profile's command rendered into the run's solver template, its output read
// by the adapter it declares, and what it is recorded in the solution file. The solver resolver
// (solver_resolver.hpp) calls this for `mosb run --profile` and experiments alike; the run itself
// is lib/run's.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mosb/converters/export_cache.hpp"
#include "mosb/converters/profile.hpp"
#include "mosb/run.hpp"
#include "mosb/solver_spec.hpp"

namespace mosb::converters {

// Checks a profile solver before anything runs (spec.profile, its options, its executable, an ε
// its command takes) and says its name and binding (mosb/solver_spec.hpp). Throws mosb::Error
// (invalid_argument for what the user can change).
ResolvedSolver check_profile_solver(const SolverSpec& spec);

// Fills `config` (instance, instance_path, choice and limits already set) for a profile solver:
// the text input exported (through the export cache), the solver template, output format and
// adapter, success exit codes, id base, ε, solver name and version, and the profile's parameters.
// Throws as check_profile_solver does, and for what the instance shows: too many objectives, a
// float objective for an integer solver without a scale.
void apply_profile(RunConfig& config, const SolverSpec& spec);
// apply_profile's refusals that a cell's objectives alone show, without exporting anything
// (SolverResolver::check_cell): the objective count, float costs without a scale for a solver
// that reads integers, a scale without float costs.
void check_profile_cell(const SolverSpec& spec, const CellObjectives& objectives);

// The vectors adapter (spec/RUN.md §10.4) of `profile` for a run of `objectives` objectives.
struct VectorsContext {
  unsigned id_base = 0;
  std::size_t objectives = 0;
  std::size_t padded_columns = 0;  // the text's cost columns, when padded past the objectives
  std::vector<bool> scaled;  // per objective: written × scale, the solver's values divided back
  double scale = 0;
  std::map<std::string, std::string> options;  // every option's value
};
ParsedOutput read_vectors_output(const SolverOutputFiles& files, const ProfileOutput& output,
                                 const VectorsContext& context);

}  // namespace mosb::converters
