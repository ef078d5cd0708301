// A solver as a user names it, and the one step from it to the solver part of a RunConfig.
// `mosb run`, an experiment's [[solver]] and every SLURM task name a solver as a SolverSpec; the
// step itself (a template checked, or a solver profile loaded, its text input exported and its
// output read by the adapter it declares) is converters/profiles' solver_resolver(), which
// lib/run and lib/experiment reach only through SolverResolver: they know no profile and no
// output format but the protocol.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mosb/run.hpp"

namespace mosb {

struct SolverSpec {
  // Exactly one of a command template (spec/RUN.md §2) and a solver profile (§10).
  std::string solver_template;
  std::string output_format = "protocol";  // with a template: how its output is read
  std::string profile;                     // a shipped profile's name, or a profile file
  std::string executable;                  // with a profile: what {executable} is
  std::vector<std::string> options;        // with a profile: KEY=VALUE, in order
  double scale = 0;                        // with a profile: float costs × scale (0: none)
  std::string export_cache;                // with a profile: empty for the default cache
  std::string epsilon = "0";               // the ε the solver claims (RunConfig::epsilon)
  std::string name, version;               // recorded; name empty: ResolvedSolver::name
};

struct ResolvedSolver {
  std::string executable;  // the program every query runs, resolved (resolve_executable)
  // The name recorded when the spec gives none: a profile's solver with its options' values
  // where they are not the defaults, and its ε when not 0 ("A*pex NAMOAdr", "A*pex ε=0.05");
  // empty for a template (lib/run then records the executable's file name).
  std::string name;
  // Everything but the executable's bytes that shapes the solver's numbers, as one line: the
  // template, or the profile's name and the SHA-256 of its text with the options and scale;
  // then the output format and ε. A finished experiment cell is bound to it.
  std::string binding;
};

// What a cell's view shows a solver before anything runs: its objectives, in order, and whether
// each holds float costs.
struct CellObjectives {
  std::vector<std::string> names;
  std::vector<bool> is_float;
};

struct SolverResolver {
  // Checks a spec before anything runs. Throws mosb::Error (invalid_argument) saying what is
  // wrong: a template that does not parse, an unknown placeholder or output format, a program
  // that is not there, an unknown profile or option, an ε the profile's solver is not given.
  std::function<ResolvedSolver(const SolverSpec&)> check;
  // Fills the solver part of `config` (its instance, instance_path and choice already set): the
  // template, output format and adapter, exit codes, id base, ε, name, version and parameters;
  // a profile's text input is exported first. Throws as check does, and for what only the
  // instance shows (too many objectives, float costs for an integer solver).
  std::function<void(RunConfig& config, const SolverSpec& spec)> configure;
  // What configure would refuse for a cell's objectives, checked before any cell runs (an
  // experiment's plan): too many or too few objectives, float costs for a solver that reads
  // integers without a scale, a scale without float costs. Throws as check does.
  std::function<void(const SolverSpec& spec, const CellObjectives& objectives)> check_cell;
};

}  // namespace mosb
