#include "mosb/solution_reference.hpp"

#include <algorithm>

#include "mosb/error.hpp"
#include "mosb/eval.hpp"
#include "mosb/internal/choices.hpp"
#include "mosb/solution_summary.hpp"
#include "mosb/solver_comparison.hpp"

namespace mosb {

namespace {

// files[k] is the file of options.solvers[k], or null.
std::vector<const SolutionReader*> files_by_solver(std::span<const SolutionReader* const> files,
                                                   const ReferenceOptions& options) {
  const auto& solvers = options.solvers;
  if (solvers.empty())
    throw Error(ErrorCode::invalid_argument, "no solver named for the reference");
  for (std::size_t k = 0; k < solvers.size(); ++k) {
    if (solvers[k].empty() || solvers[k].find(',') != std::string::npos)
      throw Error(ErrorCode::invalid_argument,
                  "solver name '" + solvers[k] + "' is empty or has a ','");
    if (std::find(solvers.begin(), solvers.begin() + static_cast<std::ptrdiff_t>(k), solvers[k]) !=
        solvers.begin() + static_cast<std::ptrdiff_t>(k))
      throw Error(ErrorCode::invalid_argument, "solver '" + solvers[k] + "' is named twice");
  }
  if (options.prefer && std::find(solvers.begin(), solvers.end(), *options.prefer) == solvers.end())
    throw Error(
        ErrorCode::invalid_argument,
        {setting("prefer"), " '" + *options.prefer + "' is not one of the reference's solvers"});
  if (files.empty()) throw Error(ErrorCode::invalid_argument, "no solution file for the reference");
  std::vector<const SolutionReader*> out(solvers.size(), nullptr);
  for (const auto* file_pointer : files) {
    const auto& file = *file_pointer;
    check_same_binding(*files.front(), file);
    const auto name = solver_name(file);
    const auto at = std::find(solvers.begin(), solvers.end(), name);
    if (at == solvers.end())
      throw Error(ErrorCode::invalid_argument, file.display_name() + ": solver '" + name +
                                                   "' is not one of the reference's solvers");
    auto& slot = out[static_cast<std::size_t>(at - solvers.begin())];
    if (slot != nullptr)
      throw Error(ErrorCode::invalid_argument, file.display_name() + ": a second file of solver '" +
                                                   name + "' (the first: " + slot->display_name() +
                                                   ")");
    slot = &file;
  }
  return out;
}

QueryStatus status_of(const SolutionReader* file, std::uint64_t q) {
  return file != nullptr ? file->status(q) : QueryStatus::not_run;
}

// The status of a query no solver completed.
QueryStatus unsolved_status(const std::vector<const SolutionReader*>& files, std::uint64_t q) {
  bool timeout = false, memory = false, other = false;
  for (const auto* file : files) {
    const auto status = status_of(file, q);
    if (status == QueryStatus::not_run) continue;  // not run: says nothing of the query
    timeout |= status == QueryStatus::timeout;
    memory |= status == QueryStatus::memory_limit;
    other |= status != QueryStatus::timeout && status != QueryStatus::memory_limit;
  }
  if (other || (!timeout && !memory)) return QueryStatus::not_run;
  return timeout ? QueryStatus::timeout : QueryStatus::memory_limit;
}

}  // namespace

std::string_view to_string(ReferenceKind kind) {
  return kReferenceKindNames.name(kind);
}

std::uint64_t CrossValidation::count(ReferenceKind kind) const {
  return static_cast<std::uint64_t>(std::count_if(
      queries.begin(), queries.end(), [&](const ReferenceQuery& q) { return q.kind == kind; }));
}

CrossValidation cross_validate(std::span<const SolutionReader* const> files,
                               const ReferenceOptions& options) {
  const auto by_solver = files_by_solver(files, options);
  const std::size_t n = by_solver.size();
  // agreement[i][j] for i < j, both with a file: their fronts query by query.
  std::vector<std::vector<std::optional<FrontAgreement>>> agreement(n);
  ComparisonOptions comparison;
  comparison.tolerance = options.tolerance;
  for (std::size_t i = 0; i < n; ++i) {
    agreement[i].resize(n);
    for (std::size_t j = i + 1; j < n; ++j)
      if (by_solver[i] != nullptr && by_solver[j] != nullptr)
        agreement[i][j] = compare_fronts(*by_solver[i], *by_solver[j], comparison);
  }
  CrossValidation out;
  out.solvers = options.solvers;
  const auto queries = files.front()->query_count();
  for (std::uint64_t q = 0; q < queries; ++q) {
    ReferenceQuery r;
    r.query = q;
    std::vector<std::size_t> completed;
    for (std::size_t k = 0; k < n; ++k)
      if (is_completed(status_of(by_solver[k], q))) completed.push_back(k);
    if (completed.empty()) {
      r.status = unsolved_status(by_solver, q);
      out.queries.push_back(std::move(r));
      continue;
    }
    const auto base = completed.front();
    r.agreed.push_back(options.solvers[base]);
    for (std::size_t c = 1; c < completed.size(); ++c) {
      const auto& a = agreement[base][completed[c]]->queries[q];
      if (a.equal) {
        r.agreed.push_back(options.solvers[completed[c]]);
      } else if (r.differing.empty()) {
        r.first = options.solvers[base];
        r.differing = options.solvers[completed[c]];
        r.first_difference = a.first_difference;
        r.difference_in_first = a.difference_in_a;
      }
    }
    const auto preferred = options.prefer ? std::find(options.solvers.begin(),
                                                      options.solvers.end(), *options.prefer) -
                                                options.solvers.begin()
                                          : -1;
    if (r.differing.empty()) {
      r.kind = completed.size() == 1 ? ReferenceKind::single : ReferenceKind::agreed;
      r.source = options.solvers[base];
    } else if (preferred >= 0 &&
               std::find(completed.begin(), completed.end(), static_cast<std::size_t>(preferred)) !=
                   completed.end()) {
      r.kind = ReferenceKind::preferred;
      r.source = *options.prefer;
      r.agreed = {*options.prefer};
    } else {
      r.kind = ReferenceKind::disagreement;
      r.agreed.clear();
    }
    r.status = r.source.empty() ? QueryStatus::not_run : status_of(by_solver[base], q);
    if (r.kind == ReferenceKind::preferred)
      r.status = status_of(by_solver[static_cast<std::size_t>(preferred)], q);
    out.queries.push_back(std::move(r));
  }
  return out;
}

std::string query_ranges(std::span<const std::uint64_t> queries) {
  std::string out;
  for (std::size_t i = 0; i < queries.size();) {
    std::size_t j = i;
    while (j + 1 < queries.size() && queries[j + 1] == queries[j] + 1) ++j;
    out += (out.empty() ? "" : ",") + std::to_string(queries[i]);
    if (j > i) out += "-" + std::to_string(queries[j]);
    i = j + 1;
  }
  return out;
}

void write_reference(std::span<const SolutionReader* const> files,
                     const CrossValidation& validation, const ReferenceOptions& options,
                     const std::filesystem::path& target) {
  const auto by_solver = files_by_solver(files, options);
  SolutionWriter writer(*files.front());
  SolverInfo info;
  info.name = "reference";
  info.epsilon = "0";
  std::string names;
  for (const auto& s : options.solvers) names += (names.empty() ? "" : ",") + s;
  info.parameters["solvers"] = names;
  if (options.prefer) info.parameters["prefer"] = *options.prefer;
  for (const auto kind : {ReferenceKind::agreed, ReferenceKind::single, ReferenceKind::disagreement,
                          ReferenceKind::preferred}) {
    std::vector<std::uint64_t> of_kind;
    for (const auto& q : validation.queries)
      if (q.kind == kind) of_kind.push_back(q.query);
    info.parameters[std::string(to_string(kind))] = query_ranges(of_kind);
  }
  for (std::size_t k = 0; k < options.solvers.size(); ++k) {
    std::vector<std::uint64_t> given;
    for (const auto& q : validation.queries)
      if (std::find(q.agreed.begin(), q.agreed.end(), options.solvers[k]) != q.agreed.end())
        given.push_back(q.query);
    info.parameters["agreed." + std::to_string(k)] = query_ranges(given);
  }
  // The paper publishes its references with the statistics of the one solver that computed them
  // (NWMOA's runtime, expansions, memory): here the first solver named, on the queries it
  // completed with the reference's status. Another solver's figures never fill a gap.
  const SolutionReader* statistics_of = by_solver.front();
  if (statistics_of) {
    info.parameters["statistics"] = options.solvers.front();
    info.machine = statistics_of->solver().machine;  // where those statistics were measured
  }
  writer.set_solver(std::move(info));
  std::vector<double> costs;
  for (const auto& q : validation.queries) {
    costs.clear();
    if (!q.source.empty()) {
      const auto at = std::find(options.solvers.begin(), options.solvers.end(), q.source);
      const auto& file = *by_solver[static_cast<std::size_t>(at - options.solvers.begin())];
      const auto begin = file.front_begin(q.query), size = file.front_size(q.query);
      for (std::uint64_t row = begin; row < begin + size; ++row)
        for (std::size_t i = 0; i < file.objective_count(); ++i)
          costs.push_back(file.value_as_double(i, row));
    }
    QueryStatistics statistics;
    if (statistics_of && is_completed(q.status) && statistics_of->status(q.query) == q.status) {
      statistics = statistics_of->statistics(q.query);
    }
    writer.set_query(q.query, q.status, costs, statistics);
  }
  writer.write(target);
}

std::vector<ReferenceGroup> reference_groups(std::span<const SolutionReader> files,
                                             const ReferenceOptions& options) {
  std::vector<ReferenceGroup> groups;
  // A named solver without a file is a typo or a missing run: refused, never an empty column.
  std::vector<std::string> present;
  for (const auto& file : files)
    if (const auto name = solver_name(file);
        std::find(present.begin(), present.end(), name) == present.end())
      present.push_back(name);
  for (const auto& name : options.solvers)
    if (std::find(present.begin(), present.end(), name) == present.end())
      throw Error(ErrorCode::invalid_argument, "solver '" + name +
                                                   "' has no file among the inputs " +
                                                   choices_text(name, present, "their solvers"));
  for (std::size_t f = 0; f < files.size(); ++f) {
    const auto name = solver_name(files[f]);
    if (std::find(options.solvers.begin(), options.solvers.end(), name) == options.solvers.end())
      continue;
    const auto& file = files[f];
    // A reference is exact: an approximate front is never cross-validated into one.
    if (const auto epsilon = file.solver().epsilon; parse_epsilon(epsilon).num != 0)
      throw Error(ErrorCode::invalid_argument,
                  file.display_name() + ": solver '" + name + "' claims epsilon " + epsilon +
                      "; a reference takes exact solvers (epsilon 0) only");
    auto group = std::find_if(groups.begin(), groups.end(), [&](const ReferenceGroup& g) {
      const auto& first = files[g.files.front()];
      return first.instance_digest() == file.instance_digest() &&
             first.view_name() == file.view_name() && first.query_set() == file.query_set();
    });
    if (group == groups.end()) {
      groups.push_back({{}, std::filesystem::path(file.display_name()).filename().string()});
      group = groups.end() - 1;
    }
    group->files.push_back(f);
  }
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (std::size_t h = 0; h < g; ++h)
      if (groups[g].name == groups[h].name)
        throw Error(ErrorCode::invalid_argument,
                    "two references would be named " + groups[g].name + ": " +
                        files[groups[h].files.front()].display_name() + " and " +
                        files[groups[g].files.front()].display_name() +
                        " are of different instances or views");
  if (groups.empty())
    throw Error(ErrorCode::invalid_argument, "no solution file of the named solvers");
  return groups;
}

void check_reference_outputs(std::span<const SolutionReader> files,
                             std::span<const ReferenceGroup> groups,
                             const std::filesystem::path& directory) {
  for (const auto& group : groups)
    for (const auto& file : files) {
      std::error_code ec;
      if (std::filesystem::equivalent(directory / group.name, file.display_name(), ec))
        throw Error(ErrorCode::invalid_argument,
                    (directory / group.name).string() + " is one of the inputs (" +
                        file.display_name() + "): write the references into another directory");
    }
}

}  // namespace mosb
