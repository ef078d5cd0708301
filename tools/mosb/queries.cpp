// `mosb queries import` and `mosb queries generate`: add or replace one query set of an existing
// instance, rewriting it atomically in place with every other section byte-identical
// (spec/QUERIES.md).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/converters/query_import.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/instance_editor.hpp"
#include "mosb/random.hpp"

namespace mosb::cli {

namespace {

constexpr std::uint64_t kMaxGeneratedCount = 100'000'000;  // 800 MB of pairs

struct ImportArgs {
  std::string file;
  std::string instance;
  std::string name;
  int id_base = -1;  // -1: the instance's metadata id_base
  std::string match;
  bool replace = false;
};

struct GenerateArgs {
  std::string instance;
  std::string name;
  std::uint64_t count = 100;
  std::uint64_t seed = 0;
  bool allow_same = false;
  bool replace = false;
};

// Every key a query command writes for set `name`: cleared before a set is (re)written, so a
// replaced set never keeps keys of its predecessor. Listed exactly, not by prefix, because set
// names may contain '.' (set "a" must not clear the keys of set "a.b").
Metadata without_query_keys(const Metadata& metadata, const std::string& name) {
  static const char* const kSuffixes[] = {"source", "input.name", "input.size", "input.xxh3", "id_base",
                                          "match", "seed", "count", "allow_same"};
  Metadata out;
  for (const auto& [key, value] : metadata.entries()) {
    bool ours = false;
    for (const char* suffix : kSuffixes) ours |= key == "queries." + name + "." + suffix;
    if (!ours) out.set(key, value);
  }
  return out;
}

void check_new_set(const GraphReader& reader, const std::string& instance, const std::string& name,
                   bool replace) {
  if (reader.find(format::SectionKind::queries, name) && !replace)
    throw Error(instance + ": query set '" + name + "' exists; pass --replace to overwrite it");
}

int write_and_report(const GraphReader& reader, const Metadata& metadata, QuerySet set,
                     const std::string& instance) {
  const std::string name = set.name;
  rewrite_instance(reader, metadata, {std::move(set)}, instance);
  const auto written = GraphReader::open(instance);
  std::cout << "wrote " << instance << ": query set " << name << ", "
            << written.queries(name).size() << " queries, digest " << written.digest() << '\n';
  return 0;
}

unsigned instance_id_base(const GraphReader& reader, const std::string& instance) {
  const auto value = reader.metadata().get("id_base");
  if (!value) return 0;  // file ids are 0-based; an instance without the key came from 0-based data
  if (*value == "0") return 0;
  if (*value == "1") return 1;
  throw Error(instance + ": metadata id_base '" + *value + "' is not 0 or 1; pass --id-base");
}

int run_import(const ImportArgs& a) {
  check_output_is_not_input(a.instance, {a.file});
  const auto reader = GraphReader::open(a.instance);
  check_new_set(reader, a.instance, a.name, a.replace);
  const unsigned id_base = a.id_base >= 0 ? static_cast<unsigned>(a.id_base) : instance_id_base(reader, a.instance);
  converters::InputFile file(a.file);
  const auto& input = file.facts();
  converters::QueryFileOptions options;
  options.id_base = id_base;
  options.vertex_count = reader.vertex_count();
  if (!a.match.empty()) options.match = a.match;
  QuerySet set{a.name, converters::parse_query_file(file, input.display_name, options)};

  Metadata metadata = without_query_keys(reader.metadata(), a.name);
  const std::string key = "queries." + a.name + ".";
  metadata.set(key + "source", "import");
  metadata.set(key + "input.name", input.base_name);
  metadata.set(key + "input.size", std::to_string(input.raw_size));
  metadata.set(key + "input.xxh3", input.raw_xxh3);
  metadata.set(key + "id_base", std::to_string(id_base));
  if (options.match) metadata.set(key + "match", *options.match);
  return write_and_report(reader, metadata, std::move(set), a.instance);
}

int run_generate(const GenerateArgs& a) {
  const auto reader = GraphReader::open(a.instance);
  check_new_set(reader, a.instance, a.name, a.replace);
  const std::uint64_t n = reader.vertex_count();
  if (n == 0) throw Error(a.instance + ": the graph has no vertices to draw queries from");
  if (n == 1 && !a.allow_same)
    throw Error(a.instance + ": the graph has one vertex, so every query has start = goal; pass --allow-same");
  QuerySet set{a.name, {}};
  set.pairs.reserve(a.count);
  auto random = stream(a.seed, 0);
  for (std::uint64_t i = 0; i < a.count; ++i) {
    const auto start = static_cast<std::uint32_t>(random.uniform(0, n - 1));
    auto goal = static_cast<std::uint32_t>(random.uniform(0, n - 1));
    while (!a.allow_same && goal == start) goal = static_cast<std::uint32_t>(random.uniform(0, n - 1));
    set.pairs.push_back({start, goal});
  }
  Metadata metadata = without_query_keys(reader.metadata(), a.name);
  const std::string key = "queries." + a.name + ".";
  metadata.set(key + "source", "generate");
  metadata.set(key + "seed", std::to_string(a.seed));
  metadata.set(key + "count", std::to_string(a.count));
  metadata.set(key + "allow_same", a.allow_same ? "1" : "0");
  return write_and_report(reader, metadata, std::move(set), a.instance);
}

Command add_queries_import(CLI::App& queries) {
  auto* import = queries.add_subcommand(
      "import", "Import (start, goal) pairs from a text file (s t | s, t | s;t | graph-path s t)");
  auto a = std::make_shared<ImportArgs>();
  import->add_option("FILE", a->file, "the query file (plain, gzip, bzip2, xz or zstd)")
      ->required()->check(CLI::ExistingFile);
  import->add_option("--into", a->instance, "the .mosb instance to rewrite in place")
      ->required()->check(CLI::ExistingFile);
  import->add_option("--name", a->name, "the query set name")->required();
  import->add_option("--id-base", a->id_base, "base of vertex ids in FILE (default: the instance's id_base)")
      ->check(CLI::IsMember({0, 1}));
  import->add_option("--match", a->match, "keep only 'graph s t' lines whose graph field contains TEXT");
  import->add_flag("--replace", a->replace, "overwrite an existing query set of that name");
  return {import, [a] { return run_import(*a); }};
}

Command add_queries_generate(CLI::App& queries) {
  auto* generate = queries.add_subcommand(
      "generate", "Draw uniform random (start, goal) pairs over all vertices");
  auto a = std::make_shared<GenerateArgs>();
  generate->add_option("--into", a->instance, "the .mosb instance to rewrite in place")
      ->required()->check(CLI::ExistingFile);
  generate->add_option("--name", a->name, "the query set name")->required();
  generate->add_option("--count", a->count, "number of pairs")
      ->check(CLI::Range(std::uint64_t{1}, kMaxGeneratedCount))->capture_default_str();
  generate->add_option("--seed", a->seed, "seed of the specified random stream")->required();
  generate->add_flag("--allow-same", a->allow_same, "keep pairs with start = goal (redrawn otherwise)");
  generate->add_flag("--replace", a->replace, "overwrite an existing query set of that name");
  return {generate, [a] { return run_generate(*a); }};
}

}  // namespace

Command add_queries(CLI::App& app) {
  auto* queries = app.add_subcommand("queries", "Add or replace a query set of an instance");
  return group(queries, {add_queries_import(*queries), add_queries_generate(*queries)});
}

}  // namespace mosb::cli
