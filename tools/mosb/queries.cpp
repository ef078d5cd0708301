// `mosb queries import` and `mosb queries generate`: add or replace one query set of an instance,
// writing a new file (-o) or rewriting it atomically in place, every other section byte-identical
// (spec/QUERIES.md). The sets and their metadata come from converters/query_sets.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/converters/query_sets.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/instance_editor.hpp"
#include "mosb/internal/utf8.hpp"

namespace mosb::cli {

namespace {

// What both subcommands share: the instance, the set, where to write, how to report.
struct Target {
  std::string instance;
  std::string set;
  std::string output;
  bool in_place = false;
  bool replace = false;
  bool json = false;
  std::string view;  // bind the set to this view only (else to every view without a set)
};

converters::ViewBinding binding(const Target& t) {
  return {t.view.empty() ? std::nullopt : std::optional<std::string>(t.view)};
}

void add_target_options(CLI::App* sub, Target& t) {
  sub->add_option("INSTANCE", t.instance, "the .mosb instance")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--set", t.set, "the query set name")->required();
  auto* output =
      add_output_option(sub, t.output, "write the instance with the set to this new file");
  sub->add_flag("--in-place", t.in_place, "rewrite INSTANCE itself (atomically)")->excludes(output);
  sub->add_flag("--replace", t.replace, "overwrite an existing query set of that name");
  sub->add_option("--view", t.view,
                  "make the set this view's query set (default: of every view that has none)");
  add_json_flag(sub, t.json);
}

const std::string& destination(const Target& t) {
  if (t.output.empty() && !t.in_place) throw UsageError("give -o OUT (a new file) or --in-place");
  // -o names a new file: the instance itself (or a link to it) only with --in-place, as pack,
  // unpack and convert refuse their input as output.
  if (!t.in_place) check_output_is_not_input(t.output, {t.instance});
  return t.in_place ? t.instance : t.output;
}

int write_and_report(const GraphReader& reader, converters::QuerySetEdit edit, const Target& t) {
  const auto& path = destination(t);
  const std::string name = edit.set.name;
  if (!edit.bound_views.empty()) {
    std::string views;
    for (const auto& v : edit.bound_views) views += (views.empty() ? "" : ", ") + v;
    std::cerr << "query set " << name << " is now the query set of view"
              << (edit.bound_views.size() > 1 ? "s " : " ") << views << '\n';
  }
  rewrite_instance(reader, edit.metadata, {std::move(edit.set)}, path);
  const auto written = GraphReader::open(path);
  const std::uint64_t count = written.queries(name).size();
  if (t.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("file").value(path);
    json.key("set").value(name);
    json.key("queries").value(count);
    json.key("digest").value(written.digest());
    json.end_object();
  } else {
    std::cout << "wrote " << escape_for_terminal(path) << ": query set " << name << ", " << count
              << " queries, digest " << written.digest() << '\n';
  }
  return 0;
}

struct QueryImportArgs {
  Target target;
  std::string file;
  InstanceIdBase id_base;
  std::string match;
  bool scenario = false;
};

struct GenerateArgs {
  Target target;
  converters::QueryDrawOptions draw;
};

Command add_queries_import(CLI::App& queries) {
  auto* import = queries.add_subcommand(
      "import", "Import (start, goal) pairs from a text file (s t | s, t | s;t | graph-path s t)");
  auto a = std::make_shared<QueryImportArgs>();
  add_target_options(import, a->target);
  import->add_option("QUERIES", a->file, "the query file (plain, gzip, bzip2, xz or zstd)")
      ->required()
      ->check(CLI::ExistingFile);
  add_instance_id_base_options(import, a->id_base, "the instance's metadata id_base, else 0");
  import->add_option("--match", a->match,
                     "keep only 'graph s t' lines whose graph field contains TEXT");
  import->add_flag("--scen", a->scenario,
                   "QUERIES is a Moving AI scenario of the instance's map; its optimal lengths "
                   "are kept as references");
  return {import, [a] {
            check_output_is_not_input(destination(a->target), {a->file});  // checks before any work
            const auto reader =
                GraphReader::open(a->target.instance, VerifyLevel::full);  // its payload is copied
            converters::QueryImportOptions options;
            options.file = a->file;
            // A scenario has no ids: the importer refuses any --id-base with its own message.
            options.id_base = a->scenario && a->id_base.option->count() > 0
                                  ? std::optional<unsigned>(a->id_base.value)
                                  : a->id_base.checked(reader);
            options.binding = binding(a->target);
            if (!a->match.empty()) options.match = a->match;
            options.scenario = a->scenario;
            return write_and_report(
                reader,
                converters::import_query_set(reader, a->target.set, options, a->target.replace),
                a->target);
          }};
}

Command add_queries_generate(CLI::App& queries) {
  auto* generate = queries.add_subcommand(
      "generate", "Draw uniform random (start, goal) pairs over all vertices");
  auto a = std::make_shared<GenerateArgs>();
  add_target_options(generate, a->target);
  generate->add_option("--count", a->draw.count, "number of pairs")
      ->check(unsigned_integer(std::numeric_limits<std::uint64_t>::max()))
      ->check(CLI::Range(std::uint64_t{1}, converters::kMaxDrawnQueries))
      ->capture_default_str();
  add_seed_option(generate, a->draw.seed, "seed of the specified random stream");
  generate->add_flag("--allow-same", a->draw.allow_same,
                     "keep pairs with start = goal (redrawn otherwise)");
  return {generate, [a] {
            destination(a->target);  // checks before any work
            const auto reader =
                GraphReader::open(a->target.instance, VerifyLevel::full);  // its payload is copied
            auto draw = a->draw;
            draw.binding = binding(a->target);
            return write_and_report(
                reader, converters::draw_query_set(reader, a->target.set, draw, a->target.replace),
                a->target);
          }};
}

}  // namespace

Command add_queries(CLI::App& app) {
  auto* queries = app.add_subcommand("queries", "Add or replace a query set of an instance");
  return group(queries, {add_queries_import(*queries), add_queries_generate(*queries)});
}

}  // namespace mosb::cli
