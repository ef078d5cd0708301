#include "mosb/report/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "mosb/report/svg.hpp"

namespace mosb::plots {

namespace {

constexpr double kWidth = 800, kHeight = 480;
constexpr double kLeft = 90, kRight = 250, kTop = 60, kBottom = 70;  // plot-area margins
constexpr double kTickFont = kMinFontSize, kLegendFont = kMinFontSize, kLabelFont = 15;
constexpr double kTitleFont = 17;
constexpr const char* kReferenceColour = kOkabeIto[4];  // blue
constexpr const char* kSolverColour = kOkabeIto[5];     // vermillion
constexpr const char* kBoxColour = kOkabeIto[1];        // sky blue

std::string tick_label(double v) {
  char buffer[32];
  const double a = std::fabs(v);
  if (a != 0 && (a >= 1e6 || a < 1e-3))
    std::snprintf(buffer, sizeof buffer, "%.3g", v);
  else
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// A linear or log10 axis from data range [lo, hi] onto pixels [p0, p1].
struct Axis {
  double lo = 0, hi = 1, p0 = 0, p1 = 1;
  bool log = false;
  bool whole = false;  // counts and ranks: no tick between two integers
  double map(double v) const {
    const double a = log ? std::log10(std::max(v, lo)) : v;
    const double l = log ? std::log10(lo) : lo, h = log ? std::log10(hi) : hi;
    return p0 + (a - l) / (h - l) * (p1 - p0);
  }
  std::vector<double> ticks() const {
    if (!log) {
      auto t = nice_ticks(lo, hi);
      if (whole) std::erase_if(t, [](double v) { return v != std::floor(v); });
      return t;
    }
    std::vector<double> t;
    const auto first = static_cast<int>(std::floor(std::log10(lo)));
    const auto last = static_cast<int>(std::ceil(std::log10(hi)));
    for (int k = first; k <= last; ++k) {
      const double v = std::pow(10, k);
      if (v >= lo * 0.9999 && v <= hi * 1.0001) t.push_back(v);
    }
    return t;
  }
};

// Pads [lo, hi] outward to tick steps so points do not sit on the frame.
void widen(double& lo, double& hi) {
  if (!(hi > lo)) {
    const double pad = lo == 0 ? 1 : std::fabs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  const auto t = nice_ticks(lo, hi);
  if (t.size() >= 2) {
    const double step = t[1] - t[0];
    lo = std::floor(lo / step) * step;
    hi = std::ceil(hi / step) * step;
  }
}

void frame(Svg& svg, const Axis& x, const Axis& y, const std::string& title,
           const std::string& x_label, const std::string& y_label) {
  svg.text(kWidth / 2 - (kRight - kLeft) / 2, 28, title, "middle", kTitleFont);
  for (double t : x.ticks()) {
    const double px = x.map(t);
    svg.line(px, y.p1, px, y.p0, "#e4e4e4");
    svg.line(px, y.p0, px, y.p0 + 5, "#000");
    svg.text(px, y.p0 + 21, tick_label(t), "middle", kTickFont);
  }
  for (double t : y.ticks()) {
    const double py = y.map(t);
    svg.line(x.p0, py, x.p1, py, "#e4e4e4");
    svg.line(x.p0 - 5, py, x.p0, py, "#000");
    svg.text(x.p0 - 8, py + 5, tick_label(t), "end", kTickFont);
  }
  svg.rect(x.p0, y.p1, x.p1 - x.p0, y.p0 - y.p1, "none", "#000");
  svg.text((x.p0 + x.p1) / 2, kHeight - 22, x_label, "middle", kLabelFont);
  svg.text(24, (y.p0 + y.p1) / 2, y_label, "middle", kLabelFont, -90);
}

// Legend entries at the right of the plot area: (kind, colour, label, an optional second line);
// kind 'c' filled dot, 'o' ring, 'r' box.
struct LegendEntry {
  char kind;
  std::string colour, label, note;
};
void legend(Svg& svg, const std::vector<LegendEntry>& entries) {
  double y = kTop + 10;
  const double x = kWidth - kRight + 14;
  for (const auto& e : entries) {
    if (e.kind == 'c')
      svg.circle(x + 6, y - 5, 3.5, e.colour, "#fff", 0.75, 0.75);
    else if (e.kind == 'o')
      svg.circle(x + 6, y - 5, 5, "none", e.colour, 1.5);
    else
      svg.rect(x, y - 11, 12, 12, e.colour, "#555", 1, 0.5);
    svg.text(x + 18, y, e.label, "start", kLegendFont);
    if (!e.note.empty()) svg.text(x + 18, y += 18, e.note, "start", kLegendFont);
    y += 22;
  }
}

// Diverging blue-white-red for ρ in [−1, 1].
std::string diverging(double rho) {
  rho = std::clamp(rho, -1.0, 1.0);
  const double a = std::fabs(rho);
  int r, g, b;
  if (rho >= 0) {  // white → #b2182b
    r = static_cast<int>(255 + (178 - 255) * a);
    g = static_cast<int>(255 + (24 - 255) * a);
    b = static_cast<int>(255 + (43 - 255) * a);
  } else {  // white → #2166ac
    r = static_cast<int>(255 + (33 - 255) * a);
    g = static_cast<int>(255 + (102 - 255) * a);
    b = static_cast<int>(255 + (172 - 255) * a);
  }
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", r, g, b);
  return buffer;
}

}  // namespace

std::string viridis(double t) {
  // matplotlib's viridis at t = 0, 0.1, ..., 1, linearly interpolated between.
  static constexpr int kStops[11][3] = {{0x44, 0x01, 0x54}, {0x48, 0x24, 0x75}, {0x41, 0x44, 0x87},
                                        {0x35, 0x5f, 0x8d}, {0x2a, 0x78, 0x8e}, {0x21, 0x91, 0x8c},
                                        {0x22, 0xa8, 0x84}, {0x44, 0xbf, 0x70}, {0x7a, 0xd1, 0x51},
                                        {0xbd, 0xdf, 0x26}, {0xfd, 0xe7, 0x25}};
  t = std::isnan(t) ? 0 : std::clamp(t, 0.0, 1.0) * 10;
  const auto k = std::min(static_cast<int>(t), 9);
  const double f = t - k;
  int c[3];
  for (int i = 0; i < 3; ++i)
    c[i] = static_cast<int>(std::lround(kStops[k][i] + (kStops[k + 1][i] - kStops[k][i]) * f));
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", c[0], c[1], c[2]);
  return buffer;
}

std::string axis_label(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : name + " [" + unit + "]";
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / std::max(target, 1);
  const double power = std::pow(10, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  std::vector<double> ticks;
  const double first = std::ceil(lo / step - 1e-9);
  for (int k = 0;; ++k) {
    const double v = (first + k) * step;
    if (v > hi + step * 1e-9) break;
    ticks.push_back(std::fabs(v) < step * 1e-9 ? 0 : v);
  }
  return ticks;
}

std::vector<Point2> thin_points(const std::vector<Point2>& points, std::size_t limit) {
  if (points.size() <= limit || limit == 0) return points;
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto by_xy = [&](std::size_t a, std::size_t b) {
    const auto &p = points[a], &q = points[b];
    return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : a < b;
  };
  std::sort(order.begin(), order.end(), by_xy);
  const std::size_t step = (points.size() + limit - 1) / limit;
  std::vector<bool> keep(points.size(), false);
  for (std::size_t k = 0; k < order.size(); k += step) keep[order[k]] = true;
  const auto by_y = [&](std::size_t a, std::size_t b) {
    return points[a].y != points[b].y ? points[a].y < points[b].y : by_xy(a, b);
  };
  keep[order.front()] = keep[order.back()] = true;  // smallest and largest x
  keep[*std::min_element(order.begin(), order.end(), by_y)] = true;
  keep[*std::max_element(order.begin(), order.end(), by_y)] = true;
  std::vector<Point2> drawn;
  for (const std::size_t k : order)
    if (keep[k]) drawn.push_back(points[k]);
  return drawn;
}

namespace {

// "NAME (n vectors)"; when thinned, a second line "showing k of n". A name too long for the
// legend's column on one line puts "(n vectors)" on the second line instead.
LegendEntry front_entry(char kind, const char* colour, const std::string& name, std::size_t drawn,
                        std::size_t total) {
  const std::string count = "(" + std::to_string(total) + (total == 1 ? " vector)" : " vectors)");
  LegendEntry e{kind, colour, name + " " + count, ""};
  if (drawn != total)
    e.note = "showing " + std::to_string(drawn) + " of " + std::to_string(total);
  else if (e.label.size() > 30)
    e.label = name, e.note = count;
  return e;
}

// The value range of an axis: from 0 (or the minimum when negative) to the maximum, padded to
// tick steps; the same rule for every plot, so two plots of one query share their origin.
void value_range(double& lo, double& hi) {
  if (!std::isfinite(lo)) lo = 0, hi = 1;
  lo = std::min(lo, 0.0);
  widen(lo, hi);
}

}  // namespace

std::string plot_front(const FrontPlot& plot) {
  const double e = plot.epsilon.value_or(0);
  const auto reference = thin_points(plot.reference, kMaxDrawnPoints);
  const auto solution = thin_points(plot.solution, kMaxDrawnPoints);
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  auto extend = [&](const Point2& p) {
    x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x);
    y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
  };
  for (const auto& p : plot.reference) extend({p.x * (1 + e), p.y * (1 + e)}), extend(p);
  for (const auto& p : plot.solution) extend(p);
  if (!std::isfinite(y_lo)) y_lo = 0, y_hi = 1;
  value_range(x_lo, x_hi);
  value_range(y_lo, y_hi);
  Svg svg(kWidth, kHeight);
  const Axis x{x_lo, x_hi, kLeft, kWidth - kRight};
  const Axis y{y_lo, y_hi, kHeight - kBottom, kTop};
  frame(svg, x, y, plot.title, axis_label(plot.x_label, plot.x_unit),
        axis_label(plot.y_label, plot.y_unit));
  if (plot.objective_count > 2)
    svg.text(kWidth / 2 - (kRight - kLeft) / 2, 48,
             "projection on " + plot.x_label + ", " + plot.y_label + " of " +
                 std::to_string(plot.objective_count) + " objectives",
             "middle", kMinFontSize, 0, "#333");
  if (e > 0)
    for (const auto& q : reference)
      svg.rect(x.map(q.x), y.map(q.y * (1 + e)), x.map(q.x * (1 + e)) - x.map(q.x),
               y.map(q.y) - y.map(q.y * (1 + e)), kBoxColour, kBoxColour, 0.5, 0.25);
  // Rings under small translucent dots: a solver vector on a reference vector shows both.
  for (const auto& q : reference)
    svg.circle(x.map(q.x), y.map(q.y), 5, "none", kReferenceColour, 1.5);
  for (const auto& p : solution)
    svg.circle(x.map(p.x), y.map(p.y), 3, kSolverColour, "#fff", 0.5, 0.75);
  std::vector<LegendEntry> entries;
  if (!plot.reference.empty())
    entries.push_back(front_entry('o', kReferenceColour, plot.reference_name, reference.size(),
                                  plot.reference.size()));
  entries.push_back(
      front_entry('c', kSolverColour, plot.solver_name, solution.size(), plot.solution.size()));
  if (e > 0) entries.push_back({'r', kBoxColour, "ε-box, ε = " + tick_label(e), ""});
  legend(svg, entries);
  return svg.str();
}

std::string plot_cardinality(const CardinalityPlot& plot) {
  std::vector<std::uint64_t> sizes = plot.sizes;
  std::sort(sizes.begin(), sizes.end());
  const double smallest =
      sizes.empty() ? 1 : static_cast<double>(std::max<std::uint64_t>(sizes.front(), 1));
  const double largest =
      sizes.empty() ? 1 : static_cast<double>(std::max<std::uint64_t>(sizes.back(), 1));
  const bool log = largest / smallest > 100;
  double y_lo = log ? std::pow(10, std::floor(std::log10(smallest))) : 0;
  double y_hi = log ? std::pow(10, std::ceil(std::log10(largest))) : largest;
  if (!log) widen(y_lo, y_hi);
  double x_lo = 0, x_hi = static_cast<double>(std::max<std::size_t>(sizes.size(), 1));
  widen(x_lo, x_hi);
  Svg svg(kWidth, kHeight);
  const Axis x{x_lo, x_hi, kLeft, kWidth - kRight, false, true};
  const Axis y{y_lo, y_hi, kHeight - kBottom, kTop, log, true};
  frame(svg, x, y, plot.title, "query rank (sorted by front size)",
        log ? "front size (log scale)" : "front size");
  std::string points;
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    const double px = x.map(static_cast<double>(k + 1));
    const double py = y.map(static_cast<double>(std::max<std::uint64_t>(sizes[k], log ? 1 : 0)));
    points += Svg::number(px) + "," + Svg::number(py) + " ";
  }
  if (!points.empty()) points.pop_back();
  svg.polyline(points, kReferenceColour);
  for (std::size_t k = 0; k < sizes.size(); ++k)
    svg.circle(x.map(static_cast<double>(k + 1)),
               y.map(static_cast<double>(std::max<std::uint64_t>(sizes[k], log ? 1 : 0))), 2.5,
               kReferenceColour);
  legend(svg, {{'c', kReferenceColour, std::to_string(sizes.size()) + " queries", ""}});
  return svg.str();
}

std::string plot_correlation(const CorrelationPlot& plot) {
  const std::size_t n = plot.names.size();
  // Cells of at least 48 px hold "-0.44" at the minimum font size.
  const double cell = n == 0 ? 60 : std::clamp(320.0 / static_cast<double>(n), 48.0, 80.0);
  const double x0 = 150, y0 = 70;
  const double width = x0 + cell * static_cast<double>(n) + 150;
  const double height = y0 + cell * static_cast<double>(n) + 110;
  Svg svg(width, height);
  svg.text(width / 2, 30, plot.title, "middle", kTitleFont);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<double>(i);
    svg.text(x0 - 8, y0 + cell * c + cell / 2 + 4, plot.names[i], "end", kLegendFont);
    svg.text(x0 + cell * c + cell / 2, y0 + cell * static_cast<double>(n) + 18, plot.names[i],
             "middle", kLegendFont);
    for (std::size_t j = 0; j < n; ++j) {
      const auto rho =
          i < plot.rho.size() && j < plot.rho[i].size() ? plot.rho[i][j] : std::nullopt;
      const double px = x0 + cell * static_cast<double>(j), py = y0 + cell * c;
      svg.rect(px, py, cell, cell, rho ? diverging(*rho) : "#d9d9d9", "#fff", 1);
      char buffer[16];
      if (rho)
        std::snprintf(buffer, sizeof buffer, "%.2f", *rho);
      else
        std::snprintf(buffer, sizeof buffer, "n/a");
      svg.text(px + cell / 2, py + cell / 2 + 4, buffer, "middle", kMinFontSize, 0,
               rho && std::fabs(*rho) > 0.6 ? "#fff" : "#000");
    }
  }
  // Colour scale: ρ from −1 (bottom) to +1 (top).
  const double bar_x = x0 + cell * static_cast<double>(n) + 40, bar_h = 160;
  for (int k = 0; k < 40; ++k) {
    const double rho = 1 - 2 * (k + 0.5) / 40;
    svg.rect(bar_x, y0 + bar_h * k / 40, 16, bar_h / 40 + 0.5, diverging(rho));
  }
  svg.rect(bar_x, y0, 16, bar_h, "none", "#000");
  for (double t : {1.0, 0.5, 0.0, -0.5, -1.0})
    svg.text(bar_x + 22, y0 + bar_h * (1 - t) / 2 + 4, tick_label(t), "start", kTickFont);
  svg.text(bar_x + 8, y0 - 10, "Pearson ρ", "middle", kLegendFont);
  return svg.str();
}

namespace {

// Exposure v on reversed viridis: the lowest value yellow, the highest dark purple.
std::string exposure_colour(double v, double lo, double hi) {
  return viridis(hi > lo ? 1 - (v - lo) / (hi - lo) : 1);
}

// The legend's exposure entries: every distinct value when there are at most 8, else 5 values
// evenly spaced from the lowest to the highest.
std::vector<LegendEntry> exposure_legend(const MapPlot& plot, double lo, double hi) {
  std::vector<double> values;
  for (double v : plot.exposure)
    if (!std::isnan(v)) values.push_back(v);
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  if (values.size() > 8) {
    values.clear();
    for (int k = 0; k <= 4; ++k) values.push_back(lo + (hi - lo) * k / 4);
  }
  std::vector<LegendEntry> entries;
  if (!plot.exposure_unit.empty() && !values.empty())
    entries.push_back({'-', "", "exposure [" + plot.exposure_unit + "]", ""});
  for (double v : values)
    entries.push_back({'r', exposure_colour(v, lo, hi), "exposure " + tick_label(v), ""});
  return entries;
}

// One rectangle per run of equal colour along each row keeps large maps small; white (passable,
// no exposure) is the background.
void map_cells(Svg& svg, const MapPlot& plot, double x0, double y0, double cell, double lo,
               double hi) {
  for (std::uint32_t yy = 0; yy < plot.height; ++yy) {
    auto colour_of = [&](std::uint32_t xx) -> std::string {
      const std::size_t k = static_cast<std::size_t>(yy) * plot.width + xx;
      if (k >= plot.passable.size() || !plot.passable[k]) return "#252525";
      if (plot.exposure.empty()) return "#ffffff";
      const double v = plot.exposure[k];
      return std::isnan(v) ? "#d9d9d9" : exposure_colour(v, lo, hi);
    };
    std::uint32_t start = 0;
    std::string run_colour;
    for (std::uint32_t xx = 0; xx <= plot.width; ++xx) {
      const std::string c = xx < plot.width ? colour_of(xx) : "";
      if (xx == 0) {
        run_colour = c;
        continue;
      }
      if (c != run_colour) {
        if (run_colour != "#ffffff")
          svg.rect(x0 + cell * start, y0 + cell * yy, cell * (xx - start), cell, run_colour);
        start = xx;
        run_colour = c;
      }
    }
  }
}

}  // namespace

std::string plot_map(const MapPlot& plot) {
  const double w = plot.width, h = plot.height;
  const double cell = std::max(1.0, std::min(600 / std::max(w, 1.0), 600 / std::max(h, 1.0)));
  const double x0 = 40, y0 = 50;
  const double width = x0 + cell * w + 190, height = y0 + cell * h + 40;
  Svg svg(width, height);
  svg.set_crisp_edges();
  svg.text(x0 + cell * w / 2, 30, plot.title, "middle", kTitleFont);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : plot.exposure)
    if (!std::isnan(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  svg.rect(x0, y0, cell * w, cell * h, "#ffffff", "#000", 1);
  map_cells(svg, plot, x0, y0, cell, lo, hi);
  // Path colours: Okabe–Ito without yellow (unreadable on the light end of the shading).
  const char* colours[] = {kOkabeIto[0], kOkabeIto[1], kOkabeIto[2], kOkabeIto[4],
                           kOkabeIto[5], kOkabeIto[6], kOkabeIto[7]};
  std::vector<LegendEntry> entries = {{'r', "#252525", "blocked cell", ""}};
  if (!plot.exposure.empty() && hi >= lo)
    for (auto& e : exposure_legend(plot, lo, hi)) entries.push_back(std::move(e));
  for (std::size_t k = 0; k < plot.paths.size(); ++k) {
    std::string points;
    for (const auto& p : plot.paths[k])
      points +=
          Svg::number(x0 + cell * (p.x + 0.5)) + "," + Svg::number(y0 + cell * (p.y + 0.5)) + " ";
    if (!points.empty()) points.pop_back();
    svg.polyline(points, colours[k % 7], std::max(1.5, cell / 3));
    if (k < 8) entries.push_back({'r', colours[k % 7], "path " + std::to_string(k + 1), ""});
  }
  // The legend sits right of the map; '-' is a heading without a swatch.
  double ly = y0 + 10;
  for (const auto& e : entries) {
    if (e.kind != '-') svg.rect(x0 + cell * w + 20, ly - 11, 12, 12, e.colour, "#555");
    svg.text(x0 + cell * w + (e.kind == '-' ? 20 : 38), ly, e.label, "start", kLegendFont);
    ly += 20;
  }
  return svg.str();
}

}  // namespace mosb::plots
