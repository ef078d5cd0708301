#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/converters/dimacs_export.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/utf8.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct ExportDimacsArgs {
  std::string instance;
  std::string output;
  ViewChoice choice;
  InstanceIdBase id_base;
  bool multi_column = false;
  std::string queries_format = "space";
  double scale = 0;
  bool json = false;
};

int run_export_dimacs(const ExportDimacsArgs& a) {
  converters::DimacsExportOptions o;
  o.out_dir = a.output;
  o.selection = a.choice;
  o.id_base = a.id_base.checked(GraphReader::open(a.instance));
  o.multi_column = a.multi_column;
  o.queries_format = *converters::kQueriesFormatNames.parse(a.queries_format);
  o.scale = a.scale;
  TerminalProgress progress;
  const auto written = converters::export_dimacs(a.instance, o, progress.callback());
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("instance").value(a.instance);
    json.key("directory").value(a.output);
    json.key("wrote").begin_array();
    for (const auto& path : written) json.value(path.string());
    json.end_array();
    json.end_object();
  } else {
    for (const auto& path : written)
      std::cout << "wrote " << escape_for_terminal(path.string()) << '\n';
  }
  return 0;
}

Command add_export_dimacs(CLI::App& parent) {
  auto* dimacs = parent.add_subcommand(
      "dimacs",
      "one DIMACS .gr per objective (or one multi-column .gr), a .co for coords, a .queries file "
      "per query set");
  auto args = std::make_shared<ExportDimacsArgs>();
  dimacs->add_option("INSTANCE", args->instance, "the .mosb instance")
      ->required()
      ->check(CLI::ExistingFile);
  add_output_option(dimacs, args->output, "directory for <benchmark>-<objective>.gr etc. (created)")
      ->required();
  add_view_choice_options(dimacs, args->choice, "export only these objectives and their query set");
  add_instance_id_base_options(dimacs, args->id_base, "the instance's metadata id_base, else 1");
  dimacs->add_flag("--multi-column", args->multi_column,
                   "one .gr whose arc lines carry every objective's cost (a u v c1 c2 ...) "
                   "instead of one .gr per objective");
  dimacs
      ->add_option("--queries-format", args->queries_format,
                   "how a .queries line separates its two ids: space (default, `s t`) or "
                   "comma (`s,t`, as the A*pex and mohs query files)")
      ->check(CLI::IsMember(converters::kQueriesFormatNames.names()));
  dimacs
      ->add_option("--scale", args->scale,
                   "write float objectives' costs x K rounded to integers (for solvers that "
                   "read integer costs only)")
      ->check(CLI::PositiveNumber)
      ->option_text("K");
  add_json_flag(dimacs, args->json);
  return {dimacs, [args] { return run_export_dimacs(*args); }};
}

}  // namespace

Command add_export(CLI::App& app) {
  auto* exporter = app.add_subcommand("export", "Write an instance back out in a source format");
  return group(exporter, {add_export_dimacs(*exporter)});
}

}  // namespace mosb::cli
