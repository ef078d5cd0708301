#include "mosb/solution_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "mosb/file_writer.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/parallel.hpp"
#include "mosb/internal/sections_by_kind.hpp"
#include "mosb/internal/xxh3.hpp"
#include "mosb/pack.hpp"
#include "mosb/verify.hpp"
#include "mosb/version.hpp"

namespace mosb {

using format::ElementType;
using format::SectionKind;

namespace {

// The section kinds of a solution file (SOLUTIONS.md §3).
constexpr SectionKind kSolutionKinds[] = {
    SectionKind::metadata,     SectionKind::solution_status,     SectionKind::front_offsets,
    SectionKind::front_cost,   SectionKind::solution_statistics, SectionKind::path_offsets,
    SectionKind::path_vertices};

bool is_digest(std::string_view text) {
  return text.size() == 32 && std::all_of(text.begin(), text.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

// A status that carries a front (solved alone, and its front is non-empty); every other status's
// front must be empty (SOLUTIONS.md §4).
bool has_front(QueryStatus s) {
  return s == QueryStatus::solved;
}
// Which statistics a status may carry (SOLUTIONS.md §4): the search counters on a solved query
// and a disconnected one (the search ran to completion and proved it); the exit status on a failed
// one; nothing on the others.
bool statistic_allowed(QueryStatus s, Statistic statistic) {
  if (statistic == Statistic::exit_status) return s == QueryStatus::failed;
  return is_completed(s);
}

// A runtime statistic of `stats` (is_seconds(s)), or nullopt.
std::optional<double> seconds_of(const QueryStatistics& stats, Statistic s) {
  return s == Statistic::runtime_seconds ? stats.runtime_seconds : stats.reported_runtime_seconds;
}

// A counter statistic of `stats` (not is_seconds(s)), or nullopt.
std::optional<std::uint64_t> count_of(const QueryStatistics& stats, Statistic s) {
  switch (s) {
    case Statistic::expanded:
      return stats.expanded;
    case Statistic::generated:
      return stats.generated;
    case Statistic::peak_memory_bytes:
      return stats.peak_memory_bytes;
    case Statistic::exit_status:
      return stats.exit_status;
    case Statistic::runtime_seconds:
    case Statistic::reported_runtime_seconds:
      break;
  }
  return std::nullopt;
}

bool has_statistic(const QueryStatistics& stats, Statistic s) {
  return is_seconds(s) ? seconds_of(stats, s).has_value() : count_of(stats, s).has_value();
}

// The first statistic `stats` holds that `status` may not carry, or nullopt.
std::optional<Statistic> forbidden_statistic(QueryStatus status, const QueryStatistics& stats) {
  for (const auto statistic : kStatistics)
    if (has_statistic(stats, statistic) && !statistic_allowed(status, statistic)) return statistic;
  return std::nullopt;
}

// The first runtime of `stats` that is not finite and >= 0, or nullopt.
std::optional<Statistic> bad_seconds(const QueryStatistics& stats) {
  for (const auto statistic : kStatistics)
    if (const auto v = is_seconds(statistic) ? seconds_of(stats, statistic) : std::nullopt;
        v && !(std::isfinite(*v) && *v >= 0))
      return statistic;
  return std::nullopt;
}

}  // namespace

std::string_view to_string(QueryStatus status) {
  return kQueryStatusNames.name(status);
}

std::optional<QueryStatus> parse_query_status(std::string_view text) {
  return kQueryStatusNames.parse(text);
}

std::string_view to_string(Statistic s) {
  return kStatisticNames.name(s);
}

// ---- SolutionReader ----

SolutionReader SolutionReader::open(const std::filesystem::path& path) {
  SolutionReader reader;
  auto file = map_file(path);
  // A packed file (SOLUTIONS.md §1) is read from its decoded form, every checksum checked.
  if (stated_packed(file.bytes)) file = unpack_bytes(file.bytes, path.string(), 0);
  reader.attach(std::move(file), path.string(), format::FileKind::solutions);
  reader.validate();
  return reader;
}

SolutionReader SolutionReader::open(const std::filesystem::path& path,
                                    const GraphReader& instance) {
  auto reader = open(path);
  reader.check_bound_to(instance);
  return reader;
}

SolutionReader SolutionReader::open_verified(const std::filesystem::path& path) {
  auto reader = open(path);
  if (auto problem = reader.verify_payload())
    reader.fail("file is damaged: " + *problem + "; run mosb verify");
  return reader;
}

SolutionReader SolutionReader::from_memory(std::span<const std::byte> bytes,
                                           std::string display_name, std::uint64_t max_memory) {
  SolutionReader reader;
  if (stated_packed(bytes)) {
    auto image = unpack_bytes(bytes, display_name, max_memory);
    reader.attach(std::move(image), std::move(display_name), format::FileKind::solutions);
  } else {
    reader.attach_borrowed(bytes, std::move(display_name), format::FileKind::solutions);
  }
  reader.validate();
  return reader;
}

std::vector<SolutionReader> open_verified_all(std::span<const std::filesystem::path> paths,
                                              unsigned threads) {
  std::vector<std::optional<SolutionReader>> opened(paths.size());
  parallel_for(paths.size(), thread_count(threads),
               [&](std::size_t i) { opened[i] = SolutionReader::open_verified(paths[i]); });
  std::vector<SolutionReader> readers;
  readers.reserve(paths.size());
  for (auto& r : opened) readers.push_back(std::move(*r));
  return readers;
}

// After attach: the container's checks are done.
void SolutionReader::validate() {
  if (header_.version_minor < 1)
    fail("a solution file states format 1." + std::to_string(header_.version_minor) +
         ", but solution files exist since 1.1");

  for (const auto& s : sections_) {
    if (!s.kind) continue;  // a later minor's kind: ignored
    if (std::find(std::begin(kSolutionKinds), std::end(kSolutionKinds), *s.kind) ==
        std::end(kSolutionKinds))
      fail("section '" + s.name + "': a " + std::string(format::to_string(*s.kind)) +
           " section does not belong in a solution file");
    if (s.is_packed())
      fail("section '" + s.name + "': is packed; SolutionReader::open decodes a packed file");
  }
  const SectionsByKind table(sections_, display_name_);
  const auto metadata_index = table.single(SectionKind::metadata, ElementType::u8);
  status_index_ = table.single(SectionKind::solution_status, ElementType::u8);
  front_offsets_index_ = table.single(SectionKind::front_offsets, ElementType::u64);
  path_offsets_index_ = table.single(SectionKind::path_offsets, ElementType::u64);
  path_vertices_index_ = table.single(SectionKind::path_vertices, ElementType::u32);
  const auto costs = table.all(SectionKind::front_cost);
  for (auto i : costs) {
    table.expect_cost_column(sections_[i]);
    const auto type = sections_[i].type;
    if (stores_path_sums() && type != format::path_sum_type(type))
      fail("section '" + sections_[i].name + "': a front_cost column of format 1." +
           std::to_string(format::kSolutionSumsMinor) + " holds path sums (u64 or f64), not " +
           std::string(format::to_string(type)));
  }
  cost_indices_.assign(costs.begin(), costs.end());
  for (auto i : table.all(SectionKind::solution_statistics)) {
    const auto& s = sections_[i];
    const auto found = kStatisticNames.parse(s.name);
    if (!found) fail("section '" + s.name + "': is not a statistic of SOLUTIONS.md §3");
    const auto which = static_cast<std::size_t>(*found);
    table.expect_shape(s, is_seconds(*found) ? ElementType::f64 : ElementType::u64);
    statistic_indices_[which] = i;  // one at most: names are unique within a kind
  }
  if (metadata_index == SIZE_MAX) fail("no metadata section");
  if (status_index_ == SIZE_MAX) fail("no solution_status section");
  if (front_offsets_index_ == SIZE_MAX) fail("no front_offsets section");
  if (cost_indices_.empty()) fail("no front_cost section");
  if (header_.objective_count != cost_indices_.size())
    fail("header declares " + std::to_string(header_.objective_count) + " objectives, table has " +
         std::to_string(cost_indices_.size()) + " front_cost sections");
  if ((path_offsets_index_ == SIZE_MAX) != (path_vertices_index_ == SIZE_MAX))
    fail("path_offsets and path_vertices come together");

  // Row counts, and the ends of the offsets columns (O(1), like FORMAT.md §9 step 9).
  query_count_ = sections_[status_index_].entry.row_count;
  const auto& offsets_section = sections_[front_offsets_index_];
  if (offsets_section.entry.row_count != query_count_ + 1)
    fail("section '" + offsets_section.name + "' has " +
         std::to_string(offsets_section.entry.row_count) + " rows, but the query count + 1 is " +
         std::to_string(query_count_ + 1));
  const auto offsets = values<std::uint64_t>(offsets_section);
  if (offsets.front() != 0)
    fail("section '" + offsets_section.name + "': first offset " + std::to_string(offsets.front()) +
         " is not 0");
  vector_count_ = offsets.back();
  auto expect_rows = [&](const Section& s, std::uint64_t rows, const char* what) {
    if (s.entry.row_count != rows)
      fail("section '" + s.name + "' has " + std::to_string(s.entry.row_count) + " rows, but " +
           what + " is " + std::to_string(rows));
  };
  for (auto i : cost_indices_) expect_rows(sections_[i], vector_count_, "the last front offset");
  for (auto i : statistic_indices_)
    if (i != SIZE_MAX) expect_rows(sections_[i], query_count_, "the query count");
  if (has_paths()) {
    expect_rows(sections_[path_offsets_index_], vector_count_ + 1, "the last front offset + 1");
    const auto path_offsets = values<std::uint64_t>(sections_[path_offsets_index_]);
    if (path_offsets.front() != 0 ||
        path_offsets.back() != sections_[path_vertices_index_].entry.row_count)
      fail("section '" + sections_[path_offsets_index_].name +
           "' does not run from 0 to the path_vertices row count");
  }

  // The binding keys (SOLUTIONS.md §2): parsed at open, since nothing is usable without them.
  const auto& meta = sections_[metadata_index];
  try {
    metadata_ = Metadata::parse(
        std::string_view(reinterpret_cast<const char*>(meta.stored.data()), meta.stored.size()));
  } catch (const Error& e) {
    fail("section 'metadata': " + std::string(e.what()));
  }
  auto required = [&](std::string_view key) {
    auto value = metadata_.get(key);
    if (!value || value->empty()) fail("metadata has no '" + std::string(key) + "'");
    return *value;
  };
  instance_digest_ = required("solution.instance_digest");
  if (!is_digest(instance_digest_))
    fail("metadata 'solution.instance_digest' is not 32 lowercase hex digits");
  // Before 1.4 every file names a view; from 1.4 a file may be bound to its objectives alone.
  if (header_.version_minor < format::kSolutionObjectivesMinor)
    view_ = required(format::kSolutionViewKey);
  else if (const auto view = metadata_.get(format::kSolutionViewKey); view && !view->empty())
    view_ = *view;
  query_set_ = required("solution.query_set");
}

std::vector<std::size_t> SolutionReader::instance_objectives(const GraphReader& instance) const {
  std::vector<std::size_t> indices;
  if (!view_.empty()) {
    const auto view = instance.find_view(view_);
    if (!view)
      fail(ErrorCode::invalid_argument,
           "view '" + view_ + "' is not in " + instance.display_name());
    bool same = view->objectives.size() == objective_count();
    for (std::size_t i = 0; same && i < objective_count(); ++i)
      same = instance.objective(view->objectives[i]).name == objective_name(i);
    if (!same)
      fail(ErrorCode::invalid_argument, "front_cost columns differ from the objectives of view '" +
                                            view_ + "' in " + instance.display_name());
    return view->objectives;
  }
  for (std::size_t i = 0; i < objective_count(); ++i) {
    const auto found = instance.find_objective(objective_name(i));
    if (!found)
      fail(ErrorCode::invalid_argument, "front_cost column '" + objective_name(i) +
                                            "' is no objective of " + instance.display_name());
    indices.push_back(*found);
  }
  return indices;
}

void SolutionReader::check_bound_to(const GraphReader& instance) const {
  const auto digest = instance.digest();
  if (digest != instance_digest_)
    fail(ErrorCode::invalid_argument, "solutions of the instance with digest " + instance_digest_ +
                                          ", not of " + instance.display_name() + " (digest " +
                                          digest + ")");
  if (header_.vertex_count != instance.vertex_count() || header_.arc_count != instance.arc_count())
    fail(ErrorCode::invalid_argument, "header states n = " + std::to_string(header_.vertex_count) +
                                          ", m = " + std::to_string(header_.arc_count) + ", but " +
                                          instance.display_name() +
                                          " has n = " + std::to_string(instance.vertex_count()) +
                                          ", m = " + std::to_string(instance.arc_count()));
  const auto objectives = instance_objectives(instance);
  // Format 1.3 stores path sums; 1.1 and 1.2 stored the arc cost type itself.
  for (std::size_t i = 0; i < objective_count(); ++i) {
    const auto& arc = instance.objective(objectives[i]);
    if ((stores_path_sums() ? format::path_sum_type(arc.type) : arc.type) != objective_type(i))
      fail(ErrorCode::invalid_argument, "front_cost column '" + objective_name(i) + "' is " +
                                            std::string(format::to_string(objective_type(i))) +
                                            ", but objective '" + arc.name + "' of " +
                                            instance.display_name() + " is " +
                                            std::string(format::to_string(arc.type)));
  }
  const auto* queries = instance.find(SectionKind::queries, query_set_);
  if (!queries)
    fail(ErrorCode::invalid_argument,
         "query set '" + query_set_ + "' is not in " + instance.display_name());
  if (queries->entry.row_count != query_count_)
    fail(ErrorCode::invalid_argument,
         "has " + std::to_string(query_count_) + " queries, query set '" + query_set_ + "' of " +
             instance.display_name() + " has " + std::to_string(queries->entry.row_count));
}

SolverInfo SolutionReader::solver() const {
  SolverInfo info;
  info.name = metadata_.get("solution.solver.name").value_or("");
  info.version = metadata_.get("solution.solver.version").value_or("");
  info.epsilon = metadata_.get("solution.epsilon").value_or("0");
  info.machine = metadata_.get("solution.machine").value_or("");
  constexpr std::string_view kParam = "solution.solver.param.";
  for (const auto& [key, value] : metadata_.entries())
    if (key.starts_with(kParam)) info.parameters[key.substr(kParam.size())] = value;
  return info;
}

std::optional<DroppedVectors> SolutionReader::dropped_vectors() const {
  const auto vectors = metadata_.get("solution.import.dropped_vectors");
  const auto queries = metadata_.get("solution.import.dropped_queries");
  if (!vectors && !queries) return std::nullopt;
  const auto number = [&](const std::optional<std::string>& text, const char* key) {
    std::uint64_t value = 0;
    const char* end = text ? text->data() + text->size() : nullptr;
    if (!text || text->empty() || text->front() < '0' || text->front() > '9' ||
        std::from_chars(text->data(), end, value).ptr != end)
      fail(ErrorCode::invalid_argument, std::string("metadata '") + key +
                                            "' is not an unsigned decimal integer (or is missing)");
    return value;
  };
  return DroppedVectors{number(vectors, "solution.import.dropped_vectors"),
                        number(queries, "solution.import.dropped_queries")};
}

const Section& SolutionReader::objective(std::size_t i) const {
  if (i >= cost_indices_.size())
    fail(ErrorCode::invalid_argument, "objective index " + std::to_string(i) + " out of range (" +
                                          std::to_string(cost_indices_.size()) + " objectives)");
  return sections_[cost_indices_[i]];
}

std::span<const std::uint64_t> SolutionReader::front_offsets() const {
  return values<std::uint64_t>(sections_[front_offsets_index_]);
}

QueryStatus SolutionReader::status(std::uint64_t q) const {
  if (q >= query_count_)
    fail(ErrorCode::invalid_argument, "query " + std::to_string(q) + " out of range (" +
                                          std::to_string(query_count_) + " queries)");
  const auto raw = values<std::uint8_t>(sections_[status_index_])[q];
  if (raw > kLastQueryStatus)
    fail("query " + std::to_string(q) + " has status " + std::to_string(raw) +
         ", not one of SOLUTIONS.md §4");
  return static_cast<QueryStatus>(raw);
}

std::uint64_t SolutionReader::front_begin(std::uint64_t q) const {
  if (q >= query_count_)
    fail(ErrorCode::invalid_argument, "query " + std::to_string(q) + " out of range (" +
                                          std::to_string(query_count_) + " queries)");
  const auto offsets = front_offsets();
  if (offsets[q] > offsets[q + 1] || offsets[q + 1] > vector_count_)
    fail("section 'front_offsets': query " + std::to_string(q) +
         " has offsets out of order; run mosb solutions verify");
  return offsets[q];
}

std::uint64_t SolutionReader::front_size(std::uint64_t q) const {
  const auto begin = front_begin(q);
  return front_offsets()[q + 1] - begin;
}

double SolutionReader::value_as_double(std::size_t i, std::uint64_t row) const {
  return visit_column(i, [&](auto column) -> double {
    if (row >= column.size())
      fail(ErrorCode::invalid_argument, "front vector " + std::to_string(row) + " out of range");
    return static_cast<double>(column[row]);
  });
}

std::size_t SolutionReader::statistic_index(Statistic s) const {
  return statistic_indices_[static_cast<std::size_t>(s)];
}

std::optional<double> SolutionReader::seconds_statistic(Statistic s, std::uint64_t q) const {
  const auto i = statistic_index(s);
  if (i == SIZE_MAX || q >= query_count_ || !is_seconds(s)) return std::nullopt;
  const double v = values<double>(sections_[i])[q];
  if (std::isnan(v)) return std::nullopt;
  return v;
}

std::optional<double> SolutionReader::runtime_seconds(std::uint64_t q) const {
  return seconds_statistic(Statistic::runtime_seconds, q);
}

std::optional<double> SolutionReader::reported_runtime_seconds(std::uint64_t q) const {
  return seconds_statistic(Statistic::reported_runtime_seconds, q);
}

std::optional<std::uint64_t> SolutionReader::count_statistic(Statistic s, std::uint64_t q) const {
  const auto i = statistic_index(s);
  if (i == SIZE_MAX || q >= query_count_ || is_seconds(s)) return std::nullopt;
  const auto v = values<std::uint64_t>(sections_[i])[q];
  if (v == kAbsentCount) return std::nullopt;
  return v;
}

std::optional<double> SolutionReader::statistic_as_double(Statistic s, std::uint64_t q) const {
  if (is_seconds(s)) return seconds_statistic(s, q);
  if (const auto count = count_statistic(s, q)) return static_cast<double>(*count);
  return std::nullopt;
}

QueryStatistics SolutionReader::statistics(std::uint64_t q) const {
  QueryStatistics stats;
  stats.runtime_seconds = runtime_seconds(q);
  stats.expanded = count_statistic(Statistic::expanded, q);
  stats.generated = count_statistic(Statistic::generated, q);
  stats.peak_memory_bytes = count_statistic(Statistic::peak_memory_bytes, q);
  stats.exit_status = count_statistic(Statistic::exit_status, q);
  stats.reported_runtime_seconds = reported_runtime_seconds(q);
  return stats;
}

std::span<const std::uint32_t> SolutionReader::path(std::uint64_t row) const {
  if (!has_paths()) return {};
  const auto offsets = values<std::uint64_t>(sections_[path_offsets_index_]);
  const auto vertices = values<std::uint32_t>(sections_[path_vertices_index_]);
  if (row >= vector_count_)
    fail(ErrorCode::invalid_argument, "front vector " + std::to_string(row) + " out of range");
  if (offsets[row] > offsets[row + 1] || offsets[row + 1] > vertices.size())
    fail("section 'path_offsets': vector " + std::to_string(row) +
         " has offsets out of order; run mosb solutions verify");
  return vertices.subspan(offsets[row], offsets[row + 1] - offsets[row]);
}

std::optional<std::string> SolutionReader::verify_payload() const {
  for (const auto& s : sections_) {
    const std::uint64_t computed = XXH3_64bits(s.stored.data(), s.stored.size());
    if (computed != s.entry.checksum)
      return "section '" + s.name + "': [checksum] mismatch (stored " + hex64(s.entry.checksum) +
             ", computed " + hex64(computed) + ")";
  }
  if (auto problem = find_padding_problem(*this)) return problem;
  const auto statuses = values<std::uint8_t>(sections_[status_index_]);
  const auto offsets = front_offsets();
  for (std::uint64_t q = 0; q < query_count_; ++q) {
    const std::string label = "query " + std::to_string(q) + ": ";
    if (statuses[q] > kLastQueryStatus)
      return label + "[status] value " + std::to_string(statuses[q]) + " is not a status";
    if (offsets[q] > offsets[q + 1])
      return label + "[front-offsets] offsets decrease (" + std::to_string(offsets[q]) + " > " +
             std::to_string(offsets[q + 1]) + ")";
    const auto status = static_cast<QueryStatus>(statuses[q]);
    const auto size = offsets[q + 1] - offsets[q];
    if (status == QueryStatus::solved && size == 0)
      return label + "[status] solved with an empty front (a query without a path is disconnected)";
    if (!has_front(status) && size != 0)
      return label + "[status] " + std::string(to_string(status)) + " with a front of " +
             std::to_string(size) + " vectors (only solved queries carry a front)";
    if (const auto statistic = forbidden_statistic(status, statistics(q)))
      return label + "[statistics] " + std::string(to_string(status)) + " carries " +
             (*statistic == Statistic::exit_status ? "exit_status" : "statistics") +
             " (SOLUTIONS.md §4)";
    if (const auto bad = bad_seconds(statistics(q)))
      return label + "[statistics] " + std::string(to_string(*bad)) + " is not finite and >= 0";
  }
  for (std::size_t i = 0; i < objective_count(); ++i) {
    auto problem = visit_column(i, [&](auto column) -> std::optional<std::string> {
      using T = typename decltype(column)::value_type;
      if constexpr (std::is_floating_point_v<T>) {
        for (std::uint64_t row = 0; row < column.size(); ++row)
          if (!(std::isfinite(column[row]) && column[row] >= 0))
            return "section '" + objective_name(i) + "': [cost-value] front vector " +
                   std::to_string(row) + " is not finite and >= 0";
      } else if constexpr (sizeof(T) == 8) {
        // Above 2^53 a sum is no exact double, and verify, eval and export read sums as doubles.
        for (std::uint64_t row = 0; row < column.size(); ++row)
          if (static_cast<std::uint64_t>(column[row]) > kMaxIntegerSum)
            return "section '" + objective_name(i) + "': [cost-value] front vector " +
                   std::to_string(row) + " is above 2^53";
      }
      return std::nullopt;
    });
    if (problem) return problem;
  }
  if (has_paths()) {
    const auto path_offsets = values<std::uint64_t>(sections_[path_offsets_index_]);
    for (std::uint64_t row = 0; row < vector_count_; ++row)
      if (path_offsets[row] > path_offsets[row + 1])
        return "section '" + sections_[path_offsets_index_].name +
               "': [path-offsets] offsets decrease at front vector " + std::to_string(row);
    const auto vertices = values<std::uint32_t>(sections_[path_vertices_index_]);
    for (const std::uint32_t vertex : vertices)
      if (vertex >= header_.vertex_count)
        return "section '" + sections_[path_vertices_index_].name + "': [path-vertex] vertex " +
               std::to_string(vertex) + " is not below the vertex count " +
               std::to_string(header_.vertex_count);
  }
  return std::nullopt;
}

// ---- SolutionWriter ----

namespace {

// One query as set_query recorded it.
struct QueryResult {
  QueryStatus status = QueryStatus::not_run;
  std::vector<double> costs;
  QueryStatistics statistics;
  std::vector<std::vector<std::uint32_t>> paths;
};

// A statistic column for each statistic some query recorded; absent values are NaN (runtime) or
// the reserved count 2^64-1.
void add_statistic_sections(FileWriter& out, std::span<const QueryResult> results) {
  for (const auto s : kStatistics) {
    if (std::none_of(results.begin(), results.end(),
                     [s](const QueryResult& r) { return has_statistic(r.statistics, s); }))
      continue;
    if (is_seconds(s)) {
      std::vector<double> column;
      for (const auto& r : results)
        column.push_back(
            seconds_of(r.statistics, s).value_or(std::numeric_limits<double>::quiet_NaN()));
      out.add_section<double>(SectionKind::solution_statistics, to_string(s), 1,
                              std::span<const double>(column));
    } else {
      std::vector<std::uint64_t> column;
      for (const auto& r : results)
        column.push_back(count_of(r.statistics, s).value_or(kAbsentCount));
      out.add_section<std::uint64_t>(SectionKind::solution_statistics, to_string(s), 1,
                                     std::span<const std::uint64_t>(column));
    }
  }
}

void add_path_sections(FileWriter& out, std::span<const QueryResult> results) {
  std::vector<std::uint64_t> path_offsets{0};
  std::vector<std::uint32_t> vertices;
  for (const auto& r : results)
    for (const auto& path : r.paths) {
      vertices.insert(vertices.end(), path.begin(), path.end());
      path_offsets.push_back(vertices.size());
    }
  out.add_section<std::uint64_t>(SectionKind::path_offsets, "path_offsets", 1,
                                 std::span<const std::uint64_t>(path_offsets));
  out.add_section<std::uint32_t>(SectionKind::path_vertices, "path_vertices", 1,
                                 std::span<const std::uint32_t>(vertices));
}

}  // namespace

struct SolutionWriter::State {
  std::string instance_digest, view, query_set;
  std::uint64_t vertex_count = 0, arc_count = 0, query_count = 0;
  std::vector<std::string> objective_names;
  std::vector<ElementType> objective_types;
  SolverInfo solver;
  std::optional<DroppedVectors> dropped;
  std::string source_tool = std::string("mosb ") + version();
  std::vector<QueryResult> results;

  Metadata metadata() const;
  void add_front_sections(FileWriter& out) const;
};

Metadata SolutionWriter::State::metadata() const {
  Metadata meta;
  meta.set("solution.instance_digest", instance_digest);
  if (!view.empty()) meta.set(format::kSolutionViewKey, view);
  meta.set("solution.query_set", query_set);
  meta.set("solution.epsilon", solver.epsilon.empty() ? "0" : solver.epsilon);
  if (!solver.name.empty()) meta.set("solution.solver.name", solver.name);
  if (!solver.version.empty()) meta.set("solution.solver.version", solver.version);
  if (!solver.machine.empty()) meta.set("solution.machine", solver.machine);
  for (const auto& [key, value] : solver.parameters)
    meta.set("solution.solver.param." + key, value);
  if (dropped) {
    meta.set("solution.import.dropped_vectors", std::to_string(dropped->vectors));
    meta.set("solution.import.dropped_queries", std::to_string(dropped->queries));
  }
  meta.set("source.tool", source_tool);
  return meta;
}

// Statuses, front offsets and one path-sum column per objective.
void SolutionWriter::State::add_front_sections(FileWriter& out) const {
  const std::size_t d = objective_names.size();
  std::vector<std::uint8_t> statuses;
  std::vector<std::uint64_t> offsets{0};
  for (const auto& r : results) {
    statuses.push_back(static_cast<std::uint8_t>(r.status));
    offsets.push_back(offsets.back() + r.costs.size() / d);
  }
  out.add_section<std::uint8_t>(SectionKind::solution_status, "solution_status", 1,
                                std::span<const std::uint8_t>(statuses));
  out.add_section<std::uint64_t>(SectionKind::front_offsets, "front_offsets", 1,
                                 std::span<const std::uint64_t>(offsets));
  for (std::size_t i = 0; i < d; ++i) {
    format::visit_element_type(format::path_sum_type(objective_types[i]), [&](auto tag) {
      using T = typename decltype(tag)::type;
      std::vector<T> column;
      column.reserve(offsets.back());
      for (const auto& r : results)
        for (std::size_t k = i; k < r.costs.size(); k += d)
          column.push_back(static_cast<T>(r.costs[k]));
      out.add_section<T>(SectionKind::front_cost, objective_names[i], 1,
                         std::span<const T>(column));
    });
  }
}

SolutionWriter::SolutionWriter(const GraphReader& instance, std::string_view view_name,
                               std::string_view query_set)
    : SolutionWriter(instance, [&] {
        auto view = instance.view(view_name);
        if (!query_set.empty()) view.query_set = std::string(query_set);
        return view;
      }()) {}

SolutionWriter::SolutionWriter(const GraphReader& instance, const View& selection)
    : state_(std::make_unique<State>()) {
  const auto& view = selection;
  auto& st = *state_;
  st.instance_digest = instance.digest();
  st.view = view.name;
  st.query_set = view.query_set;
  if (st.query_set.empty())
    throw Error(
        ErrorCode::invalid_argument,
        instance.display_name() +
            (view.name.empty() ? std::string(": no query set given")
                               : ": view '" + view.name + "' names no query set; give one"));
  if (view.objectives.empty())
    throw Error(ErrorCode::invalid_argument, instance.display_name() + ": no objectives given");
  st.query_count = instance.queries(st.query_set).size();
  st.vertex_count = instance.vertex_count();
  st.arc_count = instance.arc_count();
  for (auto i : view.objectives) {
    st.objective_names.push_back(instance.objective(i).name);
    st.objective_types.push_back(instance.objective(i).type);
  }
  st.results.resize(st.query_count);
}

SolutionWriter::SolutionWriter(const SolutionReader& like) : state_(std::make_unique<State>()) {
  auto& st = *state_;
  st.instance_digest = like.instance_digest();
  st.view = like.view_name();
  st.query_set = like.query_set();
  st.query_count = like.query_count();
  st.vertex_count = like.header().vertex_count;
  st.arc_count = like.header().arc_count;
  for (std::size_t i = 0; i < like.objective_count(); ++i) {
    st.objective_names.push_back(like.objective_name(i));
    st.objective_types.push_back(like.objective_type(i));  // path_sum_type keeps a sum's type
  }
  st.results.resize(st.query_count);
}

SolutionWriter::~SolutionWriter() = default;

void SolutionWriter::set_solver(SolverInfo info) {
  for (const auto& [key, value] : info.parameters)
    if (!Metadata::is_valid_key(key))
      throw Error(ErrorCode::invalid_argument,
                  "solver parameter name '" + key + "' is not from [A-Za-z0-9_.+-]");
  state_->solver = std::move(info);
}

void SolutionWriter::set_dropped_vectors(std::optional<DroppedVectors> dropped) {
  state_->dropped = dropped;
}

void SolutionWriter::set_source_tool(std::string tool) {
  state_->source_tool = std::move(tool);
}

std::size_t SolutionWriter::objective_count() const {
  return state_->objective_names.size();
}
std::uint64_t SolutionWriter::query_count() const {
  return state_->query_count;
}
const std::vector<std::string>& SolutionWriter::objective_names() const {
  return state_->objective_names;
}

std::optional<std::string> SolutionWriter::cost_problem(std::size_t objective, double v) const {
  const auto type = state_->objective_types.at(objective);
  if (!std::isfinite(v) || v < 0) return "cost is negative or not finite";
  if (format::is_float(type)) return std::nullopt;  // an f64 sum holds every double
  if (v != std::floor(v))
    return "cost is not an integer (the objective's arc costs are " +
           std::string(format::to_string(type)) + ")";
  if (v > static_cast<double>(kMaxIntegerSum))
    return "path sum above 2^53, the largest integer a solution file stores exactly";
  return std::nullopt;
}

std::optional<std::string> SolutionWriter::query_problem(
    std::uint64_t q, QueryStatus status, std::span<const double> costs,
    const QueryStatistics& statistics, std::span<const std::vector<std::uint32_t>> paths) const {
  const auto& st = *state_;
  if (q >= st.query_count)
    return "is not in query set '" + st.query_set + "' (" + std::to_string(st.query_count) +
           " queries)";
  const std::size_t d = st.objective_names.size();
  if (costs.size() % d != 0)
    return std::to_string(costs.size()) + " values are not a whole number of " + std::to_string(d) +
           "-objective vectors";
  const std::size_t vectors = costs.size() / d;
  if (status == QueryStatus::solved && vectors == 0) return "solved with an empty front";
  if (!has_front(status) && vectors != 0)
    return std::string(to_string(status)) + " with a front (only solved queries carry one)";
  if (const auto statistic = forbidden_statistic(status, statistics))
    return std::string(to_string(status)) + (*statistic == Statistic::exit_status
                                                 ? " carries no exit_status"
                                                 : " carries no statistics");
  if (const auto bad = bad_seconds(statistics))
    return std::string(to_string(*bad)) + " is not finite and >= 0";
  for (auto count : {statistics.expanded, statistics.generated, statistics.peak_memory_bytes,
                     statistics.exit_status})
    if (count == kAbsentCount) return "a statistic equals the reserved value 2^64-1";
  if (!paths.empty() && paths.size() != vectors)
    return std::to_string(paths.size()) + " paths for " + std::to_string(vectors) + " vectors";
  for (const auto& path : paths)
    for (auto v : path)
      if (v >= st.vertex_count)
        return "path vertex " + std::to_string(v) + " is not below the vertex count " +
               std::to_string(st.vertex_count);
  for (std::size_t k = 0; k < costs.size(); ++k)
    if (auto problem = cost_problem(k % d, costs[k]))
      return "vector " + std::to_string(k / d) + ", objective '" + st.objective_names[k % d] +
             "': " + *problem;
  return std::nullopt;
}

void SolutionWriter::set_query(std::uint64_t q, QueryStatus status, std::span<const double> costs,
                               const QueryStatistics& statistics,
                               std::span<const std::vector<std::uint32_t>> paths) {
  if (auto problem = query_problem(q, status, costs, statistics, paths))
    throw Error(ErrorCode::invalid_argument, "query " + std::to_string(q) + ": " + *problem);
  auto& r = state_->results[q];
  r.status = status;
  r.costs.assign(costs.begin(), costs.end());
  r.statistics = statistics;
  r.paths.assign(paths.begin(), paths.end());
}

void SolutionWriter::write(const std::filesystem::path& target) const {
  const auto& st = *state_;
  const auto with_front = [](const QueryResult& r) { return !r.costs.empty(); };
  const bool any_paths = std::any_of(st.results.begin(), st.results.end(), [&](const auto& r) {
    return with_front(r) && !r.paths.empty();
  });
  const bool all_paths = std::all_of(st.results.begin(), st.results.end(), [&](const auto& r) {
    return !with_front(r) || !r.paths.empty();
  });
  if (any_paths && !all_paths)
    throw Error(ErrorCode::invalid_argument,
                target.string() + ": some fronts come with paths and some without");

  FileWriter out(target);
  out.set_file_kind(format::FileKind::solutions);
  const bool reported = std::any_of(st.results.begin(), st.results.end(), [](const auto& r) {
    return r.statistics.reported_runtime_seconds.has_value();
  });
  out.require_minor(format::solution_layout_minor(reported, !st.view.empty()));
  const auto text = st.metadata().serialize();
  out.add_section<std::uint8_t>(
      SectionKind::metadata, "metadata", 1,
      std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  st.add_front_sections(out);
  add_statistic_sections(out, st.results);
  if (any_paths) add_path_sections(out, st.results);
  out.commit(st.vertex_count, st.arc_count);
}

}  // namespace mosb
