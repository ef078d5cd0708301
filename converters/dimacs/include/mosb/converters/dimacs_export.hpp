// Writes a mosb instance back out as DIMACS text (spec/families/road.md, "Export"): one .gr per
// objective (or one multi-column .gr), a .co when the instance has vertex data `coords`, one
// .queries file per query set. The same code prepares the text inputs of solver profiles
// (spec/RUN.md §10): the id base, integer costs, parallel arcs and the A*pex dummy arc are
// decided here, once, for both the arcs and the queries.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mosb/enum_names.hpp"
#include "mosb/progress.hpp"
#include "mosb/views.hpp"

namespace mosb::converters {

// How a .queries file separates a query's two ids.
enum class QueriesFormat { space, comma };
inline constexpr auto kQueriesFormatNames = enum_names<QueriesFormat>({
    {QueriesFormat::space, "space"},
    {QueriesFormat::comma, "comma"},
});

struct DimacsExportOptions {
  std::filesystem::path out_dir;  // created when missing
  ViewChoice selection;  // only these objectives and their query set (none when it names none)
  std::optional<unsigned> id_base;  // default: metadata id_base, else 1 (the DIMACS convention)
  // One .gr whose arc lines carry every objective's cost (`a u v c1 c2 ...`) instead of one .gr
  // per objective.
  bool multi_column = false;
  // With multi_column: cost columns of 0 appended up to this many (0: none). More objectives than
  // columns is refused.
  unsigned pad_columns = 0;
  QueriesFormat queries_format = QueriesFormat::space;
  // The reader of the text takes integer costs only: a float objective is refused, naming it,
  // unless scale > 0, which writes its costs × scale rounded to the nearest integer.
  bool integer_costs = false;
  double scale = 0;
  // The largest arc cost the reader can hold (a uint32 loader: 2^32 - 1); a larger one is refused.
  std::optional<std::uint64_t> max_arc_cost{};
  // The largest in- or out-degree the reader can hold (T-MDA counts them in 16 bits: 65534); a
  // vertex with more arcs in the text is refused.
  std::optional<std::uint64_t> max_degree{};
  // For a reader that keeps one arc per vertex pair: parallel arcs whose cost vectors another
  // dominates (or equals) are dropped, and each further one is subdivided through a new vertex
  // numbered after the instance's own (cost on the first half, 0 on the second), so that no
  // Pareto-optimal path is lost and query ids are unchanged.
  bool collapse_parallel_arcs = false;
  // One last arc of cost 0 between two new vertices in every .gr (A*pex's loader gives the last
  // arc of its second file a cost vector of its own; FACTS in docs/SOLVERS.md).
  bool append_dummy_arc = false;
  bool coordinates = true;  // write the .co when the instance has `coords`
};

// What an export wrote, by role.
struct DimacsExportFiles {
  std::vector<std::filesystem::path> objectives;  // one per objective, in the selection's order
  std::filesystem::path multi_column;             // with multi_column
  std::filesystem::path coordinates;              // empty when none was written
  std::vector<std::pair<std::string, std::filesystem::path>> queries;  // per query set
  std::vector<std::filesystem::path> written;  // every file, in the order written
  std::uint64_t vertex_count = 0;              // of the text (with subdivision and dummy vertices)
  std::uint64_t arc_count = 0;
  unsigned id_base = 1;
  std::vector<std::string> scaled_objectives;  // the float objectives written × scale
};

// Reads `instance` through GraphReader; writes each file atomically; `progress` gets stage
// "export", files written of the files to write. Throws mosb::Error naming the file (and the
// objective) concerned.
DimacsExportFiles export_dimacs_files(const std::filesystem::path& instance,
                                      const DimacsExportOptions& options,
                                      const Progress& progress = {});

// export_dimacs_files(...).written.
std::vector<std::filesystem::path> export_dimacs(const std::filesystem::path& instance,
                                                 const DimacsExportOptions& options,
                                                 const Progress& progress = {});

// A cost as DIMACS text that `convert dimacs` reads back to the same stored value: floats as the
// shortest round-trip form of the value widened to double, always with '.' or an exponent.
std::string format_real_cost(double value);

}  // namespace mosb::converters
