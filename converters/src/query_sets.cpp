#include "mosb/converters/query_sets.hpp"

#include "mosb/converters/query_import.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/error.hpp"
#include "mosb/random.hpp"

namespace mosb::converters {

namespace {

// Every key a query command writes for set `name`: cleared before a set is (re)written, so a
// replaced set never keeps keys of its predecessor. Listed exactly, not by prefix, because set
// names may contain '.' (set "a" must not clear the keys of set "a.b").
Metadata without_query_keys(const Metadata& metadata, const std::string& name) {
  static const char* const kSuffixes[] = {"source",     "input.name", "input.size",
                                          "input.xxh3", "id_base",    "match",
                                          "seed",       "count",      "allow_same"};
  Metadata out;
  for (const auto& [key, value] : metadata.entries()) {
    bool ours = false;
    for (const char* suffix : kSuffixes) ours |= key == "queries." + name + "." + suffix;
    if (!ours) out.set(key, value);
  }
  return out;
}

void check_new_set(const GraphReader& reader, const std::string& name, bool replace) {
  if (reader.find(format::SectionKind::queries, name) && !replace)
    throw Error(reader.display_name() + ": query set '" + name +
                "' exists; pass --replace to overwrite it");
}

unsigned instance_id_base(const GraphReader& reader) {
  const auto value = reader.metadata().get("id_base");
  if (!value) return 0;  // file ids are 0-based; an instance without the key came from 0-based data
  if (*value == "0") return 0;
  if (*value == "1") return 1;
  throw Error(reader.display_name() + ": metadata id_base '" + *value +
              "' is not 0 or 1; pass --id-base");
}

}  // namespace

QuerySetEdit import_query_set(const GraphReader& reader, const std::string& set,
                              const QueryImportOptions& options, bool replace) {
  check_new_set(reader, set, replace);
  const unsigned id_base = options.id_base ? *options.id_base : instance_id_base(reader);
  InputFile file(options.file);
  const auto& input = file.facts();
  QueryFileOptions parse;
  parse.id_base = id_base;
  parse.vertex_count = reader.vertex_count();
  parse.match = options.match;
  QuerySetEdit edit{without_query_keys(reader.metadata(), set),
                    {set, parse_query_file(file, input.display_name, parse)}};
  const std::string key = "queries." + set + ".";
  edit.metadata.set(key + "source", "import");
  edit.metadata.set(key + "input.name", input.base_name);
  edit.metadata.set(key + "input.size", std::to_string(input.raw_size));
  edit.metadata.set(key + "input.xxh3", input.raw_xxh3);
  edit.metadata.set(key + "id_base", std::to_string(id_base));
  if (options.match) edit.metadata.set(key + "match", *options.match);
  return edit;
}

QuerySetEdit draw_query_set(const GraphReader& reader, const std::string& set,
                            const QueryDrawOptions& options, bool replace) {
  check_new_set(reader, set, replace);
  const std::uint64_t n = reader.vertex_count();
  if (n == 0)
    throw Error(reader.display_name() + ": the graph has no vertices to draw queries from");
  if (n == 1 && !options.allow_same)
    throw Error(reader.display_name() +
                ": the graph has one vertex, so every query has start = goal; pass --allow-same");
  if (options.count < 1 || options.count > kMaxDrawnQueries)
    throw Error("query count " + std::to_string(options.count) + " is not 1 to " +
                std::to_string(kMaxDrawnQueries));
  QuerySetEdit edit{without_query_keys(reader.metadata(), set), {set, {}}};
  auto& pairs = edit.set.pairs;
  pairs.reserve(options.count);
  auto random = stream(options.seed, 0);
  for (std::uint64_t i = 0; i < options.count; ++i) {
    const auto start = static_cast<std::uint32_t>(random.uniform(0, n - 1));
    auto goal = static_cast<std::uint32_t>(random.uniform(0, n - 1));
    while (!options.allow_same && goal == start)
      goal = static_cast<std::uint32_t>(random.uniform(0, n - 1));
    pairs.push_back({start, goal});
  }
  const std::string key = "queries." + set + ".";
  edit.metadata.set(key + "source", "generate");
  edit.metadata.set(key + "seed", std::to_string(options.seed));
  edit.metadata.set(key + "count", std::to_string(options.count));
  edit.metadata.set(key + "allow_same", options.allow_same ? "1" : "0");
  return edit;
}

}  // namespace mosb::converters
