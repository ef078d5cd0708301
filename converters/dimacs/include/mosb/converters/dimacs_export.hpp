// Writes a mosb instance back out as DIMACS text (spec/families/road.md, "Export"): one .gr per
// objective, a .co when the instance has vertex data `coords`, one .queries file per query set.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mosb/progress.hpp"
#include "mosb/views.hpp"

namespace mosb::converters {

struct DimacsExportOptions {
  std::filesystem::path out_dir;  // created when missing
  ViewChoice selection;  // only these objectives and their query set (none when it names none)
  std::optional<unsigned> id_base;  // default: metadata id_base, else 1 (the DIMACS convention)
};

// Reads `instance` through GraphReader; writes each file atomically and returns their paths in
// the order written; `progress` gets stage "export", files written of the files to write. Throws
// mosb::Error naming the file concerned.
std::vector<std::filesystem::path> export_dimacs(const std::filesystem::path& instance,
                                                 const DimacsExportOptions& options,
                                                 const Progress& progress = {});

// A cost as DIMACS text that `convert dimacs` reads back to the same stored value: floats as the
// shortest round-trip form of the value widened to double, always with '.' or an exponent.
std::string format_real_cost(double value);

}  // namespace mosb::converters
