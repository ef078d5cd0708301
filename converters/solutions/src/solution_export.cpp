#include "mosb/converters/solution_export.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "mosb/atomic_file.hpp"
#include "mosb/converters/dimacs_export.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/solution_file.hpp"

namespace mosb::converters {

namespace {

// Every status but not-run has an input form (spec/SOLUTIONS.md §7); not-run is no input at all.
bool exported(QueryStatus status) {
  return status != QueryStatus::not_run;
}

// Integer path sums are at most 2^53 (verify_payload), exact as doubles.
std::string value_text(const SolutionReader& r, std::size_t i, std::uint64_t row) {
  const double v = r.value_as_double(i, row);
  if (format::is_float(r.objective_type(i))) return format_real_cost(v);
  return std::to_string(static_cast<std::uint64_t>(v));
}

}  // namespace

std::uint64_t export_front_directory(const SolutionReader& r, const std::filesystem::path& out_dir,
                                     unsigned id_base,
                                     const std::vector<std::filesystem::path>& inputs) {
  if (auto problem = r.verify_payload()) throw Error(r.display_name() + ": " + *problem);
  const auto file_of = [&](std::uint64_t q) {
    return out_dir / (std::to_string(q + id_base) + ".txt");
  };
  for (std::uint64_t q = 0; q < r.query_count(); ++q)
    if (exported(r.status(q))) check_output_is_not_input(file_of(q), inputs);
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error)
    throw Error(ErrorCode::io,
                out_dir.string() + ": cannot create the directory: " + error.message());
  std::uint64_t files = 0;
  for (std::uint64_t q = 0; q < r.query_count(); ++q) {
    const auto status = r.status(q);
    if (!exported(status)) continue;
    // A status without a front is stated, so that importing the file gives it back (an empty
    // file alone would get --status-for-empty).
    std::string text;
    if (status != QueryStatus::solved) text = "status " + std::string(to_string(status)) + "\n";
    if (const auto code = r.count_statistic(Statistic::exit_status, q))
      text += "exit_status " + std::to_string(*code) + "\n";
    const auto begin = r.front_begin(q);
    for (std::uint64_t k = 0; k < r.front_size(q); ++k) {
      for (std::size_t i = 0; i < r.objective_count(); ++i)
        text += (i ? " " : "") + value_text(r, i, begin + k);
      text += '\n';
    }
    write_file_atomically(file_of(q), text);
    ++files;
  }
  return files;
}

std::uint64_t export_json_log(const SolutionReader& r, const GraphReader& instance,
                              const std::filesystem::path& output, unsigned id_base,
                              const std::vector<std::filesystem::path>& inputs) {
  check_output_is_not_input(output, inputs);
  r.check_bound_to(instance);
  if (auto problem = r.verify_payload()) throw Error(r.display_name() + ": " + *problem);
  const auto queries = instance.queries(r.query_set());
  using Json = nlohmann::ordered_json;
  Json log = Json::array();
  for (std::uint64_t q = 0; q < r.query_count(); ++q) {
    const auto status = r.status(q);
    if (!exported(status)) continue;
    Json record = Json::object();
    record["source"] = std::uint64_t{queries[q].start} + id_base;
    record["target"] = std::uint64_t{queries[q].goal} + id_base;
    // PPA*'s shape for what it writes (a front, or none: disconnected); a stated status for the
    // runs that gave no answer.
    if (status != QueryStatus::solved && status != QueryStatus::disconnected) {
      record["status"] = std::string(to_string(status));
      if (const auto code = r.count_statistic(Statistic::exit_status, q))
        record["exit_status"] = *code;
      log.push_back(std::move(record));
      continue;
    }
    if (const auto seconds = r.runtime_seconds(q)) record["total_runtime(ms)"] = *seconds * 1000.0;
    Json front = Json::array();
    const auto begin = r.front_begin(q);
    for (std::uint64_t k = 0; k < r.front_size(q); ++k) {
      Json cost = Json::array();
      for (std::size_t i = 0; i < r.objective_count(); ++i) {
        const double v = r.value_as_double(i, begin + k);
        if (format::is_float(r.objective_type(i)))
          cost.push_back(v);
        else
          cost.push_back(static_cast<std::uint64_t>(v));
      }
      front.push_back(Json{{"cost_until_now", std::move(cost)}});
    }
    record["finish_info"] = Json{{"solutions", std::move(front)}};
    log.push_back(std::move(record));
  }
  write_file_atomically(output, log.dump(1) + "\n");
  return log.size();
}

}  // namespace mosb::converters
