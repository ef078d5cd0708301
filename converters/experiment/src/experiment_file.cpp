#include "mosb/converters/experiment_file.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <map>
#include <set>

#include "mosb/converters/solver_output.hpp"
#include "mosb/error.hpp"
#include "mosb/eval.hpp"
#include "mosb/internal/number_text.hpp"
#include "mosb/internal/read_file.hpp"

namespace mosb::converters {

namespace {

// toml++'s description of a syntax error may span lines: each line break (and the indentation
// after it) becomes "; ", so that the error stays one line.
std::string one_line(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n' && text[i] != '\r') {
      out += text[i];
      continue;
    }
    while (i + 1 < text.size() && (text[i + 1] == '\n' || text[i + 1] == '\r' ||
                                   text[i + 1] == ' ' || text[i + 1] == '\t'))
      ++i;
    if (!out.empty() && i + 1 < text.size()) out += "; ";
  }
  return out;
}

// Reads one table's keys, each once, refusing any key it was not asked for.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string prefix, const Experiment& e)
      : table_(table), prefix_(std::move(prefix)), e_(e) {}

  [[noreturn]] void fail(const toml::node& at, const std::string& key,
                         const std::string& problem) const {
    throw Error(ErrorCode::invalid_argument, experiment_error(e_, where(at, key), problem));
  }
  SourceLine where(const toml::node& at, const std::string& key) const {
    return {static_cast<std::size_t>(at.source().begin.line), prefix_ + key};
  }
  SourceLine where(const std::string& key) const {
    const auto* node = table_.get(key);
    return where(node != nullptr ? *node : static_cast<const toml::node&>(table_), key);
  }

  const toml::node* get(const std::string& key) {
    known_.insert(key);
    return table_.get(key);
  }
  // A string, number or boolean as text: strings as written, numbers in their shortest form,
  // booleans true/false.
  std::string text_of(const toml::node& node) const {
    if (const auto* v = node.as_string()) return v->get();
    if (const auto* v = node.as_integer()) return std::to_string(v->get());
    if (const auto* v = node.as_floating_point()) return shortest_text(v->get());
    if (const auto* v = node.as_boolean()) return v->get() ? "true" : "false";
    return "?";
  }
  std::optional<std::string> text(const std::string& key) {
    const auto* node = get(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_string()) fail(*node, key, "must be a string");
    return node->value<std::string>();
  }
  std::string required_text(const std::string& key) {
    auto value = text(key);
    if (!value || value->empty()) fail(table_, key, "is required (a non-empty string)");
    return *value;
  }
  // An array of strings, with each element's line.
  std::vector<std::pair<std::string, SourceLine>> texts(const std::string& key) {
    std::vector<std::pair<std::string, SourceLine>> out;
    const auto* node = get(key);
    if (node == nullptr) return out;
    const auto* array = node->as_array();
    if (array == nullptr) fail(*node, key, "must be an array of strings");
    for (const auto& element : *array) {
      if (!element.is_string()) fail(element, key, "must be an array of strings");
      out.emplace_back(*element.value<std::string>(), where(element, key));
    }
    return out;
  }
  const toml::table* table(const std::string& key) {
    const auto* node = get(key);
    if (node == nullptr) return nullptr;
    if (!node->is_table()) fail(*node, key, "must be a table");
    return node->as_table();
  }
  // Call last: a key nobody asked for is a mistake (a typo), never ignored.
  void refuse_unknown() const {
    for (const auto& [key, node] : table_)
      if (!known_.contains(std::string(key.str())))
        fail(node, std::string(key.str()), "unknown key");
  }

 private:
  const toml::table& table_;
  std::string prefix_;
  const Experiment& e_;
  std::set<std::string> known_;
};

// The keys of a limits table, each replacing the same key of `limits` (the experiment's, for a
// [[benchmark_limits]] entry); `given` keeps each key's canonical text, so that the limits' text
// is the same whichever table a value came from.
void read_limit_keys(TableReader& t, ExperimentLimits& limits,
                     std::map<std::string, std::string>& given) {
  // A duration: a number of seconds, or text as parse_duration reads it.
  const auto duration = [&](const std::string& key, double& out) {
    const auto* node = t.get(key);
    if (node == nullptr) return;
    std::optional<double> seconds;
    if (node->is_number())
      seconds = parse_duration(shortest_text(*node->value<double>()));
    else if (node->is_string())
      seconds = parse_duration(*node->value<std::string>());
    else
      t.fail(*node, key, "must be a number of seconds or a duration text");
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
      bytes = parse_memory_size(*node->value<std::string>());
    else if (!node->is_integer())
      t.fail(*node, key, "must be a number of bytes or a size text");
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
void read_limits(TableReader& root, Experiment& e) {
  std::map<std::string, std::string> given;
  if (const auto* limits = root.table("limits")) {
    TableReader t(*limits, "limits.", e);
    read_limit_keys(t, e.limits, given);
    t.refuse_unknown();
  }
  const auto* node = root.get("benchmark_limits");
  if (node == nullptr) return;
  const auto* array = node->as_array();
  if (array == nullptr || !array->is_array_of_tables())
    root.fail(*node, "benchmark_limits", "must be an array of tables ([[benchmark_limits]])");
  for (std::size_t i = 0; i < array->size(); ++i) {
    const auto& table = *array->get(i)->as_table();
    const auto prefix = "benchmark_limits[" + std::to_string(i + 1) + "].";
    TableReader t(table, prefix, e);
    BenchmarkLimits b;
    b.source = {static_cast<std::size_t>(table.source().begin.line), prefix + "benchmarks"};
    for (auto& [pattern, line] : t.texts("benchmarks")) {
      b.benchmarks.push_back(pattern);
      b.benchmark_sources.push_back(line);
    }
    if (b.benchmarks.empty()) t.fail(table, "benchmarks", "is required (an array of patterns)");
    b.limits = e.limits;
    auto own = given;
    read_limit_keys(t, b.limits, own);
    t.refuse_unknown();
    e.benchmark_limits.push_back(std::move(b));
  }
}

// A profile's options: strings, numbers and booleans, as KEY=VALUE in key order.
std::vector<std::string> read_options(TableReader& t) {
  std::vector<std::string> out;
  const auto* options = t.table("options");
  if (options == nullptr) return out;
  for (const auto& [key, node] : *options) {
    if (!node.is_string() && !node.is_integer() && !node.is_floating_point() && !node.is_boolean())
      t.fail(node, "options." + std::string(key.str()), "must be a string, number or boolean");
    out.push_back(std::string(key.str()) + "=" + t.text_of(node));
  }
  return out;
}

// `epsilon`: one ε (text or number), or an array of them, one solver per ε (a sweep).
std::vector<std::pair<std::string, SourceLine>> read_epsilons(TableReader& t) {
  std::vector<std::pair<std::string, SourceLine>> out;
  const auto* node = t.get("epsilon");
  if (node == nullptr) return {{"0", {}}};
  const auto one = [&](const toml::node& value) {
    if (!value.is_string() && !value.is_number())
      t.fail(value, "epsilon", "must be an ε (0.05 or \"0.05\") or an array of them");
    const auto text = t.text_of(value);
    try {
      parse_epsilon(text);
    } catch (const Error& err) {
      t.fail(value, "epsilon", err.what());
    }
    out.emplace_back(text, t.where(value, "epsilon"));
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
  TableReader t(table, "solver[" + std::to_string(index) + "].", e);
  ExperimentSolver s;
  s.source = {static_cast<std::size_t>(table.source().begin.line),
              "solver[" + std::to_string(index) + "]"};
  s.name = t.required_text("name");
  auto& spec = s.spec;
  spec.solver_template = t.text("template").value_or("");
  spec.profile = t.text("profile").value_or("");
  spec.executable = t.text("executable").value_or("");
  spec.options = read_options(t);
  if (const auto* scale = t.get("scale")) {
    if (!scale->is_number() || !(*scale->value<double>() > 0) ||
        !std::isfinite(*scale->value<double>()))
      t.fail(*scale, "scale", "must be a positive number (float costs × scale, rounded)");
    spec.scale = *scale->value<double>();
  }
  if (auto format = t.text("output_format")) {
    if (find_solver_output_format(*format) == nullptr)
      t.fail(*t.get("output_format"), "output_format", "'" + *format + "': no such output format");
    if (!spec.profile.empty())
      t.fail(*t.get("output_format"), "output_format", "not with a profile (the profile says it)");
    spec.output_format = *format;
  }
  const auto epsilons = read_epsilons(t);
  for (auto& [pattern, line] : t.texts("benchmarks")) {
    s.benchmarks.push_back(pattern);
    s.benchmark_sources.push_back(line);
  }
  t.refuse_unknown();
  if (spec.solver_template.empty() == spec.profile.empty())
    t.fail(table, "template", "give exactly one of template and profile");
  if (spec.profile.empty() && (!spec.executable.empty() || !spec.options.empty() || spec.scale))
    t.fail(table, "executable", "executable, options and scale go with a profile, not a template");
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
  toml::table root;
  try {
    root = toml::parse(text, display_name);
  } catch (const toml::parse_error& err) {
    throw Error(ErrorCode::invalid_argument,
                display_name + ":" + std::to_string(err.source().begin.line) + ":" +
                    std::to_string(err.source().begin.column) + ": " + one_line(err.description()));
  }
  TableReader t(root, "", e);
  e.name = t.required_text("name");
  if (auto store = t.text("store")) {
    e.store = *store;
    e.store_source = t.where("store");
  }
  for (auto& [path, line] : t.texts("instances")) e.instances.emplace_back(path);
  if (e.store.empty()) e.store_source = t.where("instances");
  for (auto& [pattern, line] : t.texts("benchmarks")) {
    e.benchmarks.push_back(pattern);
    e.benchmark_sources.push_back(line);
  }
  read_limits(t, e);
  if (const auto* node = t.get("solver")) {
    const auto* array = node->as_array();
    if (array == nullptr || !array->is_array_of_tables())
      t.fail(*node, "solver", "must be an array of tables ([[solver]])");
    for (std::size_t i = 0; i < array->size(); ++i)
      for (auto& solver : read_solver(*array->get(i)->as_table(), i + 1, e))
        e.solvers.push_back(std::move(solver));
  }
  if (const auto* reference = t.table("reference")) {
    TableReader r(*reference, "reference.", e);
    e.reference_source = r.where("solvers");
    for (auto& [name, line] : r.texts("solvers")) e.reference_solvers.push_back(name);
    r.refuse_unknown();
  }
  t.refuse_unknown();
  if (e.store.empty() == e.instances.empty())
    t.fail(root, e.store.empty() ? "store" : "instances",
           "give exactly one of store and instances");
  if (e.solvers.empty()) t.fail(root, "solver", "no [[solver]]");
  return e;
}

Experiment read_experiment_file(const std::filesystem::path& path) {
  // An experiment file is a page of TOML: 16 MiB is far beyond any, and no FIFO is waited for.
  return parse_experiment(read_regular_file(path, std::uint64_t{16} << 20), path.string());
}

}  // namespace mosb::converters
