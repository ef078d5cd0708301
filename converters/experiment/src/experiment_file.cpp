#include "mosb/converters/experiment_file.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <map>
#include <set>

#include "mosb/converters/solver_output.hpp"
#include "mosb/converters/toml_table.hpp"
#include "mosb/error.hpp"
#include "mosb/eval.hpp"
#include "mosb/internal/number_text.hpp"
#include "mosb/internal/read_file.hpp"

namespace mosb::converters {

namespace {

// Where a value stands, for the plan's refusals (experiment_error): its line, column and path.
SourceLine source_of(const TomlTable& t, const toml::node& at, std::string_view key) {
  const auto where = position_of(at);
  return {where.line, t.path(key), where.column};
}
SourceLine source_of(const TomlTable& t, std::string_view key) {
  const auto* node = t.table_node().get(key);
  return source_of(t, node != nullptr ? *node : t.table_node(), key);
}

// The patterns of `key` with each one's place.
void read_patterns(TomlTable& t, std::string_view key, std::vector<std::string>& patterns,
                   std::vector<SourceLine>& sources) {
  for (auto& [pattern, at] : t.strings_at(key)) {
    patterns.push_back(std::move(pattern));
    sources.push_back({at.line, t.path(key), at.column});
  }
}

// The keys of a limits table, each replacing the same key of `limits` (the experiment's, for a
// [[benchmark_limits]] entry); `given` keeps each key's canonical text, so that the limits' text
// is the same whichever table a value came from.
void read_limit_keys(TomlTable& t, ExperimentLimits& limits,
                     std::map<std::string, std::string>& given) {
  // A duration: a number of seconds, or text as parse_duration reads it.
  const auto duration = [&](const std::string& key, double& out) {
    const auto* node = t.get(key);
    if (node == nullptr) return;
    std::optional<double> seconds;
    if (node->is_number())
      seconds = parse_duration(shortest_text(*node->value<double>()));
    else if (node->is_string())
      seconds = parse_duration(*t.string(key));
    else
      t.fail(*node, key, "expected a number of seconds or a duration text");
    if (!seconds)
      t.fail(*node, key, "'" + t.text_of(*node) + "' is not a duration (60, 60s, 500ms, 2m, 1h)");
    out = *seconds;
    given[key] = key + '=' + shortest_text(*seconds) + "s";
  };
  // A size: a number of bytes, or text as parse_memory_size reads it (the command line's grammar).
  const auto size = [&](const std::string& key, std::uint64_t& out) {
    const auto* node = t.get(key);
    if (node == nullptr) return;
    std::optional<std::uint64_t> bytes;
    if (node->is_integer() && *node->value<std::int64_t>() >= 0)
      bytes = static_cast<std::uint64_t>(*node->value<std::int64_t>());
    else if (node->is_string())
      bytes = parse_memory_size(*t.string(key));
    else if (!node->is_integer())
      t.fail(*node, key, "expected a number of bytes or a size text");
    if (!bytes)
      t.fail(*node, key, "'" + t.text_of(*node) + "' is not a size (4294967296, 512M, 16G)");
    out = *bytes;
    given[key] = key + '=' + std::to_string(*bytes) + "B";
  };
  auto& p = limits.process;
  duration("time", p.wall_seconds);
  size("memory", p.memory_bytes);
  duration("cpu", p.cpu_seconds);
  duration("grace", p.grace_seconds);
  size("output", p.output_bytes);
  limits.text.clear();
  for (const char* key : {"time", "memory", "cpu", "grace", "output"})
    if (const auto at = given.find(key); at != given.end())
      limits.text += (limits.text.empty() ? "" : " ") + at->second;
}

// `limits`, then each [[benchmark_limits]] entry: its patterns and the keys it replaces.
void read_limits(TomlTable& root, Experiment& e) {
  std::map<std::string, std::string> given;
  if (const auto* limits = root.table("limits")) {
    TomlTable t(*limits, e.file, "limits.");
    read_limit_keys(t, e.limits, given);
    t.refuse_unknown();
  }
  const auto* array = root.array_of_tables("benchmark_limits");
  if (array == nullptr) return;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const auto& table = *array->get(i)->as_table();
    const auto prefix = "benchmark_limits[" + std::to_string(i + 1) + "].";
    TomlTable t(table, e.file, prefix);
    BenchmarkLimits b;
    b.source = source_of(t, table, "benchmarks");
    read_patterns(t, "benchmarks", b.benchmarks, b.benchmark_sources);
    if (b.benchmarks.empty()) t.fail_here("benchmarks", "is missing (an array of patterns)");
    b.limits = e.limits;
    auto own = given;
    read_limit_keys(t, b.limits, own);
    t.refuse_unknown();
    e.benchmark_limits.push_back(std::move(b));
  }
}

// A profile's options: strings, numbers and booleans, as KEY=VALUE in key order.
std::vector<std::string> read_options(TomlTable& t) {
  std::vector<std::string> out;
  const auto* options = t.table("options");
  if (options == nullptr) return out;
  for (const auto& [key, node] : *options) {
    if (!node.is_string() && !node.is_integer() && !node.is_floating_point() && !node.is_boolean())
      t.fail(node, "options." + std::string(key.str()), "expected a string, number or boolean");
    out.push_back(std::string(key.str()) + "=" + t.text_of(node));
  }
  return out;
}

// `epsilon`: one ε (text or number), or an array of them, one solver per ε (a sweep).
std::vector<std::pair<std::string, SourceLine>> read_epsilons(TomlTable& t) {
  std::vector<std::pair<std::string, SourceLine>> out;
  const auto* node = t.get("epsilon");
  if (node == nullptr) return {{"0", {}}};
  const auto one = [&](const toml::node& value) {
    if (!value.is_string() && !value.is_number())
      t.fail(value, "epsilon", "expected an ε (0.05 or \"0.05\") or an array of them");
    const auto text = t.text_of(value);
    try {
      parse_epsilon(text);
    } catch (const Error& err) {
      t.fail(value, "epsilon", err.what());
    }
    out.emplace_back(text, source_of(t, value, "epsilon"));
  };
  if (const auto* array = node->as_array()) {
    if (array->empty()) t.fail(*node, "epsilon", "an empty array: give at least one ε");
    for (const auto& value : *array) one(value);
  } else {
    one(*node);
  }
  return out;
}

// One [[solver]]; several with an ε sweep, named NAME-eps<ε>, one cell per ε.
std::vector<ExperimentSolver> read_solver(const toml::table& table, std::size_t index,
                                          const Experiment& e) {
  TomlTable t(table, e.file, "solver[" + std::to_string(index) + "].");
  ExperimentSolver s;
  const auto at = position_of(table);
  s.source = {at.line, "solver[" + std::to_string(index) + "]", at.column};
  s.name = t.required_string("name", false, true);
  auto& spec = s.spec;
  spec.solver_template = t.string("template").value_or("");
  spec.profile = t.string("profile").value_or("");
  spec.executable = t.string("executable").value_or("");
  spec.options = read_options(t);
  if (const auto* scale = t.get("scale")) {
    if (!scale->is_number() || !(*scale->value<double>() > 0) ||
        !std::isfinite(*scale->value<double>()))
      t.fail(*scale, "scale", "expected a positive number (float costs × scale, rounded)");
    spec.scale = *scale->value<double>();
  }
  if (auto format = t.string("output_format")) {
    if (find_solver_output_format(*format) == nullptr)
      t.fail(*t.get("output_format"), "output_format", "'" + *format + "': no such output format");
    if (!spec.profile.empty())
      t.fail(*t.get("output_format"), "output_format", "not with a profile (the profile says it)");
    spec.output_format = *format;
  }
  const auto epsilons = read_epsilons(t);
  read_patterns(t, "benchmarks", s.benchmarks, s.benchmark_sources);
  t.refuse_unknown();
  if (spec.solver_template.empty() == spec.profile.empty())
    t.fail_here("template", "give exactly one of template and profile");
  if (spec.profile.empty() && (!spec.executable.empty() || !spec.options.empty() || spec.scale))
    t.fail_here("executable", "executable, options and scale go with a profile, not a template");
  std::vector<ExperimentSolver> out;
  for (const auto& [epsilon, line] : epsilons) {
    auto solver = s;
    solver.spec.epsilon = epsilon;
    if (epsilons.size() > 1) solver.name += "-eps" + epsilon;
    solver.spec.name = solver.name;
    out.push_back(std::move(solver));
  }
  return out;
}

}  // namespace

Experiment parse_experiment(std::string_view text, const std::string& display_name) {
  Experiment e;
  e.file = display_name;
  const auto root = parse_toml(text, display_name);
  TomlTable t(root, display_name, "");
  e.name = t.required_string("name", false, true);
  if (auto store = t.string("store")) {
    e.store = *store;
    e.store_source = source_of(t, "store");
  }
  for (auto& path : t.strings("instances")) e.instances.emplace_back(path);
  if (e.store.empty()) e.store_source = source_of(t, "instances");
  read_patterns(t, "benchmarks", e.benchmarks, e.benchmark_sources);
  read_limits(t, e);
  if (const auto* array = t.array_of_tables("solver"))
    for (std::size_t i = 0; i < array->size(); ++i)
      for (auto& solver : read_solver(*array->get(i)->as_table(), i + 1, e))
        e.solvers.push_back(std::move(solver));
  if (const auto* reference = t.table("reference")) {
    TomlTable r(*reference, display_name, "reference.");
    e.reference_source = source_of(r, "solvers");
    e.reference_solvers = r.strings("solvers");
    r.refuse_unknown();
  }
  t.refuse_unknown();
  if (e.store.empty() == e.instances.empty())
    t.fail_here(e.store.empty() ? "store" : "instances", "give exactly one of store and instances");
  if (e.solvers.empty()) t.fail_here("solver", "no [[solver]]");
  return e;
}

Experiment read_experiment_file(const std::filesystem::path& path) {
  // An experiment file is a page of TOML: 16 MiB is far beyond any, and no FIFO is waited for.
  return parse_experiment(read_regular_file(path, std::uint64_t{16} << 20), path.string());
}

}  // namespace mosb::converters
