#include "mosb/converters/fmi_converter.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "mosb/converters/narrow_column.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"

namespace mosb::converters {

namespace {

using format::kMaxCount;

using namespace text;  // the shared primitives of text_scan.hpp

// A non-negative integer field (count, id, osm id, type, maxspeed).
std::uint64_t parse_unsigned(const std::string& file, std::uint64_t line, const Token& t,
                             const std::string& what, std::uint64_t max = UINT64_MAX) {
  if (!is_digits(t.text))
    fail(file, line, t.column, "expected " + what + ", found " + quoted(t.text));
  const auto value = to_u64(t.text, max);
  if (!value)
    fail(file, line, t.column, what + " " + quoted(t.text) + " exceeds " + std::to_string(max));
  return *value;
}

bool looks_real(std::string_view s) {
  return s.find_first_of(".eE") != std::string_view::npos;
}

double parse_degrees(const std::string& file, std::uint64_t line, const Token& t, const char* what,
                     double limit) {
  const auto value = to_real(t.text);
  if (!value)
    fail(file, line, t.column, std::string("expected the ") + what + ", found " + quoted(t.text));
  if (std::fabs(*value) > limit)
    fail(file, line, t.column,
         std::string(what) + " " + quoted(t.text) + " outside -" +
             std::to_string(static_cast<int>(limit)) + ".." +
             std::to_string(static_cast<int>(limit)));
  return *value;
}

using Elevation = std::variant<std::vector<std::int64_t>, std::vector<double>>;

void add_elevation(const std::string& file, std::uint64_t line, const Token& t, Elevation& column) {
  const auto s = t.text;
  if (!looks_real(s)) {
    const auto value = to_i64(s);
    if (!value) fail(file, line, t.column, "expected the elevation, found " + quoted(s));
    if (auto* ints = std::get_if<std::vector<std::int64_t>>(&column))
      ints->push_back(*value);
    else
      std::get<std::vector<double>>(column).push_back(static_cast<double>(*value));
    return;
  }
  const auto value = to_real(s);
  if (!value) fail(file, line, t.column, "expected the elevation, found " + quoted(s));
  if (auto* ints = std::get_if<std::vector<std::int64_t>>(&column))
    column = std::vector<double>(ints->begin(), ints->end());
  std::get<std::vector<double>>(column).push_back(*value);
}

using CostValues = std::variant<std::vector<std::uint64_t>, std::vector<double>>;

void add_cost(const std::string& file, std::uint64_t line, const Token& t, CostValues& column) {
  const auto s = t.text;
  if (!s.empty() && s[0] == '-') fail(file, line, t.column, "negative cost " + quoted(s));
  if (!looks_real(s)) {
    const auto value = parse_unsigned(file, line, t, "a cost");
    if (auto* ints = std::get_if<std::vector<std::uint64_t>>(&column))
      ints->push_back(value);
    else
      std::get<std::vector<double>>(column).push_back(static_cast<double>(value));
    return;
  }
  const auto value = to_real(s);
  if (!value) fail(file, line, t.column, "expected a cost, found " + quoted(s));
  if (auto* ints = std::get_if<std::vector<std::uint64_t>>(&column))
    column = std::vector<double>(ints->begin(), ints->end());
  std::get<std::vector<double>>(column).push_back(*value);
}

// Skips blank lines and '#' comment lines; false at the end of the text.
bool next_data_line(LineScanner& lines, std::vector<Token>& t) {
  std::string_view line;
  while (lines.next(line)) {
    tokenize(line, t);
    if (!t.empty() && t[0].text[0] != '#') return true;
  }
  return false;
}

}  // namespace

namespace {

FmiGraph parse(LineScanner& lines, std::uint64_t size_hint, const std::string& display_name,
               std::optional<unsigned> cost_count, bool ignore_extra_fields) {
  FmiGraph g;
  std::vector<Token> t;
  const auto end_line = [&] { return std::max<std::uint64_t>(lines.number(), 1); };

  std::uint64_t counts[2] = {0, 0};
  std::uint64_t count_lines[2] = {0, 0};
  const char* count_names[2] = {"the node count", "the edge count"};
  for (int k = 0; k < 2; ++k) {
    if (!next_data_line(lines, t))
      fail(display_name, end_line(), 1, std::string("missing ") + count_names[k]);
    if (t.size() > 1)
      fail(display_name, lines.number(), t[1].column,
           "extra field " + quoted(t[1].text) + " after " + count_names[k]);
    counts[k] = parse_unsigned(display_name, lines.number(), t[0], count_names[k], kMaxCount);
    count_lines[k] = lines.number();
  }
  const std::uint64_t n = counts[0], m = counts[1];
  // The counts are untrusted: reserve no more than the text could hold.
  const std::uint64_t max_lines = size_hint / 8 + 1;
  g.osm_ids.reserve(std::min(n, max_lines));
  g.coords.reserve(2 * std::min(n, max_lines));

  for (std::uint64_t v = 0; v < n; ++v) {
    if (!next_data_line(lines, t))
      fail(display_name, count_lines[0], 1,
           "the header declares " + plural(n, "node") + ", found " + std::to_string(v));
    const auto ln = lines.number();
    if (t.size() < 5)
      fail(display_name, ln, t.back().column + t.back().text.size(),
           "missing field: a node line is 'id osm_id lat lon elevation'");
    const auto id = parse_unsigned(display_name, ln, t[0], "a node id");
    if (id != v)
      fail(display_name, ln, t[0].column,
           "expected node id " + std::to_string(v) + " (ids 0..n-1 in order), found " +
               quoted(t[0].text));
    g.osm_ids.push_back(parse_unsigned(display_name, ln, t[1], "an OSM id"));
    g.coords.push_back(parse_degrees(display_name, ln, t[2], "latitude", 90));
    g.coords.push_back(parse_degrees(display_name, ln, t[3], "longitude", 180));
    add_elevation(display_name, ln, t[4], g.elevation);
  }
  g.vertex_count = n;

  const std::size_t fixed = cost_count ? 2 + *cost_count : 4;
  const std::size_t columns = cost_count ? *cost_count : 1;
  g.costs.assign(columns, CostValues{});
  g.tails.reserve(std::min(m, max_lines));
  g.heads.reserve(std::min(m, max_lines));
  std::size_t fields = 0;  // of every edge line, set by the first one
  std::uint64_t first_edge_line = 0;
  const std::string layout = cost_count
                                 ? "an edge line is 'src trg' and " + plural(*cost_count, "cost")
                                 : std::string("an edge line is 'src trg cost type [maxspeed]'");
  const auto id_range =
      n == 0 ? std::string("(none: the graph has no nodes)") : "0.." + std::to_string(n - 1);
  for (std::uint64_t e = 0; e < m; ++e) {
    if (!next_data_line(lines, t))
      fail(display_name, count_lines[1], 1,
           "the header declares " + plural(m, "edge") + ", found " + std::to_string(e));
    const auto ln = lines.number();
    const auto end_column = t.back().column + t.back().text.size();
    if (t.size() < fixed) fail(display_name, ln, end_column, "missing field: " + layout);
    if (first_edge_line == 0) {
      first_edge_line = ln;
      fields = t.size();
      const std::size_t allowed = cost_count ? (ignore_extra_fields ? fields : fixed) : 5;
      if (fields > allowed)
        fail(display_name, ln, t[allowed].column,
             "extra field " + quoted(t[allowed].text) + ": " + layout);
    } else if (t.size() != fields) {
      const std::string expected =
          "expected " + plural(fields, "field") + " as on line " + std::to_string(first_edge_line);
      if (t.size() < fields) fail(display_name, ln, end_column, "missing field: " + expected);
      fail(display_name, ln, t[fields].column,
           "extra field " + quoted(t[fields].text) + ": " + expected);
    }
    for (int k = 0; k < 2; ++k) {
      const auto id = parse_unsigned(display_name, ln, t[k], "a node id");
      if (id >= n)
        fail(display_name, ln, t[k].column,
             "node id " + quoted(t[k].text) + " outside " + id_range);
      (k == 0 ? g.tails : g.heads).push_back(static_cast<std::uint32_t>(id));
    }
    for (std::size_t j = 0; j < columns; ++j) add_cost(display_name, ln, t[2 + j], g.costs[j]);
    if (!cost_count) {
      g.types.push_back(parse_unsigned(display_name, ln, t[3], "the edge type"));
      if (fields == 5)
        g.maxspeeds.push_back(parse_unsigned(display_name, ln, t[4], "the maxspeed"));
    }
  }
  if (next_data_line(lines, t))
    fail(display_name, lines.number(), t[0].column,
         "the header declares " + plural(m, "edge") + ", found more");
  return g;
}

}  // namespace

FmiGraph parse_fmi(std::string_view text, const std::string& display_name,
                   std::optional<unsigned> cost_count, bool ignore_extra_fields) {
  LineScanner lines(text);
  return parse(lines, text.size(), display_name, cost_count, ignore_extra_fields);
}

FmiGraph parse_fmi(TextSource& source, std::uint64_t size_hint, const std::string& display_name,
                   std::optional<unsigned> cost_count, bool ignore_extra_fields) {
  LineScanner lines(source);
  return parse(lines, size_hint, display_name, cost_count, ignore_extra_fields);
}

std::vector<std::uint32_t> bfs_select(const FmiGraph& graph, std::uint32_t root,
                                      std::uint64_t count, bool undirected,
                                      const std::string& display_name) {
  const std::uint64_t n = graph.vertex_count;
  if (root >= n)
    throw Error(display_name + ": BFS root " + std::to_string(root) +
                " is not a vertex (the graph has " + plural(n, "vertex") + ")");
  if (count == 0) throw Error(display_name + ": the BFS vertex count must be at least 1");
  // Adjacency in file order: a stable counting sort of the arcs by tail (and by head when
  // undirected).
  std::vector<std::uint64_t> offsets(n + 1, 0);
  const std::size_t m = graph.tails.size();
  for (std::size_t a = 0; a < m; ++a) {
    ++offsets[graph.tails[a] + 1];
    if (undirected) ++offsets[graph.heads[a] + 1];
  }
  for (std::uint64_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
  std::vector<std::uint32_t> neighbours(offsets[n]);
  std::vector<std::uint64_t> fill(offsets.begin(), offsets.end() - 1);
  for (std::size_t a = 0; a < m; ++a) {
    neighbours[fill[graph.tails[a]]++] = graph.heads[a];
    if (undirected) neighbours[fill[graph.heads[a]]++] = graph.tails[a];
  }
  std::vector<bool> seen(n, false);
  std::vector<std::uint32_t> order{root};
  seen[root] = true;
  for (std::size_t head = 0; head < order.size() && order.size() < count; ++head) {
    const auto v = order[head];
    for (auto i = offsets[v]; i < offsets[v + 1] && order.size() < count; ++i) {
      const auto w = neighbours[i];
      if (seen[w]) continue;
      seen[w] = true;
      order.push_back(w);
    }
  }
  if (order.size() < count)
    throw Error(ErrorCode::other,
                {display_name + ": BFS from vertex " + std::to_string(root) + " reaches only " +
                     plural(order.size(), "vertex") + ", ",
                 setting("extract_bfs.count"), " asks for " + std::to_string(count)});
  std::sort(order.begin(), order.end());
  return order;
}

FmiGraph induced_subgraph(const FmiGraph& graph, const std::vector<std::uint32_t>& selected) {
  constexpr auto kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> new_id(graph.vertex_count, kNone);
  for (std::size_t i = 0; i < selected.size(); ++i)
    new_id[selected[i]] = static_cast<std::uint32_t>(i);
  FmiGraph out;
  out.vertex_count = selected.size();
  for (auto v : selected) {
    out.osm_ids.push_back(graph.osm_ids[v]);
    out.coords.push_back(graph.coords[2 * std::size_t{v}]);
    out.coords.push_back(graph.coords[2 * std::size_t{v} + 1]);
  }
  out.elevation = std::visit(
      [&](const auto& all) -> Elevation {
        std::decay_t<decltype(all)> kept;
        for (auto v : selected) kept.push_back(all[v]);
        return kept;
      },
      graph.elevation);
  std::vector<std::size_t> arcs;
  for (std::size_t a = 0; a < graph.tails.size(); ++a)
    if (new_id[graph.tails[a]] != kNone && new_id[graph.heads[a]] != kNone) arcs.push_back(a);
  for (auto a : arcs) {
    out.tails.push_back(new_id[graph.tails[a]]);
    out.heads.push_back(new_id[graph.heads[a]]);
    if (!graph.types.empty()) out.types.push_back(graph.types[a]);
    if (!graph.maxspeeds.empty()) out.maxspeeds.push_back(graph.maxspeeds[a]);
  }
  for (const auto& column : graph.costs)
    out.costs.push_back(std::visit(
        [&](const auto& all) -> CostValues {
          std::decay_t<decltype(all)> kept;
          for (auto a : arcs) kept.push_back(all[a]);
          return kept;
        },
        column));
  return out;
}

const std::vector<std::string>& ger10_objective_names() {
  static const std::vector<std::string> names = {
      "distance",    "time",      "ascent", "large_roads", "medium_roads",
      "small_roads", "gas_price", "energy", "unit",        "quietness"};
  return names;
}

namespace {

DataColumn unsigned_column(std::string name, const std::vector<std::uint64_t>& values) {
  return narrowest_column<std::uint8_t, std::uint16_t, std::uint32_t, std::uint64_t>(
      std::move(name), 1, values);
}

DataColumn elevation_column(const Elevation& elevation) {
  if (const auto* reals = std::get_if<std::vector<double>>(&elevation))
    return DataColumn::from("elevation", 1, *reals);
  return narrowest_column<std::int32_t, std::int64_t>(
      "elevation", 1, std::get<std::vector<std::int64_t>>(elevation));
}

}  // namespace

GraphInput convert_fmi(const FmiOptions& options) {
  if (options.cost_count && (*options.cost_count == 0 || *options.cost_count > 64))
    throw Error(ErrorCode::other, {"convert fmi: ", setting("cost_count"), " must be 1..64"});
  std::optional<InputFile> file(std::in_place, options.file);
  ReadProgress read(options.progress, {options.file});
  file->count_into(&read);
  const InputFacts input = file->facts();
  if (options.ignore_extra_fields && !options.cost_count)
    throw Error(ErrorCode::other, {"convert fmi: ", setting("ignore_extra_fields"), " needs ",
                                   setting("cost_count")});
  FmiGraph graph = naming_input_on_out_of_memory(input.display_name, [&] {
    return parse_fmi(*file, file->size_hint(), input.display_name, options.cost_count,
                     options.ignore_extra_fields);
  });
  file.reset();  // unmapped
  const std::size_t d = graph.costs.size();
  if (!options.objectives.empty() && options.objectives.size() != d)
    throw Error("convert fmi: " + plural(options.objectives.size(), "objective name") + " given, " +
                input.display_name + " has " + plural(d, "cost column"));

  std::vector<std::uint32_t> original_ids;
  if (options.extract_bfs) {
    const auto& bfs = *options.extract_bfs;
    original_ids = bfs_select(graph, bfs.root, bfs.count, bfs.undirected, input.display_name);
    graph = induced_subgraph(graph, original_ids);
  }

  GraphInput out;
  out.vertex_count = graph.vertex_count;
  out.tails = std::move(graph.tails);
  out.heads = std::move(graph.heads);
  for (std::size_t j = 0; j < d; ++j) {
    CostColumn c;
    if (!options.objectives.empty()) {
      c.name = options.objectives[j].name;
      c.unit = options.objectives[j].unit;
    } else if (d == 10) {
      c.name = ger10_objective_names()[j];
    } else {
      c.name = "c" + std::to_string(j + 1);
    }
    c.values = std::move(graph.costs[j]);
    out.costs.push_back(std::move(c));
  }
  out.vertex_data.push_back(DataColumn::from("coords", 2, graph.coords));
  out.vertex_data.push_back(elevation_column(graph.elevation));
  out.vertex_data.push_back(DataColumn::from("osm_id", 1, graph.osm_ids));
  if (options.extract_bfs)
    out.vertex_data.push_back(DataColumn::from("original_id", 1, original_ids));
  if (!graph.types.empty() || (!options.cost_count && out.tails.empty()))
    out.arc_data.push_back(unsigned_column("type", graph.types));
  if (!graph.maxspeeds.empty())
    out.arc_data.push_back(unsigned_column("maxspeed", graph.maxspeeds));

  auto& m = out.metadata;
  record_input(m, 0, input);
  m.set("benchmark", options.name
                         ? *options.name
                         : benchmark_name_from(input.base_name, {".txt", ".fmi", ".graph"}));
  m.set("family", "road");
  m.set("id_base", "0");
  m.set("coords.order", "lat,lon");
  m.set("coords.unit", "degree");
  m.set("source.command", "convert fmi");
  if (options.cost_count) m.set("source.param.costs", std::to_string(*options.cost_count));
  if (options.ignore_extra_fields) m.set("source.param.ignore_extra_fields", "1");
  if (!options.objectives.empty())
    m.set("source.param.objectives", objective_list(options.objectives));
  if (options.name) m.set("source.param.name", *options.name);
  if (options.extract_bfs) {
    m.set("source.param.extract_bfs_root", std::to_string(options.extract_bfs->root));
    m.set("source.param.extract_bfs_count", std::to_string(options.extract_bfs->count));
    m.set("source.param.bfs_undirected", options.extract_bfs->undirected ? "1" : "0");
  }
  return out;
}

}  // namespace mosb::converters
