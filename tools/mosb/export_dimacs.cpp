#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mosb/converters/dimacs_export.hpp"

namespace mosb::cli {

namespace {

struct ExportDimacsArgs {
  std::string instance;
  std::string out_dir;
  std::string view;
  int id_base = -1;  // -1: from the instance's metadata
};

int run_export_dimacs(const ExportDimacsArgs& a) {
  converters::DimacsExportOptions o;
  o.out_dir = a.out_dir;
  if (!a.view.empty()) o.view = a.view;
  if (a.id_base >= 0) o.id_base = static_cast<unsigned>(a.id_base);
  for (const auto& path : converters::export_dimacs(a.instance, o)) std::cout << "wrote " << path.string() << '\n';
  return 0;
}

Command add_export_dimacs(CLI::App& parent) {
  auto* dimacs = parent.add_subcommand(
      "dimacs", "one DIMACS .gr per objective, a .co for coords, a .queries file per query set");
  auto args = std::make_shared<ExportDimacsArgs>();
  dimacs->add_option("instance", args->instance, "the .mosb instance")->required()->check(CLI::ExistingFile);
  dimacs->add_option("--out-dir", args->out_dir, "directory for <benchmark>-<objective>.gr etc. (created)")
      ->required();
  dimacs->add_option("--view", args->view, "export only this view's objectives and query set");
  dimacs->add_option("--id-base", args->id_base, "vertex id base of the text files (default: metadata id_base, else 1)")
      ->check(CLI::IsMember({0, 1}));
  return {dimacs, [args] { return run_export_dimacs(*args); }};
}

}  // namespace

Command add_export(CLI::App& app) {
  auto* exporter = app.add_subcommand("export", "Write an instance back out in a source format");
  return group(exporter, {add_export_dimacs(*exporter)});
}

}  // namespace mosb::cli
