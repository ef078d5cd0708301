#include "mosb/report/plots.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <tuple>

#include "mosb/report/svg.hpp"

using namespace mosb::plots;

namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The contents of every <text> element, in document order.
std::vector<std::string> texts(const std::string& doc) {
  std::vector<std::string> out;
  for (auto at = doc.find("<text"); at != std::string::npos; at = doc.find("<text", at + 1)) {
    const auto open = doc.find('>', at) + 1;
    out.push_back(doc.substr(open, doc.find("</text>", open) - open));
  }
  return out;
}

bool has(const std::string& doc, const std::string& what) {
  return doc.find(what) != std::string::npos;
}

// The fill of the legend swatch (the <rect> just before the text `label`).
std::string swatch_of(const std::string& doc, const std::string& label) {
  const auto text = doc.find(">" + label + "<");
  if (text == std::string::npos) return "";
  const auto rect = doc.rfind("<rect", text);
  const auto fill = doc.find("fill=\"", rect) + 6;
  return doc.substr(fill, doc.find('"', fill) - fill);
}

FrontPlot small_front() {
  FrontPlot p;
  p.title = "q";
  p.x_label = "c1";
  p.y_label = "c2";
  p.reference = {{10, 40}, {20, 20}, {40, 10}};
  p.solution = {{10, 40}, {21, 21}, {40, 10}};
  return p;
}

}  // namespace

TEST_CASE("svg text is escaped and numbers are short and deterministic") {
  CHECK(Svg::escape("a<b & \"c\"") == "a&lt;b &amp; &quot;c&quot;");
  CHECK(Svg::number(1.5) == "1.5");
  CHECK(Svg::number(2.0) == "2");
  CHECK(Svg::number(-0.001) == "0");
  Svg svg(10, 20);
  svg.text(1, 2, "x<y");
  const auto doc = svg.str();
  CHECK(doc.find("x&lt;y") != std::string::npos);
  CHECK(doc.find("width=\"10\" height=\"20\"") != std::string::npos);
  CHECK(doc.substr(doc.size() - 7) == "</svg>\n");
}

TEST_CASE("nice_ticks are 1-2-5 steps covering the range") {
  CHECK(nice_ticks(0, 10) == std::vector<double>{0, 2, 4, 6, 8, 10});
  CHECK(nice_ticks(0, 1, 5) == std::vector<double>{0, 0.2, 0.4, 0.6000000000000001, 0.8, 1});
  const auto t = nice_ticks(13, 987);
  CHECK(t.front() >= 13);
  CHECK(t.back() <= 987);
  CHECK(t.size() >= 4);
}

// Issue 36 §2: values up to the largest double (a float objective holding DBL_MAX) give axes in a
// bounded number of steps, with finite ticks.
TEST_CASE("nice_ticks: any finite range, in a bounded number of steps") {
  constexpr double kMax = std::numeric_limits<double>::max();
  CHECK(nice_ticks(-kMax, kMax) == std::vector<double>{-1e308, 0, 1e308});
  CHECK(nice_ticks(0, kMax) == std::vector<double>{0, 5e307, 1e308, 1.5e308});
  // Too narrow for its magnitude to step through: its ends.
  const double lo = 1e300, hi = std::nextafter(std::nextafter(lo, kMax), kMax);
  CHECK(nice_ticks(lo, hi) == std::vector<double>{lo, hi});
  CHECK(nice_ticks(0, 5e-324).size() <= 25);
}

TEST_CASE("front plot of values up to the largest double: finite ticks, points on the plot") {
  constexpr double kMax = std::numeric_limits<double>::max();
  FrontPlot p = small_front();
  p.reference = {{kMax, 2}, {2, kMax}};
  p.solution = {{kMax, kMax}, {0, 0}};
  p.epsilon = 0.5;  // (1 + ε) q past the largest double: the box ends at it
  const auto doc = plot_front(p);
  for (const auto& t : texts(doc)) {
    CHECK(t.find("inf") == std::string::npos);
    CHECK(t.find("nan") == std::string::npos);
  }
  CHECK(has(doc, ">1.5e+308<"));
  CHECK(!has(doc, "width=\"-"));
  CHECK(!has(doc, "height=\"-"));
  LinePlot lines;
  lines.title = "runtimes";
  lines.y_log = true;
  lines.series = {{"a", {{1, kMax}, {2, 5e-324}, {3, 1}}}};
  const auto log_doc = plot_lines(lines);
  CHECK(has(log_doc, ">1e-307<"));  // the lowest decade a log axis has
  for (const auto& t : texts(log_doc)) CHECK(t.find("inf") == std::string::npos);
  CHECK(count(log_doc, "<text") < 40);  // at most a dozen decades labelled
}

TEST_CASE("front plot draws every vector, the epsilon boxes and a legend") {
  FrontPlot p;
  p.title = "q1";
  p.x_label = "length";
  p.y_label = "exposure";
  p.reference = {{1, 10}, {3, 7}, {5, 5}, {10, 1}};
  p.solution = {{1.05, 10.2}, {5, 5.1}, {10, 1}};
  p.epsilon = 0.1;
  const auto doc = plot_front(p);
  CHECK(count(doc, "<circle") == 4 + 3 + 2);    // + two legend dots
  CHECK(count(doc, "<rect") == 1 + 1 + 4 + 1);  // background, frame, boxes, legend box
  CHECK(doc.find("reference (4 vectors)") != std::string::npos);
  CHECK(doc.find("solver (3 vectors)") != std::string::npos);
  CHECK(doc.find("ε-box, ε = 0.1") != std::string::npos);
  CHECK(doc.find(">length<") != std::string::npos);
  CHECK(plot_front(p) == doc);  // deterministic
  if (const char* dir = std::getenv("MOSB_PLOT_DIR"))
    std::ofstream(std::string(dir) + "/front.svg") << doc;
}

TEST_CASE("cardinality plot sorts and switches to a log scale over two decades") {
  CardinalityPlot p;
  p.title = "sizes";
  p.sizes = {5, 3000, 40, 2, 700};
  const auto doc = plot_cardinality(p);
  CHECK(doc.find("front size (log scale)") != std::string::npos);
  CHECK(count(doc, "<circle") == 5 + 1);
  CHECK(doc.find(">1000<") != std::string::npos);
  p.sizes = {5, 9, 7};
  CHECK(plot_cardinality(p).find("log scale") == std::string::npos);
  if (const char* dir = std::getenv("MOSB_PLOT_DIR")) {
    p.sizes.clear();
    for (int k = 0; k < 100; ++k)
      p.sizes.push_back(static_cast<std::uint64_t>(2 + std::pow(1.09, k)));
    std::ofstream(std::string(dir) + "/cardinality.svg") << plot_cardinality(p);
  }
}

TEST_CASE("correlation heat map labels every cell, n/a when undefined") {
  CorrelationPlot p;
  p.names = {"a", "b"};
  p.rho = {{1.0, std::nullopt}, {std::nullopt, 1.0}};
  const auto doc = plot_correlation(p);
  CHECK(count(doc, ">1.00<") == 2);
  CHECK(count(doc, ">n/a<") == 2);
}

TEST_CASE("svg escape replaces the C0 controls XML 1.0 forbids") {
  const std::string text = std::string("a<b") + '\0' + "\x1b[1m\tz";
  CHECK(mosb::plots::Svg::escape(text) == "a&lt;b\xEF\xBF\xBD\xEF\xBF\xBD[1m\tz");
}

TEST_CASE("a large front is thinned, keeps its extreme points and says so") {
  std::vector<mosb::plots::Point2> front;
  front.reserve(12345);
  for (int k = 0; k < 12345; ++k) front.push_back({double(k), double(12345 - k)});
  const auto drawn = mosb::plots::thin_points(front, mosb::plots::kMaxDrawnPoints);
  CHECK(drawn.size() <= mosb::plots::kMaxDrawnPoints + 4);
  CHECK(drawn.size() >= mosb::plots::kMaxDrawnPoints / 2);
  CHECK(drawn.front().x == 0);
  CHECK(drawn.back().x == 12344);  // the largest x, and the smallest y
  CHECK(mosb::plots::thin_points(front, mosb::plots::kMaxDrawnPoints).size() == drawn.size());
  mosb::plots::FrontPlot plot;
  plot.solution = front;
  const auto svg = mosb::plots::plot_front(plot);
  CHECK(svg.find("showing " + std::to_string(drawn.size()) + " of 12345") != std::string::npos);
  CHECK(svg.find(">solver (12345 vectors)<") != std::string::npos);
  CHECK(svg.size() < 2'000'000);
  plot.solution.resize(100);
  CHECK(mosb::plots::plot_front(plot).find("showing") == std::string::npos);
}

// Issue 22 §2: each defect found by a new user, one test each.

TEST_CASE("map legend gives the lowest exposure a colour, and cells of it are shaded") {
  MapPlot p;
  p.width = 3;
  p.height = 2;
  p.passable = {true, true, true, true, false, true};
  p.exposure = {1, 2, 3, 1, NAN, 3};
  p.exposure_unit = "guards";
  const auto doc = plot_map(p);
  const auto lowest = swatch_of(doc, "exposure 1");
  REQUIRE(!lowest.empty());
  CHECK(lowest != "#ffffff");      // not the background: a colour of its own
  CHECK(count(doc, lowest) >= 3);  // the swatch and the two cells of value 1
  CHECK(swatch_of(doc, "exposure 2") != lowest);
  CHECK(swatch_of(doc, "exposure 3") == viridis(0));  // highest: dark end of viridis
  CHECK(lowest == viridis(1));
  CHECK(has(doc, ">exposure [guards]<"));  // the unit, from the instance's metadata
  CHECK(plot_map(p) == doc);
  // Many distinct values: five legend steps from the lowest to the highest.
  p.width = 9;
  p.height = 1;
  p.passable.assign(9, true);
  p.exposure = {0, 1.5, 3, 4.5, 6, 7.5, 11, 12, 13};
  p.exposure_unit.clear();
  const auto many = plot_map(p);
  CHECK(count(many, ">exposure ") == 5);
  for (const char* v : {"0", "3.25", "6.5", "9.75", "13"})
    CHECK(has(many, ">exposure " + std::string(v) + "<"));
}

TEST_CASE("map marks the guards where they stand, also on a coarsened map") {
  MapPlot p;
  p.width = 4;
  p.height = 2;
  p.passable.assign(8, true);
  CHECK(!has(plot_map(p), "guards"));
  p.guards = {{0, 0}, {3, 1}};
  const auto doc = plot_map(p);
  CHECK(has(doc, R"(class="guards" data-count="2")"));
  CHECK(has(doc, ">guard<"));
  MapPlot coarse = MapSquares(4, 2, 2, false).plot();
  CHECK(coarse.block == 2);
  CHECK((square_of(coarse, p.guards[1]).x == 1 && square_of(coarse, p.guards[1]).y == 0));
}

TEST_CASE("front legend says what it counts, and coincident vectors are both visible") {
  auto p = small_front();
  p.solver_name = "boa";
  p.reference_name = "reference namoa";
  const auto doc = plot_front(p);
  CHECK(has(doc, ">boa (3 vectors)<"));
  CHECK(has(doc, ">reference namoa (3 vectors)<"));
  CHECK(!has(doc, "(3)<"));
  // Reference vectors are rings (no fill), solver vectors smaller translucent dots on top.
  CHECK(count(doc, R"(r="5" fill="none" stroke="#0072B2" stroke-width="1.5")") == 3 + 1);
  CHECK(count(doc,
              R"(r="3" fill="#D55E00" stroke="#fff" stroke-width="0.5" fill-opacity="0.75")") == 3);
  // Rings first, dots over them: every reference ring precedes the first solver dot.
  CHECK(count(doc.substr(0, doc.find(R"(fill="#D55E00")")), R"(fill="none" stroke="#0072B2")") ==
        3);
  p.solution = {{10, 40}};
  CHECK(has(plot_front(p), ">boa (1 vector)<"));
  p.solver_name = "boa-with-a-rather-long-configuration";  // the count on a line of its own
  CHECK(has(plot_front(p), ">boa-with-a-rather-long-configuration<"));
  CHECK(has(plot_front(p), ">(1 vector)<"));
}

TEST_CASE("two plots of one query share the origin: value axes start at 0") {
  auto with_reference = small_front();
  with_reference.epsilon = 0.5;
  auto alone = small_front();
  alone.reference.clear();
  for (const auto& doc : {plot_front(with_reference), plot_front(alone)}) {
    // The first x tick sits on the left edge of the plot area and the first y tick on its
    // bottom, both labelled 0.
    CHECK(has(doc, R"(<text x="90" y="431" text-anchor="middle" font-size="13" fill="#000">0<)"));
    CHECK(has(doc, R"(<text x="82" y="415" text-anchor="end" font-size="13" fill="#000">0<)"));
  }
  CardinalityPlot c;
  c.sizes = {5, 9, 7};
  CHECK(has(plot_cardinality(c), R"(font-size="13" fill="#000">0<)"));
  // Negative values (not costs, but possible input) still fit: the axis starts below them.
  alone.solution = {{-3, 4}, {5, -2}};
  const auto negative = texts(plot_front(alone));
  CHECK(std::find(negative.begin(), negative.end(), "-4") != negative.end());
}

TEST_CASE("a front of more than two objectives says it is a projection") {
  auto p = small_front();
  CHECK(!has(plot_front(p), "projection"));
  p.objective_count = 3;
  CHECK(has(plot_front(p), ">projection on c1, c2 of 3 objectives<"));
}

TEST_CASE("no text is smaller than the minimum font size") {
  auto check_fonts = [](const std::string& doc) {
    std::size_t n = 0;
    for (auto at = doc.find("font-size=\""); at != std::string::npos;
         at = doc.find("font-size=\"", at + 1), ++n)
      CHECK(std::stod(doc.substr(at + 11)) >= kMinFontSize);
    CHECK(n > 3);
  };
  auto front = small_front();
  front.epsilon = 0.1;
  check_fonts(plot_front(front));
  CardinalityPlot c;
  c.sizes = {1, 50, 3000};
  check_fonts(plot_cardinality(c));
  CorrelationPlot r;
  r.names = {"a", "b", "c", "d", "e", "f", "g", "h", "i", "j"};
  r.rho.assign(10, std::vector<std::optional<double>>(10, -0.44));
  check_fonts(plot_correlation(r));
  MapPlot m;
  m.width = m.height = 2;
  m.passable = {true, false, true, true};
  m.exposure = {0, NAN, 1, 2};
  check_fonts(plot_map(m));
  CHECK(kMinFontSize >= 13);
}

TEST_CASE("colour-blind-safe colours and axis labels with units") {
  auto p = small_front();
  p.x_unit = "s";
  p.epsilon = 0.1;
  const auto doc = plot_front(p);
  CHECK(has(doc, ">c1 [s]<"));
  CHECK(has(doc, ">c2<"));  // no unit: the name alone
  // Okabe–Ito: reference blue, solver vermillion, ε-boxes sky blue; nothing else coloured.
  for (const char* old : {"#08519c", "#e6550d", "#9ecae1", "#6baed6"}) CHECK(!has(doc, old));
  CHECK(has(doc, "#0072B2"));
  CHECK(has(doc, "#D55E00"));
  CHECK(has(doc, R"(fill="#56B4E9")"));
  CHECK(viridis(0) == "#440154");
  CHECK(viridis(1) == "#fde725");
  CHECK(viridis(0.5) == "#21918c");
  MapPlot m;
  m.width = 4;
  m.height = 1;
  m.passable.assign(4, true);
  m.paths = {{{0, 0}, {1, 0}}, {{0, 0}, {3, 0}}};
  const auto map = plot_map(m);
  CHECK(has(map, R"(stroke="#E69F00")"));
  CHECK(has(map, R"(stroke="#56B4E9")"));
  for (const char* old : {"#1f77b4", "#2ca02c"}) CHECK(!has(map, old));
}

TEST_CASE("front plot of a reference alone has no solver entry, and an all-zero axis is 0 to 1") {
  FrontPlot p;
  p.x_label = "length";
  p.y_label = "exposure";
  p.reference = {{5, 0}};
  const auto doc = plot_front(p);
  CHECK(has(doc, ">reference (1 vector)<"));
  CHECK_FALSE(has(doc, "solver ("));
  const auto t = texts(doc);
  CHECK(std::find(t.begin(), t.end(), "-1") == t.end());  // the y axis does not go below 0
  CHECK(std::find(t.begin(), t.end(), "1") != t.end());
}

TEST_CASE("thin_rows keeps every objective's extremes and at most limit + 2d rows") {
  std::vector<std::vector<double>> rows;
  rows.reserve(1000);
  for (int k = 0; k < 1000; ++k)
    rows.push_back({static_cast<double>(k), static_cast<double>((k * 37) % 1000),
                    static_cast<double>(1000 - k), static_cast<double>((k * 91) % 997)});
  const auto kept = thin_rows(rows, 50);
  CHECK(kept.size() >= 50);
  CHECK(kept.size() <= 50 + 8);
  for (std::size_t i = 0; i < 4; ++i) {
    double lo = 1e9, hi = -1e9, klo = 1e9, khi = -1e9;
    for (const auto& r : rows) lo = std::min(lo, r[i]), hi = std::max(hi, r[i]);
    for (const auto& r : kept) klo = std::min(klo, r[i]), khi = std::max(khi, r[i]);
    CHECK(lo == klo);
    CHECK(hi == khi);
  }
  CHECK(thin_rows(rows, 50) == kept);
  CHECK(thin_rows(rows, 5000).size() == 1000);
}

TEST_CASE("parallel coordinates: an axis per objective, a polyline per vector, thinning said") {
  ParallelPlot p;
  p.title = "front";
  p.axes = {"a", "b", "c", "d"};
  p.reference = {{1, 2, 3, 4}, {4, 3, 2, 1}};
  p.solution = {{1, 2, 3, 4}};
  auto doc = plot_parallel(p);
  CHECK(count(doc, "<polyline") == 3);
  for (const char* axis : {">a<", ">b<", ">c<", ">d<"}) CHECK(has(doc, axis));
  CHECK(has(doc, "reference (2 vectors)"));
  for (int k = 0; k < 2000; ++k)
    p.solution.push_back({1.0 * k, 2000.0 - k, 1.0 * (k % 7), 1.0 * (k % 13)});
  doc = plot_parallel(p);
  CHECK(has(doc, ">showing "));
  CHECK(count(doc, "<polyline") < 2 + kMaxDrawnLines + 9);
}

TEST_CASE("instance space: a line per series at its d, the values as data attributes") {
  InstanceSpacePlot p;
  p.title = "space";
  p.series = {{"NetMaker", 3, {-0.44, -0.45, -0.43}}, {"Grid_2", 2, {0.01}}};
  const auto doc = plot_instance_space(p);
  CHECK(has(doc, R"(data-series="NetMaker" data-d="3" data-rho="-0.4400,-0.4500,-0.4300")"));
  CHECK(has(doc, R"(data-series="Grid_2" data-d="2" data-rho="0.0100")"));
  CHECK(has(doc, ">NetMaker<"));
  CHECK(has(doc, ">objectives d<"));
  // Per series: a range line, a faint dot per pair, two ends.
  CHECK(count(doc, "fill-opacity=\"0.3\"") == 4);
}

TEST_CASE("lines, scatter and bars: log axes, a diagonal, one bar per series and category") {
  LinePlot cactus;
  cactus.title = "cactus";
  cactus.y_log = true;
  cactus.series = {{"A", {{1, 0.01}, {2, 0.5}, {3, 20}}}, {"B", {{1, 0.02}}}};
  auto doc = plot_lines(cactus);
  CHECK(count(doc, "<polyline") == 2);
  CHECK(has(doc, ">0.01<"));
  CHECK(has(doc, ">100<"));  // the log axis ends at the power of ten above 20
  LinePlot profile = cactus;
  profile.steps = true;
  profile.x_log = true;
  profile.y_log = false;
  profile.y_max = 1;
  profile.x_min = 1;
  profile.series = {{"A", {{1, 0.5}, {2, 1}}}};
  doc = plot_lines(profile);
  // Steps: (1, .5), (2, .5), (2, 1) and on to the right edge.
  CHECK(count(doc, "<polyline") == 1);
  const auto points = doc.substr(doc.find("<polyline points=\"") + 18);
  CHECK(std::count(points.begin(), points.begin() + static_cast<long>(points.find('"')), ',') == 4);

  ScatterPlot scatter;
  scatter.groups = {{"Grid", {{0.1, 0.2}, {1, 0.5}}}};
  scatter.note = "1 query not drawn";
  doc = plot_runtime_scatter(scatter);
  CHECK(count(doc, "<circle") == 2 + 1);
  CHECK(has(doc, ">1 query not drawn<"));
  CHECK(has(doc, ">line: equal runtime<"));

  BarPlot bars;
  bars.categories = {"ε = 0", "ε = 0.1"};
  bars.series = {{"A", {1, 1}}, {"B", {0.5, 0.75}}};
  doc = plot_bars(bars);
  CHECK(count(doc, "<rect") == 1 + 4 + 1 + 2);  // background, bars, frame, legend
  CHECK(has(doc, ">ε = 0.1<"));
}

TEST_CASE("MapSquares: squares of k x k cells, passable when half are, the highest exposure") {
  // The 4 x 2 map with cells (0,0), (2,1), (3,1) passable, exposures 1, 2 and 5.
  MapSquares squares(4, 2, 2, true);
  for (const auto& [x, y, e] : {std::tuple{0u, 0u, 1.0}, {2u, 1u, 2.0}, {3u, 1u, 5.0}}) {
    squares.add_passable(x, y);
    squares.add_exposure(x, y, e);
  }
  auto c = squares.plot();
  CHECK(c.width == 2);
  CHECK(c.height == 1);
  CHECK(c.block == 2);
  CHECK(c.passable == std::vector<bool>{false, true});  // 1 of 4 cells, 2 of 4
  CHECK(c.passable_share == std::vector<double>{0.25, 0.5});
  CHECK(c.exposure[1] == 5);
  c.queries = {{7, square_of(c, {3, 1}), square_of(c, {0, 0})}};
  CHECK(c.queries[0].start.x == 1);
  CHECK(c.queries[0].goal.x == 0);
  CHECK(MapSquares(4, 2, 4, false).plot().width == 4);  // small enough: a square per cell
  CHECK(MapSquares(4, 2, 4, false).plot().exposure.empty());
  const auto doc = plot_map(c);
  CHECK(has(doc, ">1 square: 2x2 cells<"));
  CHECK(has(doc, ">blocked square<"));
  CHECK(has(doc, ">partly blocked square<"));
  CHECK(count(doc, "#808080") == 2);  // the half-blocked square and its legend swatch
  CHECK(has(doc, ">start (query number)<"));
  CHECK(count(doc, ">7<") == 2);  // start and goal labelled
  // The last square of a side the block does not divide holds fewer cells: 5 x 1 in squares of
  // 2, the last square one cell, passable when that cell is.
  MapSquares odd(5, 1, 3, false);
  odd.add_passable(4, 0);
  CHECK(odd.plot().passable == std::vector<bool>{false, false, true});
  CHECK(odd.plot().passable_share == std::vector<double>{0, 0, 1});  // the last: its one cell
  // A wall one cell thick through squares of 4 x 4 cells stays visible: every square it crosses
  // is passable (12 of 16 cells) and partly blocked; the others are open.
  MapSquares walled(8, 8, 2, false);
  for (std::uint32_t y = 0; y < 8; ++y)
    for (std::uint32_t x = 0; x < 8; ++x)
      if (x != 5) walled.add_passable(x, y);
  const auto wall = walled.plot();
  CHECK(wall.passable == std::vector<bool>{true, true, true, true});
  CHECK(wall.passable_share == std::vector<double>{1, 0.75, 1, 0.75});
  const auto walled_doc = plot_map(wall);
  CHECK(count(walled_doc, "#c0c0c0") == 2);  // 12 of 16 passable: the wall's two squares
  CHECK(MapSquares(4, 2, 4, false).plot().passable_share.empty());  // a square per cell
}

// Issue 36 §1: a map's squares come from its size alone, whatever it is (0 read as 1).
TEST_CASE("MapSquares: at most max_side squares a side, for any size up to 2^32 - 1") {
  const auto most = MapSquares(4294967295u, 4294967295u, 160, true).plot();
  CHECK(most.width == 160);
  CHECK(most.height == 160);
  CHECK(most.block == 26843546);
  CHECK(MapSquares(7, 3, 0, false).plot().width == 1);
  const auto thin = MapSquares(4294967295u, 1, 100, false).plot();
  CHECK(thin.width == 100);
  CHECK(thin.height == 1);
}
