// A solver profile applied to a run (spec/RUN.md §10): the text input prepared (through the
// export cache), the profile's command rendered into the run's solver template, its output read
// by the adapter it declares, and what it is recorded in the solution file. `mosb run --profile`
// calls this; the run itself is lib/run's.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mosb/converters/export_cache.hpp"
#include "mosb/converters/profile.hpp"
#include "mosb/run.hpp"

namespace mosb::converters {

struct ProfileRunRequest {
  SolverProfile profile;
  std::string executable;              // what {executable} becomes
  std::vector<std::string> options;    // --profile-option KEY=VALUE, in order
  double scale = 0;                    // --scale K (0: none)
  std::filesystem::path export_cache;  // empty: default_export_cache()
};

struct PreparedProfileRun {
  std::filesystem::path export_directory;  // empty for a solver that reads the .mosb
  bool export_reused = false;
  std::vector<std::string> words;  // the command as the first query would run it (for messages)
};

// Fills `config` (instance, instance_path, choice, limits and epsilon already set): the solver
// template, output format and adapter, success exit codes, id base, solver name and version (when
// the caller left them empty), and the profile's parameters. Throws mosb::Error (invalid_argument
// for what the user can change: an unknown option or value, too many objectives, a float
// objective for an integer solver without --scale, an ε the solver is not given).
PreparedProfileRun apply_profile(RunConfig& config, const ProfileRunRequest& request);

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
