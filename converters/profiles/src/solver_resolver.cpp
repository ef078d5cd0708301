#include "mosb/converters/solver_resolver.hpp"

#include "mosb/command_template.hpp"
#include "mosb/converters/profile_run.hpp"
#include "mosb/converters/solver_output.hpp"
#include "mosb/error.hpp"
#include "mosb/eval.hpp"

namespace mosb::converters {

namespace {

[[noreturn]] void refuse(const std::string& message) {
  throw Error(ErrorCode::invalid_argument, message);
}

const SolverOutputFormat& output_format(const std::string& name) {
  const auto* format = find_solver_output_format(name);
  if (format == nullptr) refuse("output format '" + name + "': no such format");
  return *format;
}

}  // namespace

ResolvedSolver check_solver(const SolverSpec& spec) {
  if (spec.solver_template.empty() == spec.profile.empty())
    refuse("give exactly one of a template and a profile");
  parse_epsilon(spec.epsilon);  // throws naming the text
  if (!spec.profile.empty()) {
    if (spec.output_format != "protocol")
      refuse("output format " + spec.output_format + ": not with a profile (the profile says it)");
    return check_profile_solver(spec);
  }
  if (!spec.executable.empty() || !spec.options.empty() || spec.scale != 0 ||
      !spec.export_cache.empty())
    refuse("an executable, options, a scale and an export cache go with a profile, not a template");
  output_format(spec.output_format);
  ResolvedSolver resolved;
  resolved.executable = template_executable(spec.solver_template);
  resolved.binding = "template " + spec.solver_template + " | output " + spec.output_format +
                     " | epsilon " + spec.epsilon;
  return resolved;
}

void configure_solver(RunConfig& config, const SolverSpec& spec) {
  if (!spec.profile.empty()) {
    apply_profile(config, spec);
    return;
  }
  config.solver_template = spec.solver_template;
  config.output_format = spec.output_format;
  config.adapter = output_format(spec.output_format).adapter();
  config.epsilon = spec.epsilon;
  config.solver_name = spec.name;
  config.solver_version = spec.version;
}

void check_solver_cell(const SolverSpec& spec, const CellObjectives& objectives) {
  if (!spec.profile.empty()) check_profile_cell(spec, objectives);
}

SolverResolver solver_resolver() {
  return {check_solver, configure_solver, check_solver_cell};
}

}  // namespace mosb::converters
