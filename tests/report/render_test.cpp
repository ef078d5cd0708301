#include "mosb/report/render.hpp"

#include <doctest/doctest.h>

#include <string>

#include "mosb/error.hpp"
#include "mosb/report/plots.hpp"

using namespace mosb;
using namespace mosb::plots;

TEST_CASE("parse_length: a number and a unit, in points") {
  CHECK(parse_length("3.5in") == doctest::Approx(252));
  CHECK(parse_length("252pt") == doctest::Approx(252));
  CHECK(parse_length("2.54cm") == doctest::Approx(72));
  CHECK(parse_length("25.4mm") == doctest::Approx(72));
  CHECK(parse_length("96px") == doctest::Approx(72));
  for (const char* bad : {"3.5", "in", "3.5 in", "-1in", "0pt", "300in", "1e400in", ""})
    CHECK_THROWS_AS(parse_length(bad), Error);
}

TEST_CASE("page_size keeps the aspect ratio unless both sides are given") {
  RenderSize s;
  auto p = page_size(800, 480, s);
  CHECK(p.width_pt == doctest::Approx(600));
  CHECK(p.height_pt == doctest::Approx(360));
  s.width_pt = 252;
  s.dpi = 200;
  p = page_size(800, 480, s);
  CHECK(p.height_pt == doctest::Approx(151.2));
  CHECK(p.width_px == 700);
  CHECK(p.height_px == 420);
  s.height_pt = 100;
  p = page_size(800, 480, s);
  CHECK(p.width_pt == doctest::Approx(252));
  CHECK(p.height_pt == doctest::Approx(100));
}

TEST_CASE("render_svg: a PDF and a PNG of a figure, the same bytes twice") {
  CardinalityPlot plot;
  plot.title = "sizes";
  plot.sizes = {3, 5, 8};
  const auto svg = plot_cardinality(plot);
  RenderSize size;
  size.width_pt = 252;
  const auto pdf = render_svg(svg, ImageFormat::pdf, size);
  CHECK(pdf.substr(0, 5) == "%PDF-");
  CHECK(pdf.find("/CreationDate") == std::string::npos);
  CHECK(render_svg(svg, ImageFormat::pdf, size) == pdf);
  const auto png = render_svg(svg, ImageFormat::png, size);
  CHECK(png.substr(1, 3) == "PNG");
  CHECK(render_svg(svg, ImageFormat::svg, size) == svg);
  CHECK_THROWS_AS(render_svg("<svg", ImageFormat::png, size), Error);
  CHECK(image_format_of("a/b.PDF") == ImageFormat::pdf);
  CHECK_FALSE(image_format_of("fig.jpg"));
}
