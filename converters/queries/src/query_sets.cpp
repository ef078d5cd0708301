#include "mosb/converters/query_sets.hpp"

#include "mosb/converters/movingai.hpp"
#include "mosb/converters/query_import.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/random.hpp"

namespace mosb::converters {

namespace {

// Every key a query command writes for set `name`: cleared before a set is (re)written, so a
// replaced set never keeps keys of its predecessor. Listed exactly, not by prefix, because set
// names may contain '.' (set "a" must not clear the keys of set "a.b").
Metadata without_query_keys(const Metadata& metadata, const std::string& name) {
  static const char* const kSuffixes[] = {"source",
                                          "input.name",
                                          "input.size",
                                          "input.xxh3",
                                          "id_base",
                                          "match",
                                          "seed",
                                          "count",
                                          "allow_same",
                                          "format",
                                          "reference.objective",
                                          "reference.source"};
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
    throw Error(ErrorCode::other,
                {reader.display_name() + ": query set '" + name + "' exists; pass ",
                 setting("replace"), " to overwrite it"});
}

unsigned instance_id_base(const GraphReader& reader) {
  const auto value = reader.metadata().get("id_base");
  if (!value) return 0;  // file ids are 0-based; an instance without the key came from 0-based data
  if (*value == "0") return 0;
  if (*value == "1") return 1;
  throw Error(ErrorCode::other,
              {reader.display_name() + ": metadata id_base '" + *value + "' is not 0 or 1; pass ",
               setting("id_base")});
}

// The octile map an instance was built from, as far as a scenario check needs it: its size and
// which cells are vertices. Refuses an instance whose vertices are not the passable cells in
// row-major order (the numbering of build_octile_graph that scenario_queries relies on).
OctileMap instance_map(const GraphReader& reader) {
  const std::string& file = reader.display_name();
  auto dimension = [&](const char* key) -> std::uint32_t {
    const auto value = reader.metadata().get(key);
    const auto parsed = value ? text::to_u64(*value, 0xFFFFFFFFULL) : std::nullopt;
    if (!parsed || *parsed == 0)
      throw Error(ErrorCode::other,
                  {file + ": metadata " + key + " is missing or not a positive integer: ",
                   setting("scenario"),
                   " needs an instance converted from a Moving AI map (convert movingai or "
                   "convert guards)"});
    return static_cast<std::uint32_t>(*parsed);
  };
  OctileMap map;
  map.width = dimension("map.width");
  map.height = dimension("map.height");
  const Section* cell = reader.find(format::SectionKind::vertex_data, "cell");
  if (!cell || cell->entry.row_width != 2 ||
      (cell->type != format::ElementType::u16 && cell->type != format::ElementType::u32))
    throw Error(ErrorCode::other,
                {file + ": no vertex data 'cell' (u16 or u32 x 2): ", setting("scenario"),
                 " needs an instance converted from a Moving AI map"});
  std::vector<std::uint32_t> cells;
  if (cell->type == format::ElementType::u16) {
    const auto v = reader.values<std::uint16_t>(*cell);
    cells.assign(v.begin(), v.end());
  } else {
    const auto v = reader.values<std::uint32_t>(*cell);
    cells.assign(v.begin(), v.end());
  }
  const std::uint64_t cells_in_map = std::uint64_t{map.width} * map.height;
  if (cells_in_map > kMaxOctileCells)
    throw Error(file + ": metadata map.width x map.height is " + std::to_string(map.width) + " x " +
                std::to_string(map.height) + ", more cells than a map may have (" +
                std::to_string(kMaxOctileCells) + ")");
  map.passable.assign(cells_in_map, 0);
  std::uint64_t previous = 0;
  for (std::size_t v = 0; v < cells.size() / 2; ++v) {
    const std::uint32_t x = cells[2 * v], y = cells[2 * v + 1];
    const std::uint64_t index = std::uint64_t{y} * map.width + x;
    if (x >= map.width || y >= map.height || (v > 0 && index <= previous))
      throw Error(file + ": vertex " + std::to_string(v) + " has cell (" + std::to_string(x) +
                  ", " + std::to_string(y) +
                  "): the vertices are not the cells of the map in row-major order");
    map.passable[index] = 1;
    previous = index;
  }
  return map;
}

// Gives views their `view.NAME.queries` key (ViewBinding): so a family's default views, written
// before any query set existed, name the set a user adds, and no view is left without one by
// accident. A converter's intended set (`source.param.view.NAME = OBJ,...@SET`, spec/families/
// road.md §2) keeps a view for that set.
void link_views_to(QuerySetEdit& edit, const GraphReader& reader, const ViewBinding& binding) {
  Metadata& m = edit.metadata;
  const auto views = view_keys(m);
  if (binding.view) {
    bool found = false;
    std::string names;
    for (const auto& v : views) {
      found |= v.name == *binding.view && !v.objectives.empty();
      names += (names.empty() ? "" : ", ") + v.name;
    }
    if (!found)
      throw Error(ErrorCode::not_found, reader.display_name() + ": no view '" + *binding.view +
                                            "' (views: " + (names.empty() ? "none" : names) + ")");
    m.set("view." + *binding.view + ".queries", edit.set.name);
    edit.bound_views = {*binding.view};
    return;
  }
  for (const auto& v : views) {
    if (v.objectives.empty() || !v.query_set.empty()) continue;
    const auto intended = m.get("source.param.view." + v.name);
    const auto at = intended ? intended->rfind('@') : std::string::npos;
    if (at != std::string::npos && intended->substr(at + 1) != edit.set.name) continue;
    m.set("view." + v.name + ".queries", edit.set.name);
    edit.bound_views.push_back(v.name);
  }
}

}  // namespace

QuerySetEdit import_query_set(const GraphReader& reader, const std::string& set,
                              const QueryImportOptions& options, bool replace) {
  check_new_set(reader, set, replace);
  if (options.scenario) {
    if (options.id_base || options.match)
      throw Error(ErrorCode::other, {"a scenario (", setting("scenario"),
                                     ") gives cells, not ids: ", setting("id_base"), " and ",
                                     setting("match"), " do not apply"});
    const auto map = instance_map(reader);
    const auto input = read_text_input(options.file);
    const auto entries = parse_scenario(input.text, input.display_name);
    if (entries.empty()) throw Error(input.display_name + ": no queries");
    check_scenario(entries, input.display_name, map, reader.display_name());
    QuerySetEdit edit{
        without_query_keys(reader.metadata(), set), scenario_queries(entries, map), {}};
    edit.set.name = set;
    const std::string key = "queries." + set + ".";
    edit.metadata.set(key + "source", "import");
    edit.metadata.set(key + "format", "movingai-scen");
    edit.metadata.set(key + "input.name", input.base_name);
    edit.metadata.set(key + "input.size", std::to_string(input.raw_size));
    edit.metadata.set(key + "input.xxh3", input.raw_xxh3);
    link_views_to(edit, reader, options.binding);
    return edit;
  }
  const unsigned id_base = options.id_base ? *options.id_base : instance_id_base(reader);
  InputFile file(options.file);
  const auto& input = file.facts();
  QueryFileOptions parse;
  parse.id_base = id_base;
  parse.vertex_count = reader.vertex_count();
  parse.match = options.match;
  QuerySetEdit edit{without_query_keys(reader.metadata(), set),
                    {set, parse_query_file(file, input.display_name, parse)},
                    {}};
  const std::string key = "queries." + set + ".";
  edit.metadata.set(key + "source", "import");
  edit.metadata.set(key + "input.name", input.base_name);
  edit.metadata.set(key + "input.size", std::to_string(input.raw_size));
  edit.metadata.set(key + "input.xxh3", input.raw_xxh3);
  edit.metadata.set(key + "id_base", std::to_string(id_base));
  if (options.match) edit.metadata.set(key + "match", *options.match);
  link_views_to(edit, reader, options.binding);
  return edit;
}

QuerySetEdit draw_query_set(const GraphReader& reader, const std::string& set,
                            const QueryDrawOptions& options, bool replace) {
  check_new_set(reader, set, replace);
  const std::uint64_t n = reader.vertex_count();
  if (n == 0)
    throw Error(reader.display_name() + ": the graph has no vertices to draw queries from");
  if (n == 1 && !options.allow_same)
    throw Error(ErrorCode::other,
                {reader.display_name() +
                     ": the graph has one vertex, so every query has start = goal; pass ",
                 setting("allow_same")});
  if (options.count < 1 || options.count > kMaxDrawnQueries)
    throw Error("query count " + std::to_string(options.count) + " is not 1 to " +
                std::to_string(kMaxDrawnQueries));
  QuerySetEdit edit{without_query_keys(reader.metadata(), set), {set, {}}, {}};
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
  link_views_to(edit, reader, options.binding);
  return edit;
}

}  // namespace mosb::converters
