// `mosb solutions import | inspect | verify`: solution files (spec/SOLUTIONS.md). The CLI parses
// options, calls the importers (converters/solution_import.hpp), SolutionWriter, SolutionReader or
// verify_solutions, and prints.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/converters/solution_export.hpp"
#include "mosb/converters/solution_import.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pack.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_summary.hpp"
#include "mosb/solution_verify.hpp"

namespace mosb::cli {

namespace {

struct SolutionImportArgs {
  std::string instance, output;
  ViewChoice choice;
  std::string directory, table, json_log;  // exactly one
  std::string example_log;                 // with directory: the example solvers' stdout
  std::string match = "position";
  std::string status_for_empty = "failed";
  InstanceIdBase id_base;
  std::vector<std::size_t> columns;
  std::string solver, solver_version, epsilon = "0";
  bool nondominated = false, json = false;
};

// Every file the import reads: the instance, the input, and each regular file of --dir (a file
// of the directory is a front file, the output among them).
std::vector<std::filesystem::path> import_inputs(const SolutionImportArgs& a) {
  std::vector<std::filesystem::path> inputs{a.instance, a.table, a.json_log, a.example_log};
  std::error_code error;
  if (!a.directory.empty())
    for (const auto& entry : std::filesystem::directory_iterator(a.directory, error))
      inputs.push_back(entry.path());
  return inputs;
}

int run_import(const SolutionImportArgs& a) {
  const int inputs = !a.directory.empty() + !a.table.empty() + !a.json_log.empty();
  if (inputs != 1)
    throw Error(ErrorCode::invalid_argument, "give exactly one of --dir, --table, --json-log");
  check_output_is_not_input(a.output, import_inputs(a));
  if (a.choice.view.empty() && a.choice.objectives.empty())
    throw UsageError("give --view V or --objectives A,B,... (the objectives the costs are)");
  const auto instance = mosb::load(a.instance, VerifyLevel::checksums);
  View selected;
  try {
    selected = solution_selection(instance, a.choice);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::invalid_argument) throw;
    throw UsageError(error_text(e));
  }
  SolutionWriter writer(instance, selected);
  const auto& set = selected.query_set;
  converters::SolutionImportOptions options;
  options.objective_count = writer.objective_count();
  options.columns = a.columns;
  options.id_base = a.id_base.checked(instance).value_or(0);
  options.vertex_count = instance.vertex_count();
  options.queries = instance.queries(set);
  options.match = *converters::kRecordMatchNames.parse(a.match);       // checked by CLI11
  options.status_for_empty = *parse_query_status(a.status_for_empty);  // checked by CLI11
  std::vector<converters::ImportedResult> results;
  if (!a.directory.empty()) {
    results = converters::import_front_directory(a.directory, options);
    if (!a.example_log.empty()) {
      const auto input = converters::read_text_input(a.example_log);
      converters::apply_example_run_log(input.text, a.example_log, options, results);
    }
  } else if (!a.table.empty()) {
    const auto input = converters::read_text_input(a.table);
    results =
        converters::parse_solution_table(input.text, a.table, writer.objective_names(), options);
  } else {
    const auto input = converters::read_text_input(a.json_log);
    results = converters::parse_solver_json_log(input.text, a.json_log, options);
  }
  writer.set_solver({a.solver, a.solver_version, {}, a.epsilon, {}});
  const auto dropped =
      converters::set_imported_results(writer, results,
                                       a.nondominated ? converters::DominatedVectors::keep_optimal
                                                      : converters::DominatedVectors::refuse);
  writer.write(a.output);
  const auto written = SolutionReader::open(a.output);
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("file").value(a.output);
    json.key("queries").value(written.query_count());
    json.key("imported").value(static_cast<std::uint64_t>(results.size()));
    json.key("vectors").value(written.vector_count());
    json.key("dropped_vectors").value(dropped.vectors);
    json.key("dropped_queries").value(dropped.queries);
    json.key("digest").value(written.digest());
    json.end_object();
  } else {
    std::cout << "wrote " << escape_for_terminal(a.output) << ": " << results.size() << " of "
              << written.query_count() << " queries imported, " << written.vector_count()
              << " vectors";
    if (a.nondominated)
      std::cout << " (" << dropped.vectors << " dominated or repeated vectors dropped from "
                << dropped.queries << " queries)";
    std::cout << ", digest " << written.digest() << "\n";
  }
  return 0;
}

struct ExportArgs {
  std::string file, instance, directory, json_log;
  unsigned id_base = 0;
};

int run_export(const ExportArgs& a) {
  if (a.directory.empty() == a.json_log.empty())
    throw Error(ErrorCode::invalid_argument, "give exactly one of --dir, --json-log");
  const auto r = SolutionReader::open_verified(a.file);
  const std::vector<std::filesystem::path> inputs{a.file, a.instance};
  if (!a.directory.empty()) {
    const auto files = converters::export_front_directory(r, a.directory, a.id_base, inputs);
    std::cout << "wrote " << files << " front files to " << escape_for_terminal(a.directory)
              << "\n";
    return 0;
  }
  if (a.instance.empty())
    throw Error(ErrorCode::invalid_argument, "--json-log needs --instance (for the endpoints)");
  const auto records = converters::export_json_log(
      r, mosb::load(a.instance, VerifyLevel::checksums), a.json_log, a.id_base, inputs);
  std::cout << "wrote " << escape_for_terminal(a.json_log) << ": " << records << " records\n";
  return 0;
}

struct InspectArgs {
  std::string file;
  bool json = false;
};

void print_inspect_json(const InspectArgs& a, const SolutionReader& r, const SolutionSummary& t) {
  const auto solver = r.solver();
  JsonWriter json(std::cout);
  json.begin_object();
  json.key("file").value(a.file);
  json.key("instance_digest").value(r.instance_digest());
  json.key("view");
  if (r.view_name().empty())
    json.null();
  else
    json.value(r.view_name());
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
  json.key("machine").value(solver.machine);
  json.key("parameters").begin_object();
  for (const auto& [key, value] : solver.parameters) json.key(key).value(value);
  json.end_object();
  json.key("queries").value(r.query_count());
  json.key("vectors").value(r.vector_count());
  json.key("statuses");
  json_status_counts(json, t.completed.statuses);
  json.key("front_size");
  json_distribution(json, t.completed.front_size, true, false);
  json.key("runtime_seconds");
  json_distribution(json, t.completed.runtime, true, false);
  json.key("paths").value(r.has_paths());
  json.key("dropped_vectors");
  if (const auto dropped = r.dropped_vectors())
    json.begin_object()
        .key("vectors")
        .value(dropped->vectors)
        .key("queries")
        .value(dropped->queries)
        .end_object();
  else
    json.null();
  json.key("statistics").begin_object();
  for (const auto& statistic : t.statistics) {
    json.key(to_string(statistic.statistic)).begin_object();
    json.key("queries").value(statistic.queries);
    json.key("total").value(statistic.total);
    json.key("max").value(statistic.max);
    json.end_object();
  }
  json.end_object();
  json.end_object();
}

void print_inspect_text(const InspectArgs& a, const SolutionReader& r, const SolutionSummary& t) {
  const auto solver = r.solver();
  // The solver's name, version and epsilon are free text from the file: escaped, as inspect escapes
  // metadata values, so that a forged file cannot drive the terminal.
  std::cout << escape_for_terminal(a.file) << ": solutions of instance " << r.instance_digest()
            << (r.view_name().empty() ? std::string(", no view")
                                      : ", view " + escape_for_terminal(r.view_name()))
            << ", query set " << escape_for_terminal(r.query_set()) << "\n";
  std::cout << "objectives";
  for (std::size_t i = 0; i < r.objective_count(); ++i)
    std::cout << ' ' << r.objective_name(i) << " (" << format::to_string(r.objective_type(i))
              << ')';
  std::cout << "\nsolver " << (solver.name.empty() ? "-" : escape_for_terminal(solver.name))
            << (solver.version.empty() ? "" : " " + escape_for_terminal(solver.version))
            << ", epsilon " << escape_for_terminal(solver.epsilon) << "\n";
  if (!solver.machine.empty())
    std::cout << "machine " << escape_for_terminal(solver.machine) << "\n";
  for (const auto& [key, value] : solver.parameters)
    std::cout << "parameter " << key << " = " << escape_for_terminal(value) << "\n";
  std::cout << r.query_count() << " queries: " << status_counts_text(t.completed.statuses, false)
            << "\n";
  const auto& c = t.completed;
  std::cout << "front size over " << (c.front_size ? c.front_size->count : 0)
            << " completed queries (solved or disconnected): "
            << distribution_text(c.front_size, "", true) << " (" << r.vector_count()
            << " vectors)\n";
  std::cout << "runtime over " << (c.runtime ? c.runtime->count : 0)
            << " completed queries: " << distribution_text(c.runtime, " s", true) << "\n";
  std::cout << "paths: " << (r.has_paths() ? "yes" : "no") << "\n";
  if (const auto dropped = r.dropped_vectors())
    std::cout << "imported with --nondominated: " << dropped->vectors
              << " dominated or repeated vectors dropped from " << dropped->queries << " queries\n";
  for (const auto& statistic : t.statistics)
    std::cout << to_string(statistic.statistic) << ": " << statistic.queries << " queries, total "
              << statistic.total << ", max " << statistic.max << "\n";
}

int run_inspect(const InspectArgs& a) {
  const auto r = SolutionReader::open_verified(a.file);
  const auto summary = summarize(r);
  if (a.json)
    print_inspect_json(a, r, summary);
  else
    print_inspect_text(a, r, summary);
  return 0;
}

struct SolutionVerifyArgs {
  std::string file;
  std::string instance;
  bool json = false;
};

int run_solution_verify(const SolutionVerifyArgs& a) {
  std::optional<std::string> problem;
  try {
    const auto r = SolutionReader::open(a.file);
    if (a.instance.empty()) {
      problem = r.verify_payload();
      if (problem) problem = a.file + ": " + *problem;
    } else {
      problem = verify_solutions(r, mosb::load(a.instance, VerifyLevel::full));
      if (problem && !problem->starts_with(a.file)) problem = a.file + ": " + *problem;
    }
  } catch (const Error& e) {
    problem = error_text(e);
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
    std::cerr << "mosb: " << escape_for_terminal(*problem) << "\n";
  } else {
    std::cout << "OK   " << escape_for_terminal(a.file)
              << (a.instance.empty() ? " (payload; give --instance for fronts and paths)"
                                     : " (against " + escape_for_terminal(a.instance) + ")")
              << "\n";
  }
  return problem ? 1 : 0;
}

}  // namespace

Command add_solutions(CLI::App& app) {
  auto* group_app = app.add_subcommand("solutions", "Solution files: reference or solver fronts");
  auto import_args = std::make_shared<SolutionImportArgs>();
  auto* import = group_app->add_subcommand(
      "import", "Write a solution file from solver output: per-query files, a table or a JSON log");
  import->add_option("--instance", import_args->instance, "the instance (.mosb)")->required();
  add_view_choice_options(import, import_args->choice, "the objectives of the costs");
  import->add_option("--dir", import_args->directory,
                     "a directory of per-query front files (query id in the name)");
  import
      ->add_option("--example-log", import_args->example_log,
                   "with --dir: the per-query lines an example solver printed (start goal "
                   "front_size seconds expansions), kept as runtime and expanded")
      ->needs(import->get_option("--dir"));
  import->add_option("--table", import_args->table,
                     "a CSV/TSV table: a 'query' column and one column per objective");
  import->add_option("--json-log", import_args->json_log,
                     "a PPA*/BOA*-style JSON log (source, target, finish_info.solutions)");
  import
      ->add_option("--match", import_args->match,
                   "JSON records to queries by 'position' (default) or 'endpoints'")
      ->check(CLI::IsMember(converters::kRecordMatchNames.names()));
  add_instance_id_base_options(import, import_args->id_base, "0");
  import
      ->add_option("--status-for-empty", import_args->status_for_empty,
                   "with --dir: the status of a front file with no vector and no 'status' line: "
                   "disconnected, timeout or failed (default: failed; with --example-log, a "
                   "line saying front size 0 makes it disconnected)")
      ->check(
          CLI::IsMember(std::vector<std::string>{std::string(to_string(QueryStatus::disconnected)),
                                                 std::string(to_string(QueryStatus::timeout)),
                                                 std::string(to_string(QueryStatus::failed))}))
      ->needs(import->get_option("--dir"));
  import
      ->add_option("--columns", import_args->columns,
                   "0-based positions of the view's values in each input vector (or table "
                   "row), in the view's order")
      ->delimiter(',')
      ->check(unsigned_integer(std::numeric_limits<std::size_t>::max()));
  import->add_option("--solver", import_args->solver, "the solver's name")->check(printable_text());
  import->add_option("--solver-version", import_args->solver_version, "the solver's version")
      ->check(printable_text());
  import->add_option("--epsilon", import_args->epsilon, "the epsilon the solver used (0: exact)")
      ->check(epsilon_value());
  import->add_flag("--nondominated", import_args->nondominated,
                   "keep each front's non-dominated vectors (the first of equal ones) instead of "
                   "refusing a front with dominated or repeated vectors; the file records how "
                   "many were dropped");
  add_output_option(import, import_args->output, "the solution file")->required();
  add_json_flag(import, import_args->json);
  auto export_args = std::make_shared<ExportArgs>();
  auto* export_ = group_app->add_subcommand(
      "export", "Write a solution file's fronts as per-query text files or a JSON log");
  export_->add_option("SOLUTIONS", export_args->file, "a solution file")->required();
  export_->add_option("--dir", export_args->directory, "write <query id>.txt files here");
  export_->add_option("--json-log", export_args->json_log,
                      "write a PPA*/BOA*-style JSON log to this file");
  export_->add_option("--instance", export_args->instance,
                      "the file's instance (for the endpoints of --json-log)");
  add_id_base_option(export_, export_args->id_base, "0");
  auto inspect_args = std::make_shared<InspectArgs>();
  auto* inspect = group_app->add_subcommand(
      "inspect", "Summarise a solution file: binding, solver, statuses, front sizes");
  inspect->add_option("SOLUTIONS", inspect_args->file, "a solution file")->required();
  add_json_flag(inspect, inspect_args->json);
  auto verify_args = std::make_shared<SolutionVerifyArgs>();
  auto* verify = group_app->add_subcommand(
      "verify",
      "Check a solution file: checksums and statuses; with --instance also the digest, "
      "non-dominated duplicate-free fronts and paths");
  verify->add_option("SOLUTIONS", verify_args->file, "a solution file")->required();
  verify->add_option("--instance", verify_args->instance, "the instance the file belongs to");
  add_json_flag(verify, verify_args->json);
  return group(group_app, {{import, [import_args] { return run_import(*import_args); }},
                           {export_, [export_args] { return run_export(*export_args); }},
                           {inspect, [inspect_args] { return run_inspect(*inspect_args); }},
                           {verify, [verify_args] { return run_solution_verify(*verify_args); }},
                           add_solutions_compare(group_app),
                           add_solutions_merge(group_app),
                           add_solutions_reference(group_app)});
}

}  // namespace mosb::cli
