#include "mosb/converters/profile_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "mosb/command_template.hpp"
#include "mosb/converters/solver_output.hpp"
#include "mosb/error.hpp"
#include "mosb/eval.hpp"
#include "mosb/views.hpp"
#include "placeholders.hpp"

namespace mosb::converters {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const std::string& message) {
  throw Error(ErrorCode::invalid_argument, message);
}

// Every option's value: its default, or what --profile-option gave.
std::map<std::string, std::string> option_values(const SolverProfile& p,
                                                 const std::vector<std::string>& given) {
  std::map<std::string, std::string> values;
  for (const auto& option : p.options) values[option.name] = option.default_value;
  std::map<std::string, bool> seen;
  for (const auto& text : given) {
    const auto eq = text.find('=');
    const std::string key = text.substr(0, eq);
    const auto option = std::find_if(p.options.begin(), p.options.end(),
                                     [&](const auto& o) { return o.name == key; });
    if (eq == std::string::npos || option == p.options.end()) {
      std::string names;
      for (const auto& o : p.options) names += (names.empty() ? "" : ", ") + o.name;
      refuse("option " + text + ": profile " + p.name + " has " +
             (names.empty() ? std::string("no options") : "the options " + names) + " (KEY=VALUE)");
    }
    if (seen[key]) refuse("option " + key + ": given twice");
    seen[key] = true;
    const auto value = text.substr(eq + 1);
    if (!option->values.empty() &&
        std::find(option->values.begin(), option->values.end(), value) == option->values.end()) {
      std::string allowed;
      for (const auto& v : option->values) allowed += (allowed.empty() ? "" : ", ") + v;
      refuse("option " + text + ": " + key + " is one of " + allowed);
    }
    if (value.empty() || value.find_first_of(" \t\n{}") != std::string::npos)
      refuse("option " + text + ": a value without blanks or braces");
    values[key] = value;
  }
  return values;
}

void check_objective_count(const SolverProfile& p, std::size_t d,
                           const std::map<std::string, std::string>& values) {
  const auto& in = p.input;
  if (d < in.min_objectives || (in.max_objectives > 0 && d > in.max_objectives))
    refuse("profile " + p.name + ": its solver takes " + std::to_string(in.min_objectives) +
           (in.max_objectives > 0 ? " to " + std::to_string(in.max_objectives) : " or more") +
           " objectives, the run has " + std::to_string(d));
  for (const auto& option : p.options) {
    const auto limit = option.max_objectives.find(values.at(option.name));
    if (limit != option.max_objectives.end() && d > limit->second)
      refuse("profile " + p.name + ": " + option.name + "=" + limit->first + " takes at most " +
             std::to_string(limit->second) + " objectives, the run has " + std::to_string(d) +
             " (the solver would silently drop the others)");
  }
}

// {time_limit}: above mosb's own limit, so the solver's cut-off never ends a search mosb would let
// finish (its limit is CPU time of the search; mosb's wall time of the whole process).
std::string time_limit_text(const ProfileTimeLimit& rule, const ProcessLimits& limits) {
  const double mosb = std::max(limits.wall_seconds, limits.cpu_seconds);
  double value = mosb > 0 ? mosb * rule.scale + rule.add_seconds : rule.unlimited;
  if (rule.integer) value = std::ceil(value);
  if (rule.integer || value == std::floor(value))
    return std::to_string(static_cast<std::uint64_t>(value));
  return format_real_cost(value);
}

// The one check of cost types against a profile, for a run (prepare_input) and an experiment's
// plan (check_profile_cell): float costs for a solver that reads integers need a scale (none for
// one that reads the .mosb itself), and a scale needs a float cost.
void check_cost_types(const SolverProfile& p, const SolverSpec& spec,
                      const CellObjectives& objectives) {
  bool any_float = false;
  for (std::size_t j = 0; j < objectives.names.size(); ++j) {
    if (!objectives.is_float[j]) continue;
    any_float = true;
    if (p.input.integer_costs && (p.input.form == InputForm::mosb || spec.scale <= 0)) {
      const std::string problem = "objective '" + objectives.names[j] +
                                  "' holds float costs and profile " + p.name +
                                  "'s solver reads integers only";
      if (p.input.form == InputForm::mosb) refuse(problem);
      throw Error(ErrorCode::invalid_argument,
                  {problem + ": give a scale K (", setting("scale"), ")"});
    }
  }
  if (spec.scale > 0 && p.input.form == InputForm::mosb)
    refuse("scale: profile " + p.name + "'s solver reads the .mosb itself");
  if (spec.scale > 0 && !any_float) refuse("scale: no objective of the run holds float costs");
}

struct RunInput {
  DimacsExportFiles files;
  fs::path directory;
  bool reused = false;
  std::vector<std::string> objective_names;
  std::string query_set;
};

RunInput prepare_input(const RunConfig& config, const SolverProfile& p, const SolverSpec& request,
                       bool uses_coordinates) {
  const auto& instance = *config.instance;
  const View selection = solution_selection(instance, config.choice);
  RunInput in;
  in.query_set = selection.query_set;
  CellObjectives objectives;
  for (const auto j : selection.objectives) {
    objectives.names.push_back(instance.objective(j).name);
    objectives.is_float.push_back(format::is_float(instance.objective(j).type));
  }
  try {
    check_cost_types(p, request, objectives);
  } catch (const Error& err) {
    throw err.with_context(instance.display_name() + ": ");
  }
  in.objective_names = std::move(objectives.names);
  if (p.input.form == InputForm::mosb) return in;
  DimacsExportOptions o;
  o.selection.objectives = in.objective_names;
  o.selection.queries = in.query_set;
  o.id_base = p.input.id_base;
  o.multi_column = p.input.form == InputForm::dimacs_multi_column;
  o.pad_columns = p.input.pad_columns;
  o.queries_format = p.input.queries_format.value_or(QueriesFormat::space);
  o.integer_costs = p.input.integer_costs;
  o.scale = request.scale;
  o.max_arc_cost = p.input.max_arc_cost;
  o.max_degree = p.input.max_degree;
  o.collapse_parallel_arcs = p.input.parallel_arcs == ParallelArcs::collapse;
  o.append_dummy_arc = p.input.append_dummy_arc;
  o.coordinates = uses_coordinates;
  const fs::path cache =
      request.export_cache.empty() ? default_export_cache() : fs::path(request.export_cache);
  auto cached = cached_export(cache, config.instance_path, instance.digest(), o);
  if (uses_coordinates && cached.files.coordinates.empty())
    refuse(instance.display_name() + ": profile " + p.name +
           " passes {co}, and the instance has no vertex data 'coords'");
  in.files = std::move(cached.files);
  in.directory = cached.directory;
  in.reused = cached.reused;
  return in;
}

// The run-constant placeholders' values; nullopt for the per-query ones lib/run fills.
std::optional<std::string> run_value(const std::string& name, const RunConfig& config,
                                     const SolverProfile& p, const SolverSpec& request,
                                     const RunInput& in,
                                     const std::map<std::string, std::string>& options) {
  if (name == "executable") return request.executable;
  if (name == "multi_gr") return in.files.multi_column.string();
  if (name == "co") return in.files.coordinates.string();
  if (name == "d") return std::to_string(in.objective_names.size());
  if (name == "time_limit") return time_limit_text(p.time_limit, config.limits);
  if (name == "epsilon") return config.epsilon;
  if (name == "queries")
    for (const auto& [set, path] : in.files.queries)
      if (set == in.query_set) return path.string();
  if (name.rfind("gr:", 0) == 0) {
    for (std::size_t k = 0; k < in.objective_names.size(); ++k)
      if (in.objective_names[k] == name.substr(3)) return in.files.objectives[k].string();
    refuse("profile " + p.name + ": {" + name + "}: the run has no objective '" + name.substr(3) +
           "'");
  }
  if (const auto option = options.find(name); option != options.end()) return option->second;
  return std::nullopt;
}

OutputAdapter profile_adapter(const SolverProfile& p, const VectorsContext& context) {
  if (p.output.format == "vectors")
    return [output = p.output, context](const SolverOutputFiles& files) {
      return read_vectors_output(files, output, context);
    };
  const auto* format = find_solver_output_format(p.output.format);
  if (format == nullptr) refuse("profile " + p.name + ": no output format " + p.output.format);
  // The registry's readers match a log's endpoints with the query: in the solver's id base.
  return [inner = format->adapter(), context](const SolverOutputFiles& files) {
    SolverOutputFiles shifted = files;
    shifted.query.start += context.id_base;
    shifted.query.goal += context.id_base;
    auto out = inner(shifted);
    for (std::size_t i = 0; i < out.costs.size(); ++i)
      if (context.scaled[i % context.objectives]) out.costs[i] /= context.scale;
    return out;
  };
}

// Whether the profile's command uses the placeholder `name`.
bool command_uses(const SolverProfile& p, std::string_view name) {
  for (const auto& word : split_command(p.command))
    for (const auto& used : profile_internal::placeholder_names(word).value_or(
             std::vector<std::string>{}))  // parse_profile refused a lone brace
      if (used == name) return true;
  return false;
}

// The name a profile solver is recorded under when the user gives none: the solver with each
// option's value that is not its default, and ε when it is not 0, so that two algorithms or two
// ε of one program never share a name.
std::string profile_solver_name(const SolverProfile& p,
                                const std::map<std::string, std::string>& options,
                                const std::string& epsilon) {
  std::string name = p.solver.empty() ? p.name : p.solver;
  for (const auto& option : p.options)
    if (options.at(option.name) != option.default_value) name += " " + options.at(option.name);
  if (parse_epsilon(epsilon).num != 0) name += " \u03b5=" + epsilon;
  return name;
}

// The profile, its options' values and its executable, checked as check_profile_solver says.
struct CheckedProfile {
  SolverProfile profile;
  std::map<std::string, std::string> options;
  ResolvedSolver resolved;
};

CheckedProfile checked_profile(const SolverSpec& spec) {
  CheckedProfile out;
  out.profile = load_profile(spec.profile);
  const auto& p = out.profile;
  out.options = option_values(p, spec.options);
  if (spec.executable.empty())
    refuse("profile " + p.name + ": give its solver's executable (the program it runs)");
  out.resolved.executable = resolve_executable(spec.executable);
  if (out.resolved.executable.empty() || ::access(out.resolved.executable.c_str(), X_OK) != 0)
    refuse("executable " + spec.executable + ": no such executable" +
           (spec.executable.find('/') == std::string::npos ? " in PATH" : ""));
  if (parse_epsilon(spec.epsilon).num != 0 && !command_uses(p, "epsilon"))
    refuse("epsilon " + spec.epsilon + ": profile " + p.name +
           " gives its solver no epsilon (its command has no {epsilon})");
  if (spec.scale < 0 || !std::isfinite(spec.scale)) refuse("scale: a positive number");
  out.resolved.name = profile_solver_name(p, out.options, spec.epsilon);
  auto& binding = out.resolved.binding;
  binding = "profile " + p.name + " xxh3 " + p.text_digest;
  for (const auto& [key, value] : out.options) binding += " " + key + "=" + value;
  if (spec.scale > 0) binding += " scale=" + format_real_cost(spec.scale);
  binding += " | output " + p.output.format + " | epsilon " + spec.epsilon;
  return out;
}

}  // namespace

ResolvedSolver check_profile_solver(const SolverSpec& spec) {
  return checked_profile(spec).resolved;
}

void check_profile_cell(const SolverSpec& spec, const CellObjectives& objectives) {
  const auto checked = checked_profile(spec);
  check_objective_count(checked.profile, objectives.names.size(), checked.options);
  check_cost_types(checked.profile, spec, objectives);
}

void apply_profile(RunConfig& config, const SolverSpec& spec) {
  const auto checked = checked_profile(spec);
  const auto& p = checked.profile;
  const auto& options = checked.options;
  config.epsilon = spec.epsilon;
  const auto in = prepare_input(config, p, spec, command_uses(p, "co"));
  check_objective_count(p, in.objective_names.size(), options);

  std::string command;
  const auto add = [&](const std::string& word) {
    command += (command.empty() ? "" : " ") + shell_quote(word);  // split_command reads it back
  };
  for (const auto& word : split_command(p.command)) {
    if (word == "{gr}") {
      for (const auto& path : in.files.objectives) add(path.string());
      continue;
    }
    add(profile_internal::fill_placeholders(word, [&](const std::string& name) {
      return run_value(name, config, p, spec, in, options);
    }));
  }

  VectorsContext context;
  context.id_base = p.input.id_base;
  context.objectives = in.objective_names.size();
  context.padded_columns = p.input.pad_columns;
  context.scale = spec.scale;
  context.options = options;
  for (const auto& name : in.objective_names)
    context.scaled.push_back(std::find(in.files.scaled_objectives.begin(),
                                       in.files.scaled_objectives.end(),
                                       name) != in.files.scaled_objectives.end());
  config.solver_template = command;
  config.output_format = p.output.format;
  config.adapter = profile_adapter(p, context);
  config.success_exit_codes = p.success_exit_codes;
  config.id_base = p.input.id_base;
  config.solver_name = spec.name.empty() ? checked.resolved.name : spec.name;
  config.solver_version = spec.version.empty() ? p.version : spec.version;
  auto& m = config.parameters;
  m["profile.name"] = p.name;
  m["profile.file"] = p.file;
  if (!p.repository.empty()) m["profile.repository"] = p.repository;
  m["profile.input"] = std::string(kInputFormNames.name(p.input.form));
  m["profile.runtime_clock"] = std::string(kRuntimeClockNames.name(p.output.runtime_clock));
  m["profile.id_base"] = std::to_string(p.input.id_base);
  for (const auto& [key, value] : options) m["profile.option." + key] = value;
  if (!in.files.scaled_objectives.empty()) {
    m["profile.scale"] = format_real_cost(spec.scale);
    std::string names;
    for (const auto& name : in.files.scaled_objectives) names += (names.empty() ? "" : ",") + name;
    m["profile.scaled_objectives"] = names;
  }
  if (p.input.parallel_arcs == ParallelArcs::collapse)
    m["profile.parallel_arcs"] =
        "collapsed: dominated parallel arcs dropped, the others subdivided";
  if (p.input.append_dummy_arc) m["profile.dummy_arc"] = "appended to every .gr";
}

}  // namespace mosb::converters
