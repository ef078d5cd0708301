// `mosb solutions inspect | verify`: solution files (spec/SOLUTIONS.md). The CLI parses options,
// calls SolutionReader / verify_solutions and prints.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_verify.hpp"

namespace mosb::cli {

namespace {

struct InspectArgs {
  std::string file;
  bool json = false;
};

int run_inspect(const InspectArgs& a) {
  const auto r = SolutionReader::open(a.file);
  std::uint64_t counts[kLastQueryStatus + 1] = {};
  std::vector<std::uint64_t> sizes;
  for (std::uint64_t q = 0; q < r.query_count(); ++q) {
    const auto status = r.status(q);
    ++counts[static_cast<std::size_t>(status)];
    if (status == QueryStatus::solved) sizes.push_back(r.front_size(q));
  }
  std::sort(sizes.begin(), sizes.end());
  // The median of an even count is the lower middle one: a front cardinality, never a fraction.
  const auto median = sizes.empty() ? 0 : sizes[(sizes.size() - 1) / 2];
  const auto solver = r.solver();
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("file").value(a.file);
    json.key("instance_digest").value(r.instance_digest());
    json.key("view").value(r.view_name());
    json.key("query_set").value(r.query_set());
    json.key("objectives").begin_array();
    for (std::size_t i = 0; i < r.objective_count(); ++i) {
      json.begin_object();
      json.key("name").value(r.objective_name(i));
      json.key("type").value(format::to_string(r.objective_type(i)));
      json.end_object();
    }
    json.end_array();
    json.key("solver").value(solver.name);
    json.key("solver_version").value(solver.version);
    json.key("epsilon").value(solver.epsilon);
    json.key("queries").value(r.query_count());
    json.key("vectors").value(r.vector_count());
    json.key("statuses").begin_object();
    for (std::uint8_t s = 0; s <= kLastQueryStatus; ++s)
      json.key(to_string(static_cast<QueryStatus>(s))).value(counts[s]);
    json.end_object();
    json.key("front_size").begin_object();
    if (sizes.empty()) {
      json.key("min").null().key("median").null().key("max").null();
    } else {
      json.key("min").value(sizes.front());
      json.key("median").value(median);
      json.key("max").value(sizes.back());
    }
    json.end_object();
    json.key("paths").value(r.has_paths());
    json.end_object();
    return 0;
  }
  std::cout << a.file << ": solutions of instance " << r.instance_digest() << ", view "
            << r.view_name() << ", query set " << r.query_set() << "\n";
  std::cout << "objectives";
  for (std::size_t i = 0; i < r.objective_count(); ++i)
    std::cout << ' ' << r.objective_name(i) << " (" << format::to_string(r.objective_type(i))
              << ')';
  std::cout << "\nsolver " << (solver.name.empty() ? "-" : solver.name) << ' ' << solver.version
            << ", epsilon " << solver.epsilon << "\n";
  std::cout << r.query_count() << " queries:";
  for (std::uint8_t s = 0; s <= kLastQueryStatus; ++s)
    std::cout << ' ' << counts[s] << ' ' << to_string(static_cast<QueryStatus>(s))
              << (s < kLastQueryStatus ? "," : "\n");
  if (sizes.empty())
    std::cout << "front size: no solved query\n";
  else
    std::cout << "front size: min " << sizes.front() << ", median " << median << ", max "
              << sizes.back() << " (" << r.vector_count() << " vectors)\n";
  std::cout << "paths: " << (r.has_paths() ? "yes" : "no") << "\n";
  return 0;
}

struct VerifyArgs {
  std::string file;
  std::string instance;
  bool json = false;
};

int run_verify(const VerifyArgs& a) {
  std::optional<std::string> problem;
  try {
    const auto r = SolutionReader::open(a.file);
    if (a.instance.empty()) {
      problem = r.verify_payload();
      if (problem) problem = a.file + ": " + *problem;
    } else {
      problem = verify_solutions(r, GraphReader::open(a.instance, VerifyLevel::full));
      if (problem && !problem->starts_with(a.file)) problem = a.file + ": " + *problem;
    }
  } catch (const Error& e) {
    problem = e.what();
  }
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("file").value(a.file);
    json.key("instance").value(a.instance);
    json.key("ok").value(!problem);
    if (problem) json.key("problem").value(*problem);
    json.end_object();
  } else if (problem) {
    std::cerr << "mosb: " << *problem << "\n";
  } else {
    std::cout << "OK   " << a.file
              << (a.instance.empty() ? " (payload; give --instance for fronts and paths)"
                                     : " (against " + a.instance + ")")
              << "\n";
  }
  return problem ? 1 : 0;
}

}  // namespace

Command add_solutions(CLI::App& app) {
  auto* group_app = app.add_subcommand("solutions", "Solution files: reference or solver fronts");
  auto inspect_args = std::make_shared<InspectArgs>();
  auto* inspect = group_app->add_subcommand(
      "inspect", "Summarise a solution file: binding, solver, statuses, front sizes");
  inspect->add_option("SOLUTIONS", inspect_args->file, "a solution file")->required();
  add_json_flag(inspect, inspect_args->json);
  auto verify_args = std::make_shared<VerifyArgs>();
  auto* verify = group_app->add_subcommand(
      "verify",
      "Check a solution file: checksums and statuses; with --instance also the digest, "
      "non-dominated duplicate-free fronts and paths");
  verify->add_option("SOLUTIONS", verify_args->file, "a solution file")->required();
  verify->add_option("--instance", verify_args->instance, "the instance the file belongs to");
  add_json_flag(verify, verify_args->json);
  return group(group_app, {{inspect, [inspect_args] { return run_inspect(*inspect_args); }},
                           {verify, [verify_args] { return run_verify(*verify_args); }}});
}

}  // namespace mosb::cli
