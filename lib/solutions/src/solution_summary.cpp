#include "mosb/solution_summary.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

namespace mosb {

namespace {

StatisticSummary summarize(const SolutionReader& r, Statistic statistic) {
  StatisticSummary summary{statistic};
  for (std::uint64_t q = 0; q < r.query_count(); ++q) {
    const auto value = r.statistic_as_double(statistic, q);
    if (!value) continue;
    ++summary.queries;
    summary.total += *value;
    summary.max = std::max(summary.max, *value);
  }
  return summary;
}

}  // namespace

std::string solver_name(const SolutionReader& solutions) {
  const auto& name = solutions.solver().name;
  if (!name.empty()) return name;
  return std::filesystem::path(solutions.display_name()).stem().string();
}

std::vector<std::string> front_solvers(const SolutionReader& solutions) {
  const auto info = solutions.solver();
  const auto named = info.parameters.find("solvers");
  if (info.name != "reference" || named == info.parameters.end()) return {solver_name(solutions)};
  std::vector<std::string> out;
  std::size_t i = 0;
  for (std::size_t begin = 0; begin <= named->second.size(); ++i) {
    const auto comma = std::min(named->second.find(',', begin), named->second.size());
    const auto agreed = info.parameters.find("agreed." + std::to_string(i));
    if (agreed == info.parameters.end() || !agreed->second.empty())
      out.push_back(named->second.substr(begin, comma - begin));
    begin = comma + 1;
  }
  return out;
}

std::optional<Distribution> distribution_of(std::vector<double> values,
                                            std::optional<double> runtime_shift) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  Distribution d;
  d.count = values.size();
  const std::size_t mid = values.size() / 2;
  d.median = values.size() % 2 ? values[mid] : (values[mid - 1] + values[mid]) / 2;
  d.min = values.front();
  d.max = values.back();
  d.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(d.count);
  if (runtime_shift) {
    double log_sum = 0;
    for (double v : values) log_sum += std::log(v + *runtime_shift);
    d.shifted_geometric_mean = std::exp(log_sum / static_cast<double>(d.count)) - *runtime_shift;
  }
  return d;
}

CompletedSummary summarize_completed(std::span<const SolutionReader* const> files) {
  CompletedSummary summary;
  std::vector<double> sizes, runtimes, reported, memory, expanded;
  for (const auto* r : files)
    for (std::uint64_t q = 0; q < r->query_count(); ++q) {
      const auto status = r->status(q);
      ++summary.statuses[status];
      if (!is_completed(status)) continue;
      sizes.push_back(static_cast<double>(r->front_size(q)));
      if (const auto runtime = r->runtime_seconds(q)) runtimes.push_back(*runtime);
      if (const auto runtime = r->reported_runtime_seconds(q)) reported.push_back(*runtime);
      if (const auto bytes = r->statistic_as_double(Statistic::peak_memory_bytes, q))
        memory.push_back(*bytes);
      if (const auto n = r->statistic_as_double(Statistic::expanded, q)) expanded.push_back(*n);
    }
  summary.front_size = distribution_of(std::move(sizes));
  summary.runtime = distribution_of(std::move(runtimes));
  summary.reported_runtime = distribution_of(std::move(reported));
  summary.peak_memory_bytes = distribution_of(std::move(memory));
  summary.expanded = distribution_of(std::move(expanded));
  return summary;
}

std::string runtime_caption(RuntimeSource source, std::span<const SolutionReader* const> files) {
  if (source == RuntimeSource::wall) return "wall-clock runtime (mosb's measurement)";
  std::string caption = "runtime as each solver reported it";
  std::vector<std::pair<std::string, std::string>> clocks;  // (solver, clock), each solver once
  bool one_clock = true;
  for (const auto* f : files) {
    const auto name = solver_name(*f);
    const auto clock = reported_clock(*f);
    one_clock = one_clock && (clocks.empty() || clocks.front().second == clock);
    if (std::none_of(clocks.begin(), clocks.end(), [&](const auto& c) { return c.first == name; }))
      clocks.emplace_back(name, clock);
  }
  if (clocks.empty() || (one_clock && clocks.front().second == "wall")) return caption;
  if (one_clock) return caption + " (" + clocks.front().second + " time)";
  // The most common clock (the first solver's on a tie) is "the others'".
  std::string common;
  std::size_t most = 0;
  for (const auto& entry : clocks) {
    const auto n = static_cast<std::size_t>(std::count_if(
        clocks.begin(), clocks.end(), [&](const auto& c) { return c.second == entry.second; }));
    if (n > most) most = n, common = entry.second;
  }
  std::string listed;
  for (const auto& [name, clock] : clocks)
    if (clock != common) listed += (listed.empty() ? "" : ", ") + name + " " + clock;
  return caption + " (clocks differ: " + listed + "; the others " + common + ")";
}

const std::optional<Distribution>& CompletedSummary::runtime_of(RuntimeSource source) const {
  return source == RuntimeSource::reported ? reported_runtime : runtime;
}

SolutionSummary summarize(const SolutionReader& r) {
  SolutionSummary summary;
  const SolutionReader* const files[] = {&r};
  summary.completed = summarize_completed(files);
  for (const auto statistic : kStatistics)
    if (r.has_statistic(statistic)) summary.statistics.push_back(summarize(r, statistic));
  return summary;
}

}  // namespace mosb
