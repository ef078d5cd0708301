#include "mosb/report/plots.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "mosb/report/svg.hpp"

using namespace mosb::plots;

namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
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

TEST_CASE("front plot draws every vector, the epsilon boxes and a legend") {
  FrontPlot p;
  p.title = "q1";
  p.x_label = "length";
  p.y_label = "exposure";
  p.reference = {{1, 10}, {3, 7}, {5, 5}, {10, 1}};
  p.solution = {{1.05, 10.2}, {5, 5.1}, {10, 1}};
  p.epsilon = 0.1;
  const auto doc = plot_front(p);
  CHECK(count(doc, "<circle") == 4 + 3 + 2);   // + two legend dots
  CHECK(count(doc, "fill-opacity") == 4 + 1);  // boxes + legend box
  CHECK(doc.find("reference (4)") != std::string::npos);
  CHECK(doc.find("solver (3)") != std::string::npos);
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
  CHECK(svg.size() < 2'000'000);
  plot.solution.resize(100);
  CHECK(mosb::plots::plot_front(plot).find("showing") == std::string::npos);
}
