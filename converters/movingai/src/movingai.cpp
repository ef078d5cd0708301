#include "mosb/converters/movingai.hpp"

#include <algorithm>
#include <optional>

#include "mosb/converters/narrow_column.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/views.hpp"
#include "octile_steps.hpp"

namespace mosb::converters {

namespace {

using namespace text;  // the shared primitives of text_scan.hpp

// 1 passable, 0 blocked, nullopt for a character the format does not define.
std::optional<std::uint8_t> terrain(char c, const TerrainRules& rules) {
  switch (c) {
    case '.':
    case 'G':
      return 1;
    case '@':
    case 'O':
    case 'T':
      return 0;
    case 'S':
      return rules.swamp_passable ? 1 : 0;
    case 'W':
      return rules.water_passable ? 1 : 0;
    default:
      return std::nullopt;
  }
}

std::uint32_t parse_dimension(const std::string& file, std::uint64_t ln, const Token& t,
                              const char* what) {
  const auto value = to_u64(t.text, 0xFFFFFFFFULL);
  if (!value || *value == 0)
    fail(file, ln, t.column,
         std::string("expected the map ") + what + " (an integer from 1 to 4294967295), found " +
             quoted(t.text));
  return static_cast<std::uint32_t>(*value);
}

}  // namespace

OctileMap parse_octile_map(std::string_view text_in, const std::string& file,
                           const TerrainRules& rules) {
  text::LineScanner lines(text_in, text::LineEnd::cr);
  std::string_view line;
  std::vector<Token> t;
  OctileMap map;
  std::uint64_t header_line = 0;
  bool have_type = false;
  // The header: `type octile`, then `height H` and `width W` (either order), then `map`.
  while (true) {
    if (!lines.next(line))
      fail(
          file, lines.number() + 1, 1,
          have_type ? "missing 'map' line after the header" : "empty file: expected 'type octile'");
    const auto ln = lines.number();
    text::tokenize(line, t);
    if (!have_type) {
      if (t.empty() || t[0].text != "type")
        fail(file, ln, t.empty() ? 1 : t[0].column, "expected 'type octile'");
      if (t.size() < 2 || t[1].text != "octile")
        fail(file, ln, t.size() < 2 ? line.size() + 1 : t[1].column,
             "expected 'type octile' (only octile maps are supported)");
      if (t.size() > 2) fail(file, ln, t[2].column, "extra field " + quoted(t[2].text));
      have_type = true;
      continue;
    }
    if (t.empty()) fail(file, ln, 1, "expected 'height H', 'width W' or 'map'");
    if (t[0].text == "map") {
      if (t.size() > 1) fail(file, ln, t[1].column, "extra field " + quoted(t[1].text));
      if (map.height == 0) fail(file, ln, 1, "'map' before the 'height H' line");
      if (map.width == 0) fail(file, ln, 1, "'map' before the 'width W' line");
      break;
    }
    const bool is_height = t[0].text == "height";
    if (!is_height && t[0].text != "width")
      fail(file, ln, t[0].column,
           "expected 'height H', 'width W' or 'map', found " + quoted(t[0].text));
    auto& field = is_height ? map.height : map.width;
    const char* what = is_height ? "height" : "width";
    if (field != 0) fail(file, ln, t[0].column, std::string("second '") + what + "' line");
    if (t.size() < 2) fail(file, ln, line.size() + 1, std::string("missing the map ") + what);
    if (t.size() > 2) fail(file, ln, t[2].column, "extra field " + quoted(t[2].text));
    field = parse_dimension(file, ln, t[1], what);
    header_line = ln;
  }
  const auto cells = std::uint64_t{map.width} * map.height;
  // Untrusted header: the rows must be in the text before anything that large is allocated.
  if (cells > kMaxOctileCells || cells > text_in.size())
    fail(file, header_line, 1,
         "a " + std::to_string(map.width) + " x " + std::to_string(map.height) +
             " map cannot be held in this " + std::to_string(text_in.size()) + "-byte file");
  map.passable.resize(cells);
  for (std::uint32_t y = 0; y < map.height; ++y) {
    if (!lines.next(line))
      fail(file, lines.number() + 1, 1,
           "missing row " + std::to_string(y + 1) + " of " + std::to_string(map.height));
    const auto ln = lines.number();
    const auto n = std::min<std::size_t>(line.size(), map.width);
    for (std::size_t x = 0; x < n; ++x) {
      const auto flag = terrain(line[x], rules);
      if (!flag) fail(file, ln, x + 1, "unknown terrain character " + quoted(line.substr(x, 1)));
      map.passable[std::size_t{y} * map.width + x] = *flag;
    }
    if (line.size() != map.width)
      fail(file, ln, n + 1,
           "row " + std::to_string(y + 1) + " has " + std::to_string(line.size()) +
               " cells, the map is " + std::to_string(map.width) + " wide");
  }
  while (lines.next(line))
    if (!line.empty())
      fail(file, lines.number(), 1,
           "text after the " + std::to_string(map.height) + " rows of the map");
  return map;
}

std::vector<ScenarioEntry> parse_scenario(std::string_view text_in, const std::string& file) {
  text::LineScanner lines(text_in, text::LineEnd::cr);
  std::string_view line;
  std::vector<Token> words, fields;
  bool have_version = false;
  std::vector<ScenarioEntry> entries;
  while (lines.next(line)) {
    const auto ln = lines.number();
    text::tokenize(line, words);
    if (words.empty()) continue;
    if (!have_version) {
      if (words[0].text != "version") fail(file, ln, words[0].column, "expected 'version 1'");
      if (words.size() < 2 || (words[1].text != "1" && words[1].text != "1.0"))
        fail(file, ln, words.size() < 2 ? line.size() + 1 : words[1].column,
             "expected 'version 1' (only version 1 scenarios are supported)");
      if (words.size() > 2) fail(file, ln, words[2].column, "extra field " + quoted(words[2].text));
      have_version = true;
      continue;
    }
    // Fields are tab-separated (a map path may hold blanks); a row without tabs is split on blanks.
    if (line.find('\t') != std::string_view::npos) {
      fields.clear();
      std::size_t start = 0;
      while (true) {
        const auto tab = line.find('\t', start);
        const auto end = tab == std::string_view::npos ? line.size() : tab;
        fields.push_back({line.substr(start, end - start), start + 1});
        if (tab == std::string_view::npos) break;
        start = tab + 1;
      }
      while (fields.size() > 9 && fields.back().text.empty()) fields.pop_back();  // trailing tabs
    } else {
      fields = words;
    }
    if (fields.size() < 9)
      fail(file, ln, line.size() + 1,
           "missing field: a row is 'bucket map width height sx sy gx gy optimal'");
    if (fields.size() > 9)
      fail(file, ln, fields[9].column, "extra field " + quoted(fields[9].text));
    ScenarioEntry e;
    e.line = ln;
    for (std::size_t k = 0; k < 9; ++k) e.columns[k] = static_cast<std::uint32_t>(fields[k].column);
    const auto bucket = to_u64(fields[0].text);
    if (!bucket)
      fail(file, ln, fields[0].column, "expected a bucket number, found " + quoted(fields[0].text));
    e.bucket = *bucket;
    if (fields[1].text.empty()) fail(file, ln, fields[1].column, "empty map name");
    e.map = std::string(fields[1].text);
    std::uint32_t* targets[] = {&e.map_width, &e.map_height, &e.start_x,
                                &e.start_y,   &e.goal_x,     &e.goal_y};
    const char* names[] = {"map width", "map height", "start x", "start y", "goal x", "goal y"};
    for (std::size_t k = 0; k < 6; ++k) {
      const auto value = to_u64(fields[2 + k].text, 0xFFFFFFFFULL);
      if (!value)
        fail(file, ln, fields[2 + k].column,
             std::string("expected the ") + names[k] + ", found " + quoted(fields[2 + k].text));
      *targets[k] = static_cast<std::uint32_t>(*value);
    }
    const auto opt = fields[8].text;
    const auto optimal = text::to_real(opt);
    if (!optimal || opt[0] < '0' || opt[0] > '9')
      fail(file, ln, fields[8].column,
           "expected the optimal length (a non-negative number), found " + quoted(opt));
    e.optimal = *optimal;
    entries.push_back(std::move(e));
  }
  if (!have_version)
    fail(file, std::max<std::uint64_t>(lines.number(), 1), 1, "empty file: expected 'version 1'");
  return entries;
}

void check_scenario(const std::vector<ScenarioEntry>& entries, const std::string& file,
                    const OctileMap& map, const std::string& map_name) {
  for (const auto& e : entries) {
    if (e.map_width != map.width || e.map_height != map.height)
      fail(file, e.line, e.columns[e.map_width != map.width ? 2 : 3],
           "the row gives a " + std::to_string(e.map_width) + " x " + std::to_string(e.map_height) +
               " map, " + map_name + " is " + std::to_string(map.width) + " x " +
               std::to_string(map.height));
    const struct {
      std::uint32_t x, y;
      std::size_t field;
      const char* what;
    } ends[] = {{e.start_x, e.start_y, 4, "start"}, {e.goal_x, e.goal_y, 6, "goal"}};
    for (const auto& end : ends) {
      const std::string cell = "(" + std::to_string(end.x) + ", " + std::to_string(end.y) + ")";
      if (end.x >= map.width || end.y >= map.height)
        fail(file, e.line, e.columns[end.x >= map.width ? end.field : end.field + 1],
             std::string("the ") + end.what + " cell " + cell + " lies outside " + map_name);
      if (!map.is_passable(end.x, end.y))
        fail(file, e.line, e.columns[end.field],
             std::string("the ") + end.what + " cell " + cell + " is blocked in " + map_name);
    }
  }
}

namespace {

// The arcs of an octile map in ascending tail order, replayable: each pass walks the map again, so
// no arc list is ever held (spec/families/games.md §2 states the memory bound).
struct OctileArcs {
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  OctileMap map;
  std::vector<std::uint32_t> id;  // vertex of each cell, kNone when blocked

  std::size_t at(std::int64_t x, std::int64_t y) const {
    return static_cast<std::size_t>(y) * map.width + static_cast<std::size_t>(x);
  }
  // f(tail, head, diagonal, x, y, hx, hy) per arc. Neighbours in row-major order of the 3x3
  // block, so each tail's heads are increasing.
  template <class F>
  void for_each(F&& f) const {
    auto inside = [&](std::int64_t x, std::int64_t y) {
      return x >= 0 && y >= 0 && x < map.width && y < map.height;
    };
    for (std::uint32_t y = 0; y < map.height; ++y)
      for (std::uint32_t x = 0; x < map.width; ++x) {
        const auto tail = id[at(x, y)];
        if (tail == kNone) continue;
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dx = -1; dx <= 1; ++dx) {
            const std::int64_t hx = std::int64_t{x} + dx, hy = std::int64_t{y} + dy;
            if ((dx == 0 && dy == 0) || !inside(hx, hy) || !map.passable[at(hx, hy)]) continue;
            const bool diagonal = dx != 0 && dy != 0;
            if (diagonal && (!map.passable[at(hx, y)] || !map.passable[at(x, hy)])) continue;
            f(tail, id[at(hx, hy)], diagonal, std::int64_t{x}, std::int64_t{y}, hx, hy);
          }
      }
  }
};

}  // namespace

StreamedGraph build_octile_graph(const OctileMap& map,
                                 const std::optional<CellObjective>& cell_objective) {
  auto arcs = std::make_shared<OctileArcs>();
  arcs->map = map;
  arcs->id.assign(map.passable.size(), OctileArcs::kNone);
  std::vector<std::uint32_t> cells;  // (x, y) per vertex
  std::uint32_t n = 0;
  for (std::uint32_t y = 0; y < map.height; ++y)
    for (std::uint32_t x = 0; x < map.width; ++x)
      if (map.is_passable(x, y)) {
        arcs->id[std::size_t{y} * map.width + x] = n++;
        cells.insert(cells.end(), {x, y});
      }
  StreamedGraph g;
  g.vertex_count = n;
  arcs->for_each([&](auto...) { ++g.arc_count; });
  g.replay_arcs = [arcs](const StreamedGraph::ArcSink& sink) {
    arcs->for_each([&](std::uint32_t tail, std::uint32_t head, auto...) { sink(tail, head); });
  };
  g.costs.push_back({"length", "0.1 cell", [arcs](const StreamedGraph::CostSink& sink) {
                       arcs->for_each([&](std::uint32_t, std::uint32_t, bool diagonal, auto...) {
                         sink(diagonal ? 14 : 10);
                       });
                     }});
  if (cell_objective) {
    auto values = cell_objective->values;
    g.costs.push_back({cell_objective->name, cell_objective->unit,
                       [arcs, values](const StreamedGraph::CostSink& sink) {
                         const auto& v = *values;
                         arcs->for_each([&](std::uint32_t, std::uint32_t, bool diagonal,
                                            std::int64_t x, std::int64_t y, std::int64_t hx,
                                            std::int64_t hy) {
                           auto e = v[arcs->at(hx, hy)];
                           if (diagonal) e = std::max({e, v[arcs->at(hx, y)], v[arcs->at(x, hy)]});
                           sink(e);
                         });
                       }});
  }
  g.vertex_data.push_back(narrowest_column<std::uint16_t, std::uint32_t>("cell", 2, cells));
  g.metadata.set("map.width", std::to_string(map.width));
  g.metadata.set("map.height", std::to_string(map.height));
  return g;
}

QuerySet scenario_queries(const std::vector<ScenarioEntry>& entries, const OctileMap& map) {
  std::vector<std::uint32_t> id(map.passable.size(), 0);
  std::uint32_t n = 0;
  for (std::size_t c = 0; c < id.size(); ++c)
    if (map.passable[c]) id[c] = n++;
  QuerySet scen{"scen", {}, QueryReference{"length", "movingai-optimal", {}}};
  for (const auto& e : entries) {
    scen.pairs.push_back({id[std::size_t{e.start_y} * map.width + e.start_x],
                          id[std::size_t{e.goal_y} * map.width + e.goal_x]});
    scen.reference->values.push_back(e.optimal);
  }
  return scen;
}

namespace octile {

MapInput read_map(const std::string& path, const TerrainRules& terrain, Metadata& inputs,
                  std::size_t index) {
  const auto input = read_text_input(path);
  record_input(inputs, index, input);
  MapInput r{parse_octile_map(input.text, input.display_name, terrain), input.display_name,
             input.base_name};
  if (std::find(r.map.passable.begin(), r.map.passable.end(), 1) == r.map.passable.end())
    throw Error(input.display_name + ": the map has no passable cell (with swamp " +
                (terrain.swamp_passable ? "passable" : "blocked") + ", water " +
                (terrain.water_passable ? "passable" : "blocked") +
                "): the instance would have no vertex");
  return r;
}

void add_scenario(StreamedGraph& graph, const std::string& path, const MapInput& map,
                  Metadata& inputs, std::size_t index) {
  const auto input = read_text_input(path);
  record_input(inputs, index, input);
  const auto entries = parse_scenario(input.text, input.display_name);
  check_scenario(entries, input.display_name, map.map, map.display_name);
  graph.queries.push_back(scenario_queries(entries, map.map));
}

void set_metadata(Metadata& m, const Metadata& inputs, const MapInput& map,
                  const std::optional<std::string>& name, const char* command,
                  const TerrainRules& terrain) {
  for (const auto& [key, value] : inputs.entries()) m.set(key, value);
  m.set("benchmark", name ? *name : benchmark_name_from(map.base_name, {".map"}));
  m.set("family", "games");
  m.set("id_base", "0");
  m.set("source.command", command);
  m.set("source.param.swamp", terrain.swamp_passable ? "passable" : "blocked");
  m.set("source.param.water", terrain.water_passable ? "passable" : "blocked");
  if (name) m.set("source.param.name", *name);
}

}  // namespace octile

StreamedGraph convert_movingai(const MovingaiOptions& o) {
  Metadata inputs;
  const auto map = octile::read_map(o.map_file, o.terrain, inputs, 0);
  auto graph = build_octile_graph(map.map);
  if (o.scen_file) octile::add_scenario(graph, *o.scen_file, map, inputs, 1);
  octile::set_metadata(graph.metadata, inputs, map, o.name, "convert movingai", o.terrain);
  // The suite's default view: the one objective on the scenario's queries (spec/families/games.md
  // §6); without --scen, `queries import --scen --set scen` completes it.
  add_views(graph, {{"length", {"length"}, "scen"}});
  return graph;
}

}  // namespace mosb::converters
