#include "mosb/converters/guards_converter.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "mosb/atomic_file.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/views.hpp"
#include "octile_steps.hpp"

namespace mosb::converters {

namespace {

using namespace text;  // the shared primitives of text_scan.hpp

constexpr std::uint64_t kMaxRadiusMilli = 1'000'000'000;  // 10^6 cells: beyond any map that fits

// `D` or `D.DDD` (at most 3 decimals), in thousandths.
bool parse_radius(std::string_view s, std::uint64_t& milli) {
  const auto dot = s.find('.');
  const auto whole = s.substr(0, dot);
  std::string_view fraction =
      dot == std::string_view::npos ? std::string_view() : s.substr(dot + 1);
  if (dot != std::string_view::npos && (fraction.empty() || fraction.size() > 3)) return false;
  const auto w = to_u64(whole, kMaxRadiusMilli / 1000);
  if (!w) return false;
  std::uint64_t f = 0;
  if (!fraction.empty()) {
    const auto digits = to_u64(fraction, 999);
    if (!digits) return false;
    f = *digits;
  }
  for (auto k = fraction.size(); k < 3; ++k) f *= 10;
  milli = *w * 1000 + f;
  return milli <= kMaxRadiusMilli;
}

}  // namespace

std::vector<Guard> parse_guards(std::string_view text_in, const std::string& file,
                                const OctileMap& map) {
  text::LineScanner lines(text_in, text::LineEnd::cr);
  std::string_view line;
  std::vector<Token> t;
  std::vector<Guard> guards;
  while (lines.next(line)) {
    const auto ln = lines.number();
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    text::tokenize(line, t);
    if (t.empty()) continue;
    if (t.size() < 2)
      fail(file, ln, line.size() + 1, "missing field: a guard line is 'x y [radius]'");
    if (t.size() > 3)
      fail(file, ln, t[3].column,
           "extra field " + quoted(t[3].text) + ": a guard line is 'x y [radius]'");
    Guard g;
    g.line = ln;
    const auto x = to_u64(t[0].text, map.width - 1);
    if (!x)
      fail(file, ln, t[0].column,
           "guard x " + quoted(t[0].text) + " is not a column 0.." + std::to_string(map.width - 1));
    const auto y = to_u64(t[1].text, map.height - 1);
    if (!y)
      fail(file, ln, t[1].column,
           "guard y " + quoted(t[1].text) + " is not a row 0.." + std::to_string(map.height - 1));
    g.x = static_cast<std::uint32_t>(*x);
    g.y = static_cast<std::uint32_t>(*y);
    if (!map.is_passable(g.x, g.y))
      fail(file, ln, t[0].column,
           "guard on the blocked cell (" + std::to_string(*x) + ", " + std::to_string(*y) + ")");
    if (t.size() == 3) {
      std::uint64_t milli = 0;
      if (!parse_radius(t[2].text, milli))
        fail(file, ln, t[2].column,
             "expected a radius from 0 to 1000000 with at most 3 decimals, found " +
                 quoted(t[2].text));
      g.radius_milli = milli;
    }
    guards.push_back(g);
  }
  return guards;
}

std::vector<std::uint64_t> parse_exposure(std::string_view text_in, const std::string& file,
                                          const OctileMap& map) {
  text::LineScanner lines(text_in, text::LineEnd::cr);
  std::string_view line;
  std::vector<Token> t;
  std::vector<std::uint64_t> exposure(map.passable.size(), 0);
  for (std::uint32_t y = 0; y < map.height; ++y) {
    if (!lines.next(line))
      fail(file, lines.number() + 1, 1,
           "missing row " + std::to_string(y + 1) + " of " + std::to_string(map.height));
    const auto ln = lines.number();
    text::tokenize(line, t);
    if (t.size() < map.width)
      fail(file, ln, line.size() + 1,
           "row " + std::to_string(y + 1) + " has " + std::to_string(t.size()) +
               " values, the map is " + std::to_string(map.width) + " wide");
    if (t.size() > map.width)
      fail(file, ln, t[map.width].column,
           "extra value " + quoted(t[map.width].text) + ": the map is " +
               std::to_string(map.width) + " wide");
    for (std::uint32_t x = 0; x < map.width; ++x) {
      if (!map.is_passable(x, y)) continue;  // blocked cells may hold anything
      const auto value = to_u64(t[x].text);
      if (!value)
        fail(file, ln, t[x].column,
             "expected a non-negative integer exposure, found " + quoted(t[x].text));
      exposure[std::size_t{y} * map.width + x] = *value;
    }
  }
  while (lines.next(line)) {
    text::tokenize(line, t);
    if (!t.empty())
      fail(file, lines.number(), 1,
           "text after the " + std::to_string(map.height) + " rows of the grid");
  }
  return exposure;
}

bool line_of_sight(const OctileMap& map, std::uint32_t x0, std::uint32_t y0, std::uint32_t x1,
                   std::uint32_t y1) {
  // Walks the cells the segment enters, in order: the next boundary crossed is the vertical one
  // when (ix + 1/2) / dx < (iy + 1/2) / dy; at equality the segment passes through a grid corner
  // and touches all four cells around it, so both side cells are checked too.
  const std::int64_t dx = x1 >= x0 ? std::int64_t{x1} - x0 : std::int64_t{x0} - x1;
  const std::int64_t dy = y1 >= y0 ? std::int64_t{y1} - y0 : std::int64_t{y0} - y1;
  const std::int64_t sx = x1 >= x0 ? 1 : -1, sy = y1 >= y0 ? 1 : -1;
  std::int64_t x = x0, y = y0;
  auto open = [&](std::int64_t cx, std::int64_t cy) {
    return map.is_passable(static_cast<std::uint32_t>(cx), static_cast<std::uint32_t>(cy));
  };
  if (!open(x, y)) return false;
  for (std::int64_t ix = 0, iy = 0; ix < dx || iy < dy;) {
    const std::int64_t decision = (1 + 2 * ix) * dy - (1 + 2 * iy) * dx;
    if (decision == 0) {
      if (!open(x + sx, y) || !open(x, y + sy)) return false;
      x += sx, y += sy, ++ix, ++iy;
    } else if (decision < 0) {
      x += sx, ++ix;
    } else {
      y += sy, ++iy;
    }
    if (!open(x, y)) return false;
  }
  return true;
}

std::vector<std::uint64_t> compute_exposure(const OctileMap& map,
                                            const std::vector<Guard>& guards) {
  std::vector<std::uint64_t> exposure(map.passable.size(), 0);
  for (const auto& g : guards) {
    std::uint32_t x_lo = 0, y_lo = 0, x_hi = map.width - 1, y_hi = map.height - 1;
    if (g.radius_milli) {
      const auto reach = static_cast<std::uint32_t>(*g.radius_milli / 1000);
      x_lo = g.x - std::min(g.x, reach), y_lo = g.y - std::min(g.y, reach);
      x_hi = g.x + std::min(map.width - 1 - g.x, reach),
      y_hi = g.y + std::min(map.height - 1 - g.y, reach);
    }
    for (std::uint32_t y = y_lo; y <= y_hi; ++y) {
      for (std::uint32_t x = x_lo; x <= x_hi; ++x) {
        if (!map.is_passable(x, y)) continue;
        if (g.radius_milli) {
          // Exact: dx^2 + dy^2 <= (R/1000)^2  <=>  10^6 (dx^2 + dy^2) <= R^2 (both below 2^63).
          const std::uint64_t dx = x > g.x ? x - g.x : g.x - x, dy = y > g.y ? y - g.y : g.y - y;
          if (1'000'000 * (dx * dx + dy * dy) > *g.radius_milli * *g.radius_milli) continue;
        }
        if (line_of_sight(map, g.x, g.y, x, y)) ++exposure[std::size_t{y} * map.width + x];
      }
    }
  }
  return exposure;
}

std::string format_exposure(const OctileMap& map, const std::vector<std::uint64_t>& exposure) {
  std::string out;
  for (std::uint32_t y = 0; y < map.height; ++y) {
    for (std::uint32_t x = 0; x < map.width; ++x) {
      if (x) out += ' ';
      out += std::to_string(exposure[std::size_t{y} * map.width + x]);
    }
    out += '\n';
  }
  return out;
}

StreamedGraph build_guards_graph(const OctileMap& map, const std::vector<std::uint64_t>& exposure) {
  auto g = build_octile_graph(
      map, CellObjective{"exposure", "guards",
                         std::make_shared<const std::vector<std::uint64_t>>(exposure)});
  // The paper's name; no intended query set (the paper samples 100 pairs: `queries generate`
  // makes the first set added the view's).
  add_views(g, {{"Games-GUARDS_2", {"length", "exposure"}, ""}});
  return g;
}

GuardsResult convert_guards(const GuardsOptions& o) {
  if (o.exposure_file.has_value() == o.guards_file.has_value())
    throw Error(ErrorCode::other, {"convert guards: give exactly one of ", setting("exposure_file"),
                                   " and ", setting("guards_file")});
  GuardsResult r;
  Metadata inputs;
  auto map = octile::read_map(o.map_file, o.terrain, inputs, 0);
  const auto cells_input = read_text_input(o.exposure_file ? *o.exposure_file : *o.guards_file);
  record_input(inputs, 1, cells_input);
  std::string guard_cells;  // map.guards: where the guards stand, for plots (games.md §5)
  if (o.exposure_file) {
    r.exposure = parse_exposure(cells_input.text, cells_input.display_name, map.map);
  } else {
    const auto guards = parse_guards(cells_input.text, cells_input.display_name, map.map);
    r.exposure = compute_exposure(map.map, guards);
    for (const auto& g : guards)
      guard_cells +=
          (guard_cells.empty() ? "" : ";") + std::to_string(g.x) + "," + std::to_string(g.y);
  }
  r.graph = build_guards_graph(map.map, r.exposure);
  if (o.exposure_file) r.graph.costs[1].unit = "";
  if (o.scen_file) octile::add_scenario(r.graph, *o.scen_file, map, inputs, 2);
  octile::set_metadata(r.graph.metadata, inputs, map, o.name, "convert guards", o.terrain);
  r.graph.metadata.set("source.param.exposure", o.exposure_file ? "file" : "guards");
  if (!guard_cells.empty()) r.graph.metadata.set("map.guards", guard_cells);
  r.map = std::move(map.map);
  return r;
}

}  // namespace mosb::converters
