#include "mosb/experiment.hpp"

#include <fcntl.h>
#include <fnmatch.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <sstream>

#include "mosb/atomic_file.hpp"
#include "mosb/command_template.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/number_text.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/internal/source_error.hpp"
#include "mosb/metadata.hpp"
#include "mosb/sha256.hpp"
#include "mosb/store.hpp"

namespace mosb {

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

constexpr std::string_view kPlanFile = "experiment.json";
constexpr std::string_view kPlanFormat = "mosb-experiment-plan";
constexpr int kVersion = 2;  // 2: cells bound to the solver binding

[[noreturn]] void refuse(const Experiment& e, const SourceLine& at, const std::string& problem) {
  throw Error(ErrorCode::invalid_argument, experiment_error(e, at, problem));
}

// An instance of the experiment with its views, as the plan sees it.
struct PlannedInstance {
  std::string name, file, digest;
  std::string benchmark;
  std::vector<View> views;
  std::vector<std::uint64_t> queries;      // per view: its query set's size
  std::vector<CellObjectives> objectives;  // per view
};

PlannedInstance planned_instance(const fs::path& path, std::string file) {
  const auto reader = GraphReader::open(path, VerifyLevel::checksums);
  PlannedInstance out;
  out.file = std::move(file);
  out.name = fs::path(out.file).stem().string();
  out.digest = reader.digest();
  out.benchmark = reader.metadata().get("benchmark").value_or(out.name);
  out.views = reader.views();
  for (const auto& v : out.views) {
    out.queries.push_back(!v.query_set.empty() &&
                                  reader.find(format::SectionKind::queries, v.query_set)
                              ? reader.queries(v.query_set).size()
                              : 0);
    CellObjectives objectives;
    for (const auto j : v.objectives) {
      objectives.names.push_back(reader.objective(j).name);
      objectives.is_float.push_back(format::is_float(reader.objective(j).type));
    }
    out.objectives.push_back(std::move(objectives));
  }
  return out;
}

// The instances of the experiment, by file name: a store's entries (a packed one through the
// store's unpacked copy) or the listed files.
std::vector<PlannedInstance> planned_instances(const Experiment& e) {
  std::vector<PlannedInstance> out;
  if (!e.store.empty()) {
    try {
      const auto store = Store::open(e.store);
      for (const auto& entry : store.manifest().entries)
        if (!entry.solutions)  // a reference is not an instance to run
          out.push_back(planned_instance(
              entry.packed ? store.unpack(entry.file) : store.directory() / entry.file,
              (store.directory() / entry.file).string()));
    } catch (const Error& err) {
      refuse(e, e.store_source, err.what());
    }
    return out;
  }
  for (const auto& path : e.instances) {
    try {
      out.push_back(planned_instance(path, path.string()));
    } catch (const Error& err) {
      refuse(e, e.store_source, err.what());
    }
  }
  return out;
}

bool matches(const std::string& pattern, const PlannedInstance& i, const View& v) {
  const auto full = i.benchmark + "/" + v.name;
  return ::fnmatch(pattern.c_str(), v.name.c_str(), 0) == 0 ||
         ::fnmatch(pattern.c_str(), i.benchmark.c_str(), 0) == 0 ||
         ::fnmatch(pattern.c_str(), i.name.c_str(), 0) == 0 ||
         ::fnmatch(pattern.c_str(), full.c_str(), 0) == 0;
}

bool valid_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && Metadata::is_valid_key(name);
}

Json cell_json(const ExperimentCell& c) {
  return {{"solver", c.solver},
          {"instance", c.instance},
          {"view", c.view},
          {"query_set", c.query_set},
          {"instance_digest", c.instance_digest},
          {"instance_file", c.instance_file},
          {"queries", c.queries},
          {"file", c.file}};
}

ExperimentCell cell_of(const Json& j) {
  ExperimentCell c;
  c.solver = j.at("solver").get<std::string>();
  c.instance = j.at("instance").get<std::string>();
  c.view = j.at("view").get<std::string>();
  c.query_set = j.at("query_set").get<std::string>();
  c.instance_digest = j.at("instance_digest").get<std::string>();
  c.instance_file = j.at("instance_file").get<std::string>();
  c.queries = j.at("queries").get<std::uint64_t>();
  c.file = j.at("file").get<std::string>();
  return c;
}

Json counts_json(const StatusCounts& counts) {
  Json j = Json::object();
  for (const auto status : kQueryStatuses) j[std::string(to_string(status))] = counts[status];
  return j;
}

void write_text_atomically(const fs::path& path, const std::string& text) {
  AtomicFile file(path);
  file.write(text);
  file.commit();
}

void write_results_manifest(const fs::path& results, std::vector<CellRecord> records) {
  std::sort(records.begin(), records.end(),
            [](const CellRecord& a, const CellRecord& b) { return a.cell.id() < b.cell.id(); });
  std::string text = Json{{"format", kResultsManifestFormat}, {"version", kVersion}}.dump() + "\n";
  for (const auto& r : records) {
    Json j = cell_json(r.cell);
    j["sha256"] = r.sha256;
    j["executable_sha256"] = r.executable_sha256;
    j["solver_binding"] = r.solver_binding;
    j["limits"] = r.limits;
    j["counts"] = counts_json(r.counts);
    text += j.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
  }
  write_text_atomically(results / kManifestName, text);
}

Json plan_json(const ExperimentPlan& plan) {
  Json solvers = Json::array();
  for (std::size_t s = 0; s < plan.experiment.solvers.size(); ++s)
    solvers.push_back({{"name", plan.experiment.solvers[s].name},
                       {"binding", plan.solvers[s].binding},
                       {"executable_sha256", plan.executable_sha256[s]}});
  Json cells = Json::array();
  for (const auto& c : plan.cells) cells.push_back(cell_json(c));
  std::error_code ec;
  const auto file = fs::absolute(plan.experiment.file, ec).lexically_normal().string();
  return {{"format", kPlanFormat},
          {"version", kVersion},
          {"name", plan.experiment.name},
          {"file", file},
          {"arguments", plan.experiment.command_line},
          {"limits", plan.experiment.limits.text},
          {"solvers", solvers},
          {"cells", cells}};
}

Json read_json_file(const fs::path& path) {
  try {
    return Json::parse(read_whole_file(path));
  } catch (const Json::exception& e) {
    throw Error(ErrorCode::invalid_argument, path.string() + ": not a JSON document: " + e.what());
  }
}

// The one reader of RESULTS/experiment.json: nullopt when there is none, unless it is `required`
// (then ErrorCode::not_found, "no experiment here").
std::optional<Json> read_plan_file(const fs::path& results, bool required) {
  std::error_code ec;
  if (fs::exists(results / kPlanFile, ec)) return read_json_file(results / kPlanFile);
  if (!required) return std::nullopt;
  throw Error(ErrorCode::not_found,
              results.string() + ": no experiment here (no " + std::string(kPlanFile) + ")");
}

// f(cell) for every cell the plan records; a malformed plan names the file.
template <class F>
void for_each_planned_cell(const Json& plan, const fs::path& results, F&& f) {
  try {
    for (const auto& c : plan.at("cells")) f(c);
  } catch (const Json::exception& err) {
    throw Error(ErrorCode::invalid_argument, (results / kPlanFile).string() + ": " + err.what());
  }
}

}  // namespace

std::string experiment_error(const Experiment& e, const SourceLine& at,
                             const std::string& problem) {
  return source_error(e.file, at.line, at.column, at.key, problem);
}

void set_solver_executable(Experiment& e, const std::string& name, const std::string& path) {
  bool found = false;
  for (auto& solver : e.solvers)
    if (solver.name == name || solver.name.starts_with(name + "-eps")) {
      solver.spec.executable = path;
      found = true;
    }
  if (found) return;
  std::string names;
  for (const auto& solver : e.solvers) names += (names.empty() ? "" : ", ") + solver.name;
  throw Error(ErrorCode::invalid_argument,
              "executable for solver '" + name + "': the experiment's solvers are " + names);
}

void restrict_benchmarks(Experiment& e, const std::vector<std::string>& patterns,
                         const std::string& source) {
  e.benchmarks = patterns;
  e.benchmark_sources.assign(patterns.size(), SourceLine{0, source});
  e.restricted = true;
}

namespace {

// The limits' text with its time=...s token replaced (or put first): the text a rerun compares.
void replace_time(ExperimentLimits& limits, double seconds) {
  std::string token = "time=" + shortest_text(seconds) + "s", text;
  std::istringstream words(limits.text);
  for (std::string word; words >> word;)
    if (!word.starts_with("time=")) text += " " + word;
  limits.text = token + text;
  limits.process.wall_seconds = seconds;
}

}  // namespace

void set_time_limit(Experiment& e, double seconds) {
  replace_time(e.limits, seconds);
  for (auto& b : e.benchmark_limits) replace_time(b.limits, seconds);
}

// `text` with each ${NAME} replaced by the environment variable NAME; throws mosb::Error naming
// the first variable that is not set (or empty), or a ${ without its }.
std::string expand_variables(const std::string& text) {
  std::string out;
  std::size_t at = 0;
  for (std::size_t start; (start = text.find("${", at)) != std::string::npos;) {
    const auto end = text.find('}', start);
    if (end == std::string::npos) throw Error(ErrorCode::invalid_argument, "'${' without its '}'");
    const auto name = text.substr(start + 2, end - start - 2);
    const char* value = std::getenv(name.c_str());
    if (name.empty() || value == nullptr || *value == '\0')
      throw Error(ErrorCode::invalid_argument,
                  "executable " + text + ": the environment variable " + name + " is not set");
    out += text.substr(at, start - at) + value;
    at = end + 1;
  }
  return out + text.substr(at);
}

ExperimentPlan plan_experiment(const Experiment& experiment, const SolverResolver& resolver) {
  ExperimentPlan plan;
  plan.experiment = experiment;
  const auto& e = plan.experiment;
  plan.resolver = resolver;
  if (e.solvers.empty()) refuse(e, {}, "no [[solver]]");
  // A machine's paths from its environment: one experiment file for every machine.
  for (auto& solver : plan.experiment.solvers) try {
      solver.spec.executable = expand_variables(solver.spec.executable);
    } catch (const Error& err) {
      refuse(e, solver.source, "solver '" + solver.name + "': " + err.what());
    }
  std::set<std::string> names;
  for (const auto& solver : e.solvers) {
    if (!valid_name(solver.name))
      refuse(e, solver.source, "solver name '" + solver.name + "' is not from [A-Za-z0-9_.+-]");
    if (!names.insert(solver.name).second)
      refuse(e, solver.source, "solver '" + solver.name + "' is defined twice");
    try {
      plan.solvers.push_back(resolver.check(solver.spec));
      plan.executable_sha256.push_back(sha256_file(plan.solvers.back().executable));
    } catch (const Error& err) {
      refuse(e, solver.source, "solver '" + solver.name + "': " + err.what());
    }
  }
  for (const auto& name : e.reference_solvers)
    if (!names.contains(name))
      refuse(e, e.reference_source, "'" + name + "' is none of the [[solver]] names");
  const auto instances = planned_instances(e);
  for (std::size_t b = 0; b < e.benchmarks.size(); ++b) {
    const bool any = std::any_of(instances.begin(), instances.end(), [&](const PlannedInstance& i) {
      return std::any_of(i.views.begin(), i.views.end(),
                         [&](const View& v) { return matches(e.benchmarks[b], i, v); });
    });
    if (!any)
      refuse(e, e.benchmark_sources[b],
             "'" + e.benchmarks[b] + "' matches no view or benchmark of " +
                 (e.store.empty() ? std::string("the instances") : e.store.string()));
  }
  std::vector<ExperimentCell> cells;  // instance-major, for the solvers to repeat
  std::vector<std::pair<std::size_t, std::size_t>> cell_views;  // (instance, view) per cell
  for (std::size_t n = 0; n < instances.size(); ++n) {
    const auto& i = instances[n];
    for (std::size_t k = 0; k < i.views.size(); ++k) {
      const auto& v = i.views[k];
      if (!e.benchmarks.empty() &&
          std::none_of(e.benchmarks.begin(), e.benchmarks.end(),
                       [&](const std::string& p) { return matches(p, i, v); }))
        continue;
      if (i.queries[k] == 0)
        refuse(e, {}, i.file + ": view " + v.name + " names no query set with queries");
      cells.push_back({"", i.name, v.name, v.query_set, i.digest, i.file, i.queries[k], ""});
      cell_views.emplace_back(n, k);
    }
  }
  if (cells.empty()) refuse(e, {}, "no instance view to run");
  for (const auto& solver : e.solvers) {
    const auto runs = [&](std::size_t c, const std::string& pattern) {
      const auto& i = instances[cell_views[c].first];
      return matches(pattern, i, i.views[cell_views[c].second]);
    };
    for (std::size_t b = 0; b < solver.benchmarks.size() && !e.restricted; ++b) {
      bool any = false;
      for (std::size_t c = 0; c < cells.size() && !any; ++c) any = runs(c, solver.benchmarks[b]);
      if (!any)
        refuse(e, solver.benchmark_sources[b],
               "'" + solver.benchmarks[b] + "' matches no cell of the experiment");
    }
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (!solver.benchmarks.empty() &&
          std::none_of(solver.benchmarks.begin(), solver.benchmarks.end(),
                       [&](const std::string& p) { return runs(c, p); }))
        continue;
      // What only the cell's objectives show (a float cost for an integer solver) is refused
      // now, before any cell runs, not when this one's turn comes.
      if (plan.resolver.check_cell) try {
          const auto& i = instances[cell_views[c].first];
          plan.resolver.check_cell(solver.spec, i.objectives[cell_views[c].second]);
        } catch (const Error& err) {
          refuse(e, solver.source,
                 "solver '" + solver.name + "', cell " + cells[c].instance + "/" + cells[c].view +
                     ": " + err.what());
        }
      auto cell = cells[c];
      cell.solver = solver.name;
      cell.file = "cells/" + solver.name + "/" + cell.instance + "." + cell.view + ".sol";
      plan.cells.push_back(std::move(cell));
    }
  }
  for (std::size_t k = 0; k < e.benchmark_limits.size() && !e.restricted; ++k) {
    const auto& limits = e.benchmark_limits[k];
    for (std::size_t p = 0; p < limits.benchmarks.size(); ++p) {
      bool any = false;
      for (std::size_t c = 0; c < cells.size() && !any; ++c) {
        const auto& i = instances[cell_views[c].first];
        any = matches(limits.benchmarks[p], i, i.views[cell_views[c].second]);
      }
      if (!any)
        refuse(e, limits.benchmark_sources[p],
               "'" + limits.benchmarks[p] + "' matches no cell of the experiment");
    }
  }
  // Each cell's limits: those of the first [[benchmark_limits]] that matches it.
  for (auto& cell : plan.cells) {
    const auto at = std::find_if(cells.begin(), cells.end(), [&](const ExperimentCell& x) {
      return x.instance_file == cell.instance_file && x.view == cell.view;
    });
    const auto& i = instances[cell_views[static_cast<std::size_t>(at - cells.begin())].first];
    const auto& v = i.views[cell_views[static_cast<std::size_t>(at - cells.begin())].second];
    for (std::size_t k = 0; k < e.benchmark_limits.size() && cell.limits == 0; ++k)
      for (const auto& pattern : e.benchmark_limits[k].benchmarks)
        if (matches(pattern, i, v)) cell.limits = k + 1;
  }
  if (e.restricted)
    for (const auto& solver : e.solvers)
      if (std::none_of(plan.cells.begin(), plan.cells.end(),
                       [&](const ExperimentCell& c) { return c.solver == solver.name; }))
        plan.notes.push_back("solver '" + solver.name +
                             "' runs no cell: its benchmarks match none of those run");
  std::set<std::string> files;
  for (const auto& c : plan.cells)
    if (!files.insert(c.file).second)
      refuse(e, {}, "two cells write " + c.file + " (two instances of one file name)");
  return plan;
}

const ExperimentLimits& cell_limits(const ExperimentPlan& plan, const ExperimentCell& cell) {
  return cell.limits == 0 ? plan.experiment.limits
                          : plan.experiment.benchmark_limits.at(cell.limits - 1).limits;
}

ProcessLimits largest_cell_limits(const ExperimentPlan& plan) {
  ProcessLimits largest = plan.experiment.limits.process;
  bool unlimited_memory = largest.memory_bytes == 0;
  for (const auto& cell : plan.cells) {
    const auto& p = cell_limits(plan, cell).process;
    largest.wall_seconds = std::max(largest.wall_seconds, p.wall_seconds);
    largest.grace_seconds = std::max(largest.grace_seconds, p.grace_seconds);
    largest.memory_bytes = std::max(largest.memory_bytes, p.memory_bytes);
    unlimited_memory = unlimited_memory || p.memory_bytes == 0;
  }
  if (unlimited_memory) largest.memory_bytes = 0;
  return largest;
}

std::string_view to_string(CellState state) {
  return kCellStateNames.name(state);
}

std::vector<CellRecord> read_results_manifest(const fs::path& results) {
  const auto path = results / kManifestName;
  std::error_code ec;
  if (!fs::exists(path, ec)) return {};
  const auto text = read_whole_file(path);
  std::vector<CellRecord> out;
  std::size_t line_number = 0, start = 0;
  while (start < text.size()) {
    auto end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const auto line = text.substr(start, end - start);
    start = end + 1;
    ++line_number;
    try {
      const auto j = Json::parse(line);
      if (line_number == 1) {
        if (j.at("format") != kResultsManifestFormat || j.at("version") != kVersion)
          throw Error("not a results MANIFEST of this version");
        continue;
      }
      CellRecord r;
      r.cell = cell_of(j);
      r.sha256 = j.at("sha256").get<std::string>();
      r.executable_sha256 = j.at("executable_sha256").get<std::string>();
      r.solver_binding = j.at("solver_binding").get<std::string>();
      r.limits = j.at("limits").get<std::string>();
      for (const auto status : kQueryStatuses)
        r.counts[status] = j.at("counts").at(std::string(to_string(status))).get<std::uint64_t>();
      out.push_back(std::move(r));
    } catch (const std::exception& err) {
      throw Error(ErrorCode::invalid_argument,
                  path.string() + ":" + std::to_string(line_number) + ": " + err.what());
    }
  }
  if (line_number == 0) throw Error(ErrorCode::invalid_argument, path.string() + ": empty");
  return out;
}

namespace {

// The state of one cell from the files alone.
CellStatus cell_status(const ExperimentCell& cell, const fs::path& results,
                       const std::vector<CellRecord>& records, bool lock_held) {
  CellStatus s;
  s.cell = cell;
  const auto record = std::find_if(records.begin(), records.end(),
                                   [&](const CellRecord& r) { return r.cell.file == cell.file; });
  std::error_code ec;
  if (record != records.end()) {
    if (!fs::exists(results / cell.file, ec)) {
      s.state = CellState::damaged;
      s.detail = cell.file + " is listed but absent";
    } else if (sha256_file(results / cell.file) != record->sha256) {
      s.state = CellState::damaged;
      s.detail = cell.file + " is not the listed bytes (SHA-256)";
    } else {
      s.counts = record->counts;
      s.state = record->counts[QueryStatus::failed] > 0 ? CellState::failed : CellState::done;
    }
    return s;
  }
  const auto journal = journal_path((results / cell.file).string());
  if (fs::exists(journal, ec)) {
    s.state = lock_held ? CellState::running : CellState::stopped;
    s.journaled = journaled_queries(journal);
  }
  return s;
}

// results/.lock, held (flock) by the one `experiment run` writing the directory.
class ResultsLock {
 public:
  explicit ResultsLock(const fs::path& results) {
    const auto path = results / ".lock";
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0)
      throw Error(ErrorCode::io, path.string() + ": cannot open: " + std::strerror(errno));
    held_ = ::flock(fd_, LOCK_EX | LOCK_NB) == 0;
  }
  ~ResultsLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  ResultsLock(const ResultsLock&) = delete;
  ResultsLock& operator=(const ResultsLock&) = delete;
  bool held() const { return held_; }

 private:
  int fd_ = -1;
  bool held_ = false;
};

// True when another process holds results/.lock (a running experiment).
bool lock_is_held(const fs::path& results) {
  std::error_code ec;
  if (!fs::exists(results / ".lock", ec)) return false;
  try {
    return !ResultsLock(results).held();
  } catch (const Error&) {
    return false;
  }
}

}  // namespace

std::vector<CellStatus> experiment_status(const fs::path& results) {
  const auto plan = *read_plan_file(results, true);
  const auto records = read_results_manifest(results);
  const bool held = lock_is_held(results);
  std::vector<CellStatus> out;
  for_each_planned_cell(plan, results, [&](const Json& c) {
    out.push_back(cell_status(cell_of(c), results, records, held));
  });
  return out;
}

RecordedRun recorded_run(const fs::path& results) {
  const auto found = read_plan_file(results, false);
  if (!found) return {};
  const auto& plan = *found;
  RecordedRun run;
  if (const auto file = plan.find("file"); file != plan.end() && file->is_string())
    run.file = file->get<std::string>();
  if (const auto args = plan.find("arguments"); args != plan.end() && args->is_array())
    for (const auto& a : *args)
      if (a.is_string()) run.arguments.push_back(a.get<std::string>());
  const auto text = [](const Json& object, const char* key) {
    const auto it = object.find(key);
    return it != object.end() && it->is_string() ? it->get<std::string>() : std::string();
  };
  run.name = text(plan, "name");
  run.limits = text(plan, "limits");
  if (const auto solvers = plan.find("solvers"); solvers != plan.end() && solvers->is_array())
    for (const auto& s : *solvers)
      if (s.is_object())
        run.solvers.push_back({text(s, "name"), text(s, "binding"), text(s, "executable_sha256")});
  return run;
}

std::vector<fs::path> result_files(const fs::path& path, std::vector<std::string>* left_out) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return {path};
  if (!fs::exists(path / kManifestName, ec))
    throw Error(ErrorCode::not_found,
                path.string() + ": a directory without a results MANIFEST (mosb experiment run)");
  // In the plan's cell order (solver-major, as the experiment file names the solvers), not the
  // order cells finished in, so that every table and figure lists the solvers as the experiment
  // does, and the same results give the same report whatever --jobs was.
  auto records = read_results_manifest(path);
  std::map<std::string, std::size_t> position;
  if (const auto plan = read_plan_file(path, false))
    for_each_planned_cell(*plan, path, [&](const Json& c) {
      position.emplace(c.at("file").get<std::string>(), position.size());
    });
  const auto rank = [&](const CellRecord& r) {
    const auto at = position.find(r.cell.file);
    return at == position.end() ? position.size() : at->second;
  };
  std::stable_sort(records.begin(), records.end(),
                   [&](const CellRecord& a, const CellRecord& b) { return rank(a) < rank(b); });
  std::vector<fs::path> out;
  for (const auto& r : records) {
    // A cell the last run's plan no longer has (its solver or benchmark removed from the file)
    // is not part of the experiment: left out, and said.
    if (!position.empty() && !position.contains(r.cell.file)) {
      if (left_out) left_out->push_back(r.cell.id());
      continue;
    }
    out.push_back(path / r.cell.file);
  }
  return out;
}

std::vector<fs::path> result_instances(const fs::path& results) {
  std::vector<fs::path> out;
  const auto plan =
      *read_plan_file(results, true);  // a range-for over a temporary's member dangles
  for_each_planned_cell(plan, results, [&](const Json& c) {
    const fs::path file = c.at("instance_file").get<std::string>();
    if (std::find(out.begin(), out.end(), file) == out.end()) out.push_back(file);
  });
  return out;
}

std::map<std::string, std::set<std::string>> result_views(const fs::path& results) {
  std::map<std::string, std::set<std::string>> out;
  const auto plan = *read_plan_file(results, true);
  for_each_planned_cell(plan, results, [&](const Json& c) {
    out[c.at("instance_digest").get<std::string>()].insert(c.at("view").get<std::string>());
  });
  return out;
}

std::vector<fs::path> reference_files(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return {path};
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(path))
    if (entry.path().extension() == ".sol" && entry.is_regular_file()) out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  if (out.empty()) throw Error(ErrorCode::not_found, path.string() + ": no .sol file");
  return out;
}

ReferenceFiles reference_files_for(const fs::path& source, const std::set<std::string>& digests) {
  std::error_code ec;
  if (!fs::exists(source / std::string(kManifestName), ec)) return {reference_files(source), {}};
  auto found = Store::open(source).references(digests);
  return {std::move(found.files), std::move(found.missing)};
}

namespace {

// Refuses, naming every cell, what a rerun must not continue: a done cell whose solver
// executable, command or limits are not the plan's, a listed cell whose file is not the listed
// bytes.
void check_finished_cells(const ExperimentPlan& plan, const fs::path& results,
                          const std::vector<CellRecord>& records) {
  std::string refused;
  for (std::size_t c = 0; c < plan.cells.size(); ++c) {
    const auto& cell = plan.cells[c];
    const auto r = std::find_if(records.begin(), records.end(),
                                [&](const CellRecord& x) { return x.cell.file == cell.file; });
    if (r == records.end()) continue;
    const auto s = static_cast<std::size_t>(
        std::find_if(plan.experiment.solvers.begin(), plan.experiment.solvers.end(),
                     [&](const ExperimentSolver& x) { return x.name == cell.solver; }) -
        plan.experiment.solvers.begin());
    std::string why;
    if (r->executable_sha256 != plan.executable_sha256[s])
      why = "the solver's executable changed";
    else if (r->solver_binding != plan.solvers[s].binding)
      why = "the solver's command changed (" + r->solver_binding + ", now " +
            plan.solvers[s].binding + ")";
    else if (r->limits != cell_limits(plan, cell).text)
      why = "the limits changed (" + r->limits + ", now " + cell_limits(plan, cell).text + ")";
    else if (r->cell.instance_digest != cell.instance_digest)
      why = "the instance changed";
    else if (cell_status(cell, results, records, false).state == CellState::damaged)
      why = "its file is not the listed one";
    if (!why.empty()) refused += (refused.empty() ? "" : "; ") + cell.id() + ": " + why;
  }
  if (!refused.empty())
    throw Error(ErrorCode::invalid_argument,
                results.string() +
                    ": finished cells that this run would not reproduce: " + refused +
                    " (remove their files and MANIFEST records, or use another results "
                    "directory)");
}

// Creates results/ when it is not there; takes it when it is an experiment's results directory
// (its plan, or nothing but the lock of a run killed before it wrote one). Anything else is
// refused before anything is created in it: a link, a file, a directory of the user's files.
void claim_results_directory(const fs::path& results) {
  std::error_code ec;
  const auto status = fs::symlink_status(results, ec);
  if (fs::is_symlink(status))
    throw Error(ErrorCode::invalid_argument,
                results.string() + ": a symbolic link; give the results directory itself");
  if (fs::exists(status)) {
    if (!fs::is_directory(status))
      throw Error(ErrorCode::invalid_argument, results.string() + ": not a directory");
    for (const auto& entry : fs::directory_iterator(results)) {
      const auto name = entry.path().filename().string();
      if (name != ".lock" && !fs::exists(results / kPlanFile, ec))
        throw Error(ErrorCode::invalid_argument,
                    results.string() + ": not empty and not an experiment's results directory");
    }
  }
  fs::create_directories(results, ec);
  if (ec) throw Error(ErrorCode::io, results.string() + ": cannot create: " + ec.message());
}

// What a run and a merge do first, holding results/'s `lock`: refuse when another writes it, read
// results/MANIFEST and check the plan's finished cells against it.
std::vector<CellRecord> begin_writing(const ExperimentPlan& plan, const fs::path& results,
                                      const ResultsLock& lock) {
  if (!lock.held())
    throw Error(ErrorCode::invalid_argument,
                results.string() + ": another `mosb experiment run` is writing it");
  auto records = read_results_manifest(results);
  check_finished_cells(plan, results, records);
  return records;
}

// results/cells/SOLVER, created; a link on the way (planted to write elsewhere) is refused.
void make_cell_directory(const fs::path& results, const ExperimentCell& cell) {
  auto directory = results;
  for (const auto& part : fs::path(cell.file).parent_path()) {
    directory /= part;
    std::error_code ec;
    const auto status = fs::symlink_status(directory, ec);
    if (fs::is_symlink(status) || (fs::exists(status) && !fs::is_directory(status)))
      throw Error(ErrorCode::invalid_argument,
                  directory.string() + ": not a directory of the results (a link or a file)");
    if (!fs::exists(status) && !fs::create_directory(directory, ec) && ec)
      throw Error(ErrorCode::io, directory.string() + ": cannot create: " + ec.message());
  }
}

// Records the plan; refuses a directory of another experiment.
void record_plan(const ExperimentPlan& plan, const fs::path& results) {
  if (const auto recorded = read_plan_file(results, false);
      recorded && (recorded->value("format", "") != kPlanFormat ||
                   recorded->value("name", "") != plan.experiment.name))
    throw Error(ErrorCode::invalid_argument,
                results.string() + " holds the results of experiment '" +
                    recorded->value("name", "?") + "', not '" + plan.experiment.name + "'");
  write_text_atomically(results / kPlanFile, plan_json(plan).dump(2) + "\n");
}

}  // namespace

ExperimentResult run_experiment(const ExperimentPlan& plan, const fs::path& results,
                                const ExperimentOptions& options, const std::atomic<bool>& stop) {
  std::error_code ec;
  claim_results_directory(results);
  const ResultsLock lock(results);
  auto records = begin_writing(plan, results, lock);
  record_plan(plan, results);

  ExperimentResult result;
  ExperimentProgress progress;
  progress.cells_total = plan.cells.size();
  for (const auto& c : plan.cells) progress.queries_total += c.queries;
  std::vector<char> done(plan.cells.size(), 0);
  for (std::size_t c = 0; c < plan.cells.size(); ++c) {
    const auto r = std::find_if(records.begin(), records.end(), [&](const CellRecord& x) {
      return x.cell.file == plan.cells[c].file;
    });
    if (r == records.end()) continue;
    done[c] = 1;
    ++progress.cells_done;
    progress.queries_done += plan.cells[c].queries;
    progress.counts += r->counts;
  }
  result.cells = plan.cells.size();
  result.skipped = progress.cells_done;
  const auto started = std::chrono::steady_clock::now();
  std::optional<Store> store;
  if (!plan.experiment.store.empty()) store = Store::open(plan.experiment.store);
  // Each instance is opened (and a packed entry's copy checked) once per run, not once per cell:
  // its cells share the reader, whose mapping stays as long as the run.
  std::map<std::string, std::pair<fs::path, GraphReader>> opened;
  for (std::size_t c = 0; c < plan.cells.size() && !stop.load(); ++c) {
    if (done[c]) continue;
    const auto& cell = plan.cells[c];
    const auto s = static_cast<std::size_t>(
        std::find_if(plan.experiment.solvers.begin(), plan.experiment.solvers.end(),
                     [&](const ExperimentSolver& x) { return x.name == cell.solver; }) -
        plan.experiment.solvers.begin());
    auto it = opened.find(cell.instance_file);
    if (it == opened.end()) {
      // A packed store entry runs on the store's unpacked copy; the solver maps that file.
      const auto file = fs::path(cell.instance_file);
      const auto* entry = store ? store->manifest().find(file.filename().string()) : nullptr;
      auto path = entry != nullptr && entry->packed ? store->unpack(entry->file) : file;
      auto reader = open_run_instance(path.string());
      it = opened.emplace(cell.instance_file, std::pair{std::move(path), std::move(reader)}).first;
    }
    const auto& [instance_path, instance] = it->second;
    if (instance.digest() != cell.instance_digest)
      throw Error(ErrorCode::invalid_argument,
                  cell.id() + ": " + instance_path.string() + " is no longer the planned instance");
    make_cell_directory(results, cell);
    RunConfig config;
    config.instance = &instance;
    config.instance_path = instance_path.string();
    config.choice = {cell.view, {}, cell.query_set};
    config.limits = cell_limits(plan, cell).process;
    plan.resolver.configure(config, plan.experiment.solvers[s].spec);
    config.jobs = options.jobs;
    config.measurement = options.measurement;
    config.seal = options.seal;
    config.resume = true;
    config.output = (results / cell.file).string();
    config.sha256_file = [](const std::string& path) { return sha256_file(path); };
    progress.cell = cell.id();
    const auto before = progress;
    RunCallbacks callbacks;
    callbacks.progress = [&](const RunProgress& p) {
      auto now = before;
      now.queries_done += p.done;
      now.queries_done_here += p.done_here;
      now.counts += p.counts;
      now.elapsed_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      if (options.progress) options.progress(now);
    };
    callbacks.failed = [&](const QueryRecord& r, const Query& q) {
      if (options.failed) options.failed(cell, r, q);
    };
    const auto run = run_solver(config, callbacks, stop);
    if (run.interrupted) {
      result.interrupted = true;
      break;
    }
    records.push_back({cell, sha256_file(results / cell.file), plan.executable_sha256[s],
                       plan.solvers[s].binding, cell_limits(plan, cell).text, run.counts});
    write_results_manifest(results, records);
    ++result.ran;
    for (const auto& [reason, queries] : run.failures) result.failures[reason] += queries;
    result.resumed += run.from_journal > 0;
    result.queries_from_journal += run.from_journal;
    ++progress.cells_done;
    progress.queries_done = before.queries_done + cell.queries;
    progress.queries_done_here = before.queries_done_here + run.ran;
    progress.counts += run.counts;
    progress.elapsed_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (options.progress) options.progress(progress);
  }
  if (stop.load()) result.interrupted = true;
  for (const auto& r : records) result.counts += r.counts;
  return result;
}

}  // namespace mosb

namespace mosb {

std::vector<std::vector<std::size_t>> experiment_tasks(const ExperimentPlan& plan,
                                                       std::uint64_t queries_per_task) {
  if (queries_per_task == 0)
    throw Error(ErrorCode::invalid_argument, {setting("queries_per_task"), " 0: give at least 1"});
  std::vector<std::vector<std::size_t>> tasks;
  std::uint64_t in_task = 0;
  for (std::size_t c = 0; c < plan.cells.size(); ++c) {
    const auto queries = plan.cells[c].queries;
    if (tasks.empty() || in_task + queries > queries_per_task) {
      if (tasks.empty() || !tasks.back().empty()) tasks.emplace_back();
      in_task = 0;
    }
    tasks.back().push_back(c);
    in_task += queries;
  }
  return tasks;
}

ExperimentPlan task_plan(const ExperimentPlan& plan,
                         const std::vector<std::vector<std::size_t>>& tasks, std::uint64_t index) {
  if (index < 1 || index > tasks.size())
    throw Error(ErrorCode::invalid_argument, "task " + std::to_string(index) + " of " +
                                                 std::to_string(tasks.size()) + ": no such task");
  ExperimentPlan out = plan;
  out.cells.clear();
  for (const auto c : tasks[index - 1]) out.cells.push_back(plan.cells[c]);
  return out;
}

std::uint64_t queries_of(const ExperimentPlan& plan, const std::vector<std::size_t>& cells) {
  std::uint64_t queries = 0;
  for (const auto c : cells) queries += plan.cells.at(c).queries;
  return queries;
}

std::vector<std::vector<std::size_t>> plan_experiment_array(SlurmRun& run,
                                                            const ExperimentPlan& plan,
                                                            const std::string& file,
                                                            std::uint64_t queries_per_task) {
  auto tasks = experiment_tasks(plan, queries_per_task);
  if (tasks.empty())
    throw Error(ErrorCode::invalid_argument, file + ": the experiment has no cell");
  run.kind = kExperimentKind;
  run.instance = file;
  run.queries = run.largest_shard = 0;
  for (const auto& cells : tasks) {
    const auto queries = queries_of(plan, cells);
    run.queries += queries;
    run.largest_shard = std::max(run.largest_shard, queries);
  }
  run.shards = tasks.size();
  const auto largest = largest_cell_limits(plan);  // what the array's tasks request
  run.time_limit_seconds = largest.wall_seconds;
  run.grace_seconds = largest.grace_seconds;
  run.memory_limit_bytes = largest.memory_bytes;
  const std::string count = std::to_string(run.shards);
  run.task_comment =
      "# mosb experiment run --slurm (spec/EXPERIMENT.md section 4): array task i "
      "runs task i of " +
      count + "\n# of the experiment's cells (" + std::to_string(run.queries) +
      " queries in all) into task-i/ here.\n# Merge and resubmit: mosb "
      "experiment run " +
      file + " -o RESULTS --slurm " + run.directory + " --resume --submit\n";
  run.task_command = {"experiment", "run"};
  run.task_words = {"--task", "{task}/" + count, "-o", run.directory + "/task-{task}"};
  return tasks;
}

std::vector<std::vector<std::size_t>> experiment_array_tasks(const SlurmRun& run,
                                                             const ExperimentPlan& plan,
                                                             const std::string& file) {
  const auto json = run.directory + "/run.json";
  if (file != run.instance)
    throw Error(ErrorCode::invalid_argument, json + ": the job array of " + run.instance);
  // The tasks' size, as the array's tasks are given it (a number of decimal digits).
  const auto k = std::find(run.run_arguments.begin(), run.run_arguments.end(),
                           std::string("--queries-per-task"));
  std::uint64_t queries_per_task = 0;
  const auto parsed = [&](const std::string& text) {
    const auto [end, error] =
        std::from_chars(text.data(), text.data() + text.size(), queries_per_task);
    return error == std::errc{} && end == text.data() + text.size();
  };
  if (k == run.run_arguments.end() || k + 1 == run.run_arguments.end() || !parsed(*(k + 1)))
    throw Error(ErrorCode::invalid_argument, json + ": its task arguments give no task size");
  auto tasks = experiment_tasks(plan, queries_per_task);
  if (tasks.size() != run.shards)
    throw Error(ErrorCode::invalid_argument, file + ": its cells no longer make the " +
                                                 std::to_string(run.shards) + " tasks of " +
                                                 run.directory + " (the experiment changed)");
  return tasks;
}

fs::path experiment_task_directory(const SlurmRun& run, std::uint64_t task) {
  return fs::path(run.directory) / ("task-" + std::to_string(task));
}

SlurmStatus experiment_array_status(const SlurmRun& run, const ExperimentPlan& plan,
                                    const std::vector<std::vector<std::size_t>>& tasks) {
  return slurm_status(run, [&](std::uint64_t i) {
    const auto t = task_files(task_plan(plan, tasks, i), experiment_task_directory(run, i));
    ShardState s;
    s.index = i;
    s.queries = queries_of(plan, tasks.at(i - 1));
    s.file = t.state;
    s.recorded = t.queries_done;
    s.counts = t.counts;
    s.problem = t.problem;
    return s;
  });
}

TaskFiles task_files(const ExperimentPlan& task, const fs::path& directory) {
  TaskFiles t;
  std::error_code ec;
  if (!fs::exists(directory, ec)) return t;
  std::vector<CellRecord> records;
  try {
    records = read_results_manifest(directory);
  } catch (const Error& e) {
    t.state = ShardFile::damaged;
    t.problem = e.what();
    return t;
  }
  bool started = false;
  for (const auto& cell : task.cells) {
    const auto s = cell_status(cell, directory, records, false);
    if (s.state == CellState::damaged) {
      t.state = ShardFile::damaged;
      t.problem = cell.id() + ": " + s.detail;
      return t;
    }
    if (s.state == CellState::done || s.state == CellState::failed) {
      ++t.cells_done;
      t.queries_done += cell.queries;
      t.counts += s.counts;
    } else {
      t.queries_done += s.journaled;
    }
    started = started || s.state != CellState::missing;
  }
  t.state = t.cells_done == task.cells.size() ? ShardFile::done
            : started                         ? ShardFile::partial
                                              : ShardFile::missing;
  return t;
}

namespace {

// The part's records of the plan's cells that `listed` does not hold, each checked as a rerun
// checks a finished cell (check_finished_cells): throws naming every refused cell.
std::vector<std::pair<fs::path, CellRecord>> records_to_merge(const ExperimentPlan& plan,
                                                              const std::vector<CellRecord>& listed,
                                                              const std::vector<fs::path>& parts) {
  std::vector<std::pair<fs::path, CellRecord>> out;
  std::set<std::string> taken;
  for (const auto& r : listed) taken.insert(r.cell.file);
  for (const auto& part : parts) {
    std::error_code ec;
    if (!fs::exists(part / kManifestName, ec)) continue;
    const auto records = read_results_manifest(part);
    ExperimentPlan mine = plan;
    mine.cells.clear();
    for (const auto& r : records) {
      const auto in_plan =
          std::find_if(plan.cells.begin(), plan.cells.end(),
                       [&](const ExperimentCell& c) { return c.file == r.cell.file; });
      if (in_plan == plan.cells.end() || taken.contains(r.cell.file)) continue;
      mine.cells.push_back(*in_plan);
      out.emplace_back(part, r);
      taken.insert(r.cell.file);
    }
    check_finished_cells(mine, part, records);
  }
  return out;
}

}  // namespace

std::uint64_t merge_experiment_results(const ExperimentPlan& plan, const fs::path& results,
                                       const std::vector<fs::path>& parts) {
  claim_results_directory(results);
  const ResultsLock lock(results);
  auto records = begin_writing(plan, results, lock);
  const auto merged = records_to_merge(plan, records, parts);
  record_plan(plan, results);
  for (const auto& [part, record] : merged) {
    const auto target = results / record.cell.file;
    make_cell_directory(results, record.cell);
    const auto bytes = read_whole_file(part / record.cell.file);
    if (sha256_hex(std::as_bytes(std::span(bytes.data(), bytes.size()))) != record.sha256)
      throw Error(ErrorCode::invalid_argument,
                  (part / record.cell.file).string() + ": not the bytes its MANIFEST lists");
    write_text_atomically(target, bytes);
    records.push_back(record);
    write_results_manifest(results, records);  // after each cell, as run_experiment does
  }
  return merged.size();
}

}  // namespace mosb
