#include "mosb/report/plots.hpp"

#include <algorithm>
#include <array>
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

// Where v lies between lo and hi, as a fraction: (v - lo) / (hi - lo) computed on halves, so
// that no difference of two finite values overflows (the same bits for every value a normal
// double can hold).
double fraction(double v, double lo, double hi) {
  return (v / 2 - lo / 2) / (hi / 2 - lo / 2);
}

// x when finite, else `otherwise`: a padded bound that overflowed stays where it was.
double finite_or(double x, double otherwise) {
  return std::isfinite(x) ? x : otherwise;
}

// The decades of a log axis: 10^k for k from -307 to 308, the powers of ten a double holds
// exactly enough and log10 maps back without overflow.
constexpr int kFirstDecade = -307, kLastDecade = 308;
int decade(double v, bool up) {
  const double k = up ? std::ceil(std::log10(v)) : std::floor(std::log10(v));
  return static_cast<int>(
      std::clamp(std::isnan(k) ? 0.0 : k, double{kFirstDecade}, double{kLastDecade}));
}

// A linear or log10 axis from data range [lo, hi] onto pixels [p0, p1].
struct Axis {
  double lo = 0, hi = 1, p0 = 0, p1 = 1;
  bool log = false;
  bool whole = false;  // counts and ranks: no tick between two integers
  double map(double v) const {
    const double a = log ? std::log10(std::max(v, lo)) : v;
    const double l = log ? std::log10(lo) : lo, h = log ? std::log10(hi) : hi;
    return p0 + fraction(a, l, h) * (p1 - p0);
  }
  std::vector<double> ticks() const {
    if (!log) {
      auto t = nice_ticks(lo, hi);
      if (whole) std::erase_if(t, [](double v) { return v != std::floor(v); });
      return t;
    }
    // A tick per decade, every n-th past a dozen decades: bounded whatever lo and hi are.
    std::vector<double> t;
    const int first = decade(lo, false), last = decade(hi, true);
    const int stride = std::max(1, (last - first + 12) / 12);
    for (int k = first; k <= last; k += stride) {
      const double v = std::pow(10, k);
      if (v >= lo * 0.9999 && v <= hi * 1.0001) t.push_back(v);
    }
    return t;
  }
};

// Pads [lo, hi] outward to tick steps so points do not sit on the frame; a bound padded past the
// largest double stays where it was.
void widen(double& lo, double& hi) {
  if (!(hi > lo)) {
    const double pad = lo == 0 ? 1 : std::fabs(lo) * 0.1;
    lo = finite_or(lo - pad, lo);
    hi = finite_or(hi + pad, hi);
  }
  const auto t = nice_ticks(lo, hi);
  if (t.size() >= 2) {
    const double step = t[1] - t[0];
    lo = finite_or(std::floor(lo / step) * step, lo);
    hi = finite_or(std::ceil(hi / step) * step, hi);
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
// kind 'c' filled dot, 'o' ring, 'r' box, 's' hollow square, '-' text alone.
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
    else if (e.kind == 'r')
      svg.rect(x, y - 11, 12, 12, e.colour, "#555", 1, 0.5);
    else if (e.kind == 's')
      svg.rect(x + 1, y - 10, 10, 10, "none", e.colour, 1.5);
    svg.text(e.kind == '-' ? x : x + 18, y, e.label, "start", kLegendFont);
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
  // The span on halves (hi - lo overflows for -DBL_MAX..DBL_MAX), the step at least 2 parts.
  const double raw = (hi / 2 - lo / 2) / std::max(target, 2) * 2;
  const double power = std::pow(10, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  // The ticks are the multiples first..last of the step, counted, not walked to: where the range
  // is too narrow for its magnitude (no 1-2-5 step between two doubles) or the step is no
  // number, the axis gets its ends alone.
  const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
  constexpr double kExact = 1e15;  // whole numbers a double counts exactly, with room
  if (!(step > 0) || !std::isfinite(step) || !(std::fabs(first) < kExact) ||
      !(std::fabs(last) < kExact) || last - first > 4.0 * std::max(target, 2))
    return {lo, hi};
  std::vector<double> ticks;
  for (std::int64_t k = 0; k <= static_cast<std::int64_t>(last - first); ++k) {
    const double v = (first + static_cast<double>(k)) * step;
    if (std::isfinite(v)) ticks.push_back(std::fabs(v) < step * 1e-9 ? 0 : v);
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
  hi = std::min(hi, std::numeric_limits<double>::max());  // an ε-box's corner past it
  lo = std::min(lo, 0.0);
  if (lo == 0 && hi <= 0) hi = 1;  // all zero: 0 to 1, not −1 to 1
  widen(lo, hi);
}

// A front's axis: the data's own range with a 5 % margin (never below 0 for values that are not),
// rounded to ticks; a front at 36-39 is drawn on 35-40, not squeezed into a 0-40 axis.
void data_range(double& lo, double& hi) {
  if (!std::isfinite(lo)) lo = 0, hi = 1;
  hi = std::min(hi, std::numeric_limits<double>::max());
  if (lo == 0 && hi <= 0) hi = 1;  // all zero: 0 to 1, not −1 to 1
  const double pad = (hi - lo) * 0.05;
  lo = lo >= 0 ? std::max(0.0, lo - pad) : lo - pad;
  hi = finite_or(hi + pad, hi);
  widen(lo, hi);
}

}  // namespace

std::string plot_front(const FrontPlot& plot) {
  const double e = plot.epsilon.value_or(0);
  // The far corner of an ε-box, at most the largest double.
  const auto box = [e](double v) {
    return finite_or(v * (1 + e), std::numeric_limits<double>::max());
  };
  const auto reference = thin_points(plot.reference, plot.max_points);
  const auto solution = thin_points(plot.solution, plot.max_points);
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  auto extend = [&](const Point2& p) {
    x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x);
    y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
  };
  for (const auto& p : plot.reference) extend({box(p.x), box(p.y)}), extend(p);
  for (const auto& p : plot.solution) extend(p);
  const std::size_t approximations = std::min(plot.approximations.size(), kMaxApproximations);
  std::vector<std::vector<Point2>> approximated(approximations);
  for (std::size_t k = 0; k < approximations; ++k) {
    approximated[k] = thin_points(plot.approximations[k].points, plot.max_points);
    for (const auto& p : plot.approximations[k].points) extend(p);
  }
  if (!std::isfinite(y_lo)) y_lo = 0, y_hi = 1;
  data_range(x_lo, x_hi);
  data_range(y_lo, y_hi);
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
      svg.rect(x.map(q.x), y.map(box(q.y)), x.map(box(q.x)) - x.map(q.x),
               y.map(q.y) - y.map(box(q.y)), kBoxColour, kBoxColour, 0.5, 0.25);
  // Rings under small translucent dots: a solver vector on a reference vector shows both.
  for (const auto& q : reference)
    svg.circle(x.map(q.x), y.map(q.y), 5, "none", kReferenceColour, 1.5);
  for (const auto& p : solution)
    svg.circle(x.map(p.x), y.map(p.y), 3, kSolverColour, "#fff", 0.5, 0.75);
  constexpr std::array<const char*, kMaxApproximations> kApproximationColours = {
      kOkabeIto[2], kOkabeIto[6], kOkabeIto[0], kOkabeIto[7]};
  // Hollow squares, larger per series, so fronts sharing a vector (an ε front is often a subset
  // of the exact one) show nested around the reference's ring.
  for (std::size_t k = 0; k < approximations; ++k) {
    const double half = 5.5 + 2 * static_cast<double>(k);
    for (const auto& p : approximated[k])
      svg.rect(x.map(p.x) - half, y.map(p.y) - half, 2 * half, 2 * half, "none",
               kApproximationColours[k], 1.5);
  }
  std::vector<LegendEntry> entries;
  if (!plot.reference.empty())
    entries.push_back(front_entry('o', kReferenceColour, plot.reference_name, reference.size(),
                                  plot.reference.size()));
  if (!plot.solution.empty() || plot.reference.empty())
    entries.push_back(
        front_entry('c', kSolverColour, plot.solver_name, solution.size(), plot.solution.size()));
  for (std::size_t k = 0; k < approximations; ++k)
    entries.push_back(front_entry('s', kApproximationColours[k], plot.approximations[k].name,
                                  approximated[k].size(), plot.approximations[k].points.size()));
  if (plot.approximations.size() > approximations)
    entries.push_back(
        {'-', "", std::to_string(plot.approximations.size() - approximations) + " more not drawn",
         ""});
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
  const std::string title =
      plot.left_out == 0 ? plot.title
                         : plot.title + " (" + std::to_string(plot.left_out) + " unsolved quer" +
                               (plot.left_out == 1 ? "y" : "ies") + " left out)";
  frame(svg, x, y, title, "query rank (sorted by front size)",
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
  return viridis(hi > lo ? 1 - fraction(v, lo, hi) : 1);
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
    for (int k = 0; k <= 4; ++k) values.push_back(lo + (hi - lo) / 4 * k);
  }
  std::vector<LegendEntry> entries;
  if (!plot.exposure_unit.empty() && !values.empty())
    entries.push_back({'-', "", "exposure [" + plot.exposure_unit + "]", ""});
  for (double v : values)
    entries.push_back({'r', exposure_colour(v, lo, hi), "exposure " + tick_label(v), ""});
  return entries;
}

constexpr const char* kBlockedColour = "#252525";

// A passable square with blocked cells (a passable share from 1/2 to below 1): a grey from #808080
// (half blocked) to #e0e0e0 (nearly open), in four steps so runs of squares still merge.
std::string partly_blocked_colour(double passable_share) {
  const double step = std::clamp(std::floor((passable_share - 0.5) * 8), 0.0, 3.0);
  const auto level = static_cast<unsigned>(0x80 + step * (0xe0 - 0x80) / 3);
  char colour[8];
  std::snprintf(colour, sizeof colour, "#%02x%02x%02x", level, level, level);
  return colour;
}

// One rectangle per run of equal colour along each row keeps large maps small; white (passable,
// no exposure) is the background.
void map_cells(Svg& svg, const MapPlot& plot, double x0, double y0, double cell, double lo,
               double hi) {
  for (std::uint32_t yy = 0; yy < plot.height; ++yy) {
    auto colour_of = [&](std::uint32_t xx) -> std::string {
      const std::size_t k = static_cast<std::size_t>(yy) * plot.width + xx;
      if (k >= plot.passable.size() || !plot.passable[k]) return kBlockedColour;
      if (k < plot.passable_share.size() && plot.passable_share[k] < 1)
        return partly_blocked_colour(plot.passable_share[k]);
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
  std::vector<LegendEntry> entries = {
      {'r', kBlockedColour, plot.block > 1 ? "blocked square" : "blocked cell", ""}};
  if (std::any_of(plot.passable_share.begin(), plot.passable_share.end(),
                  [](double share) { return share >= 0.5 && share < 1; }))
    entries.push_back({'r', partly_blocked_colour(0.5), "partly blocked square", ""});
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
  const double marker = std::max(4.0, cell * 0.6);
  for (const auto& q : plot.queries) {
    const double sx = x0 + cell * (q.start.x + 0.5), sy = y0 + cell * (q.start.y + 0.5);
    const double gx = x0 + cell * (q.goal.x + 0.5), gy = y0 + cell * (q.goal.y + 0.5);
    svg.circle(sx, sy, marker, kOkabeIto[2], "#fff", 1.5);
    svg.rect(gx - marker, gy - marker, 2 * marker, 2 * marker, kOkabeIto[5], "#fff", 1.5);
    svg.text(sx + marker + 2, sy - marker, std::to_string(q.query), "start", kMinFontSize);
    svg.text(gx + marker + 2, gy - marker, std::to_string(q.query), "start", kMinFontSize);
  }
  if (!plot.guards.empty()) {
    svg.begin_group(R"(class="guards" data-count=")" + std::to_string(plot.guards.size()) + "\"");
    for (const auto& g : plot.guards)
      svg.circle(x0 + cell * (g.x + 0.5), y0 + cell * (g.y + 0.5), marker * 0.8, "#000", "#fff",
                 1.5);
    svg.end_group();
  }
  if (!plot.queries.empty()) {
    entries.push_back({'r', kOkabeIto[2], "start (query number)", ""});
    entries.push_back({'r', kOkabeIto[5], "goal", ""});
  }
  if (!plot.guards.empty()) entries.push_back({'r', "#000", "guard", ""});
  if (plot.block > 1)
    entries.push_back(
        {'-', "",
         "1 square: " + std::to_string(plot.block) + "x" + std::to_string(plot.block) + " cells",
         ""});
  // The legend sits right of the map; '-' is a heading without a swatch.
  double ly = y0 + 10;
  for (const auto& e : entries) {
    if (e.kind != '-') svg.rect(x0 + cell * w + 20, ly - 11, 12, 12, e.colour, "#555");
    svg.text(x0 + cell * w + (e.kind == '-' ? 20 : 38), ly, e.label, "start", kLegendFont);
    ly += 20;
  }
  return svg.str();
}

MapSquares::MapSquares(std::uint32_t width, std::uint32_t height, std::uint32_t max_side,
                       bool shaded)
    : width_(width), height_(height) {
  // In 64 bits: a side of 2^32 - 1 cells and any max_side, 0 read as 1, neither overflows.
  const std::uint64_t side = std::max(width, height), most = std::max<std::uint32_t>(max_side, 1);
  block_ = static_cast<std::uint32_t>(std::max<std::uint64_t>((side + most - 1) / most, 1));
  columns_ = static_cast<std::uint32_t>((std::uint64_t{width} + block_ - 1) / block_);
  rows_ = static_cast<std::uint32_t>((std::uint64_t{height} + block_ - 1) / block_);
  open_.assign(std::size_t{columns_} * rows_, 0);
  if (shaded) exposure_.assign(open_.size(), std::numeric_limits<double>::quiet_NaN());
}

std::size_t MapSquares::index(std::uint32_t x, std::uint32_t y) const {
  return std::size_t{y / block_} * columns_ + x / block_;
}

void MapSquares::add_passable(std::uint32_t x, std::uint32_t y) {
  ++open_[index(x, y)];
}

void MapSquares::add_exposure(std::uint32_t x, std::uint32_t y, double value) {
  double& square = exposure_[index(x, y)];
  if (!std::isnan(value) && !(square >= value)) square = value;
}

MapPlot MapSquares::plot() const {
  MapPlot out;
  out.width = columns_;
  out.height = rows_;
  out.block = block_;
  out.exposure = exposure_;
  out.passable.resize(open_.size());
  if (block_ > 1) out.passable_share.resize(open_.size());
  // The cells of a square: k x k, fewer in the last column and row of a side k does not divide.
  const auto cells = [this](std::uint32_t square, std::uint32_t side) {
    return std::min<std::uint64_t>(block_, side - std::uint64_t{square} * block_);
  };
  for (std::uint32_t y = 0; y < rows_; ++y)
    for (std::uint32_t x = 0; x < columns_; ++x) {
      const std::size_t i = std::size_t{y} * columns_ + x;
      const std::uint64_t all = cells(x, width_) * cells(y, height_);
      out.passable[i] = 2 * std::uint64_t{open_[i]} >= all;
      if (block_ > 1)
        out.passable_share[i] = static_cast<double>(open_[i]) / static_cast<double>(all);
    }
  return out;
}

Point2 square_of(const MapPlot& map, Point2 cell) {
  const double k = std::max<std::uint32_t>(map.block, 1);
  return {std::floor(cell.x / k), std::floor(cell.y / k)};
}

namespace {

const char* category_colour(std::size_t k) {
  // Okabe–Ito without yellow, which white backgrounds swallow.
  static constexpr const char* kColours[] = {kOkabeIto[4], kOkabeIto[5], kOkabeIto[2], kOkabeIto[0],
                                             kOkabeIto[6], kOkabeIto[1], kOkabeIto[7]};
  return kColours[k % std::size(kColours)];
}

// Legend entries past what fits beside the plot area are summed up in one last line.
void capped_legend(Svg& svg, std::vector<LegendEntry> entries) {
  constexpr std::size_t kFit = 15;
  if (entries.size() > kFit) {
    const auto more = entries.size() - (kFit - 1);
    entries.resize(kFit - 1);
    entries.push_back({'-', "", "... and " + std::to_string(more) + " more", ""});
  }
  legend(svg, entries);
}

// Log axis bounds: powers of ten around the positive values (1 when there are none), from 1e-307
// up to the largest double.
void log_range(double& lo, double& hi) {
  constexpr double kLargest = std::numeric_limits<double>::max();
  const auto usable = [](double v) { return v > 0 && std::isfinite(v); };
  if (!usable(lo)) lo = usable(hi) ? hi : 1;
  if (!usable(hi)) hi = lo;
  lo = std::pow(10, decade(lo, false));
  hi = hi > std::pow(10, kLastDecade) ? kLargest : std::pow(10, decade(hi, true));
  if (hi <= lo) hi = finite_or(lo * 10, kLargest);
}

std::string polyline_points(const Axis& x, const Axis& y, const std::vector<Point2>& points) {
  std::string out;
  for (const auto& p : points) out += Svg::number(x.map(p.x)) + "," + Svg::number(y.map(p.y)) + " ";
  if (!out.empty()) out.pop_back();
  return out;
}

std::string rho_list(const std::vector<double>& rho) {
  std::string out;
  char buffer[32];
  for (double r : rho) {
    std::snprintf(buffer, sizeof buffer, "%.4f", r);
    out += (out.empty() ? "" : ",") + std::string(buffer);
  }
  return out;
}

}  // namespace

std::string plot_instance_space(const InstanceSpacePlot& plot) {
  std::size_t d_lo = SIZE_MAX, d_hi = 0;
  for (const auto& s : plot.series)
    d_lo = std::min(d_lo, s.objectives), d_hi = std::max(d_hi, s.objectives);
  if (d_lo > d_hi) d_lo = d_hi = 2;
  Svg svg(kWidth, kHeight);
  const Axis x{plot.absolute ? 0.0 : -1.0, 1, kLeft, kWidth - kRight};
  const Axis y{static_cast<double>(d_lo) - 0.5,
               static_cast<double>(d_hi) + 0.5,
               kHeight - kBottom,
               kTop,
               false,
               true};
  frame(svg, x, y, plot.title,
        plot.absolute ? "pairwise Pearson correlation |ρ| of the objectives"
                      : "pairwise Pearson correlation ρ of the objectives",
        "objectives d");
  if (!plot.absolute) svg.line(x.map(0), y.p0, x.map(0), y.p1, "#999");
  std::vector<LegendEntry> entries;
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const auto& s = plot.series[k];
    const char* colour = category_colour(k);
    svg.begin_group("data-series=\"" + Svg::escape(s.name) + "\" data-d=\"" +
                    std::to_string(s.objectives) + "\" data-rho=\"" + rho_list(s.rho) + "\"");
    const double py = y.map(static_cast<double>(s.objectives));
    if (!s.rho.empty()) {
      const auto [lo, hi] = std::minmax_element(s.rho.begin(), s.rho.end());
      svg.line(x.map(*lo), py, x.map(*hi), py, colour, 2);
      for (double r : s.rho) svg.circle(x.map(r), py, 3, colour, "none", 1, 0.3);
      svg.circle(x.map(*lo), py, 5, "#fff", colour, 2);
      svg.circle(x.map(*hi), py, 5, "#fff", colour, 2);
    }
    svg.end_group();
    entries.push_back({'c', colour, s.name, ""});
  }
  capped_legend(svg, entries);
  return svg.str();
}

std::string plot_degrees(const DegreePlot& plot) {
  const auto& v = plot.vertices_by_degree;
  double y_lo = 0, y_hi = 1;
  for (auto c : v) y_hi = std::max(y_hi, static_cast<double>(c));
  widen(y_lo, y_hi);
  double x_lo = -0.5, x_hi = static_cast<double>(std::max<std::size_t>(v.size(), 1)) - 0.5;
  Svg svg(kWidth, kHeight);
  const Axis x{x_lo, x_hi, kLeft, kWidth - kRight, false, true};
  const Axis y{y_lo, y_hi, kHeight - kBottom, kTop, false, true};
  frame(svg, x, y, plot.title, "out-degree", "vertices");
  const double w = std::max(1.0, (x.p1 - x.p0) / std::max<std::size_t>(v.size(), 1) * 0.8);
  for (std::size_t d = 0; d < v.size(); ++d)
    if (v[d] > 0)
      svg.rect(x.map(static_cast<double>(d)) - w / 2, y.map(static_cast<double>(v[d])), w,
               y.map(0) - y.map(static_cast<double>(v[d])), kReferenceColour);
  std::uint64_t n = 0;
  for (auto c : v) n += c;
  legend(svg, {{'r', kReferenceColour, std::to_string(n) + " vertices", ""}});
  return svg.str();
}

std::string plot_lines(const LinePlot& plot) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const auto& s : plot.series)
    for (const auto& p : s.points) {
      if (!plot.x_log || p.x > 0) x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x);
      if (!plot.y_log || p.y > 0) y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
    }
  if (plot.x_min) x_lo = std::min(x_lo, *plot.x_min);
  if (plot.x_log)
    log_range(x_lo, x_hi);
  else
    value_range(x_lo, x_hi);
  if (plot.y_max && !plot.y_log)
    y_lo = 0, y_hi = *plot.y_max;
  else if (plot.y_log)
    log_range(y_lo, y_hi);
  else
    value_range(y_lo, y_hi);
  if (plot.x_min && plot.x_log) x_lo = *plot.x_min;
  Svg svg(kWidth, kHeight);
  const Axis x{x_lo, x_hi, kLeft, kWidth - kRight, plot.x_log};
  const Axis y{y_lo, y_hi, kHeight - kBottom, kTop, plot.y_log};
  frame(svg, x, y, plot.title, plot.x_label, plot.y_label);
  std::vector<LegendEntry> entries;
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const auto& s = plot.series[k];
    const char* colour = category_colour(s.colour < 0 ? k : static_cast<std::size_t>(s.colour));
    std::vector<Point2> points = s.points;
    if (plot.steps) {  // horizontal, then vertical, and on to the right edge
      std::vector<Point2> stepped;
      for (std::size_t i = 0; i < s.points.size(); ++i) {
        if (i > 0) stepped.push_back({s.points[i].x, s.points[i - 1].y});
        stepped.push_back(s.points[i]);
      }
      if (!stepped.empty()) stepped.push_back({x_hi, stepped.back().y});
      points = std::move(stepped);
    }
    if (s.joined) svg.polyline(polyline_points(x, y, points), colour, 2);
    if (!plot.steps)
      for (const auto& p : s.points)
        svg.circle(x.map(p.x), y.map(p.y), s.joined ? 2.5 : 1.5, colour);
    if (!s.name.empty()) entries.push_back({'r', colour, s.name, ""});
  }
  capped_legend(svg, entries);
  return svg.str();
}

std::string plot_runtime_scatter(const ScatterPlot& plot) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& g : plot.groups)
    for (const auto& p : g.points)
      for (double v : {p.x, p.y})
        if (v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
  log_range(lo, hi);
  // A square plot area: the diagonal at 45 degrees.
  const double side = std::min(kWidth - kRight - kLeft, kHeight - kBottom - kTop);
  Svg svg(kWidth, kHeight);
  const Axis x{lo, hi, kLeft, kLeft + side, true};
  const Axis y{lo, hi, kTop + side, kTop, true};
  frame(svg, x, y, plot.title, plot.x_label, plot.y_label);
  if (!plot.note.empty())
    svg.text(kWidth / 2 - (kRight - kLeft) / 2, 48, plot.note, "middle", kMinFontSize, 0, "#333");
  svg.line(x.map(lo), y.map(lo), x.map(hi), y.map(hi), "#555", 1);
  std::vector<LegendEntry> entries;
  for (std::size_t k = 0; k < plot.groups.size(); ++k) {
    const char* colour = category_colour(k);
    for (const auto& p : plot.groups[k].points)
      svg.circle(x.map(p.x), y.map(p.y), 3.5, colour, "#fff", 0.5, 0.75);
    entries.push_back({'c', colour, plot.groups[k].name, ""});
  }
  entries.push_back({'-', "", "line: equal runtime", ""});
  capped_legend(svg, entries);
  return svg.str();
}

std::string plot_bars(const BarPlot& plot) {
  Svg svg(kWidth, kHeight);
  const double n = static_cast<double>(std::max<std::size_t>(plot.categories.size(), 1));
  const Axis x{0, n, kLeft, kWidth - kRight};
  const Axis y{0, plot.y_max, kHeight - kBottom, kTop};
  svg.text(kWidth / 2 - (kRight - kLeft) / 2, 28, plot.title, "middle", kTitleFont);
  for (double t : y.ticks()) {
    svg.line(x.p0, y.map(t), x.p1, y.map(t), "#e4e4e4");
    svg.line(x.p0 - 5, y.map(t), x.p0, y.map(t), "#000");
    svg.text(x.p0 - 8, y.map(t) + 5, tick_label(t), "end", kTickFont);
  }
  const double group = (x.p1 - x.p0) / n;
  const double bar =
      group * 0.8 / static_cast<double>(std::max<std::size_t>(plot.series.size(), 1));
  std::vector<LegendEntry> entries;
  for (std::size_t c = 0; c < plot.categories.size(); ++c)
    svg.text(x.p0 + group * (static_cast<double>(c) + 0.5), y.p0 + 21, plot.categories[c], "middle",
             kTickFont);
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const char* colour = category_colour(k);
    for (std::size_t c = 0; c < plot.series[k].values.size() && c < plot.categories.size(); ++c) {
      const double v = std::clamp(plot.series[k].values[c], 0.0, plot.y_max);
      const double left =
          x.p0 + group * (static_cast<double>(c) + 0.1) + bar * static_cast<double>(k);
      svg.rect(left, y.map(v), bar, y.map(0) - y.map(v), colour);
    }
    entries.push_back({'r', colour, plot.series[k].name, ""});
  }
  svg.rect(x.p0, y.p1, x.p1 - x.p0, y.p0 - y.p1, "none", "#000");
  svg.text((x.p0 + x.p1) / 2, kHeight - 22, plot.x_label, "middle", kLabelFont);
  svg.text(24, (y.p0 + y.p1) / 2, plot.y_label, "middle", kLabelFont, -90);
  capped_legend(svg, entries);
  return svg.str();
}

std::vector<std::vector<double>> thin_rows(const std::vector<std::vector<double>>& rows,
                                           std::size_t limit) {
  if (rows.size() <= limit || limit == 0) return rows;
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return rows[a] != rows[b] ? rows[a] < rows[b] : a < b;
  });
  const std::size_t step = (rows.size() + limit - 1) / limit;
  std::vector<bool> keep(rows.size(), false);
  for (std::size_t k = 0; k < order.size(); k += step) keep[order[k]] = true;
  const std::size_t d = rows.front().size();
  for (std::size_t i = 0; i < d; ++i) {
    const auto by = [&](std::size_t a, std::size_t b) { return rows[a][i] < rows[b][i]; };
    keep[*std::min_element(order.begin(), order.end(), by)] = true;
    keep[*std::max_element(order.begin(), order.end(), by)] = true;
  }
  std::vector<std::vector<double>> kept;
  for (const std::size_t k : order)
    if (keep[k]) kept.push_back(rows[k]);
  return kept;
}

std::string plot_parallel(const ParallelPlot& plot) {
  const std::size_t d = plot.axes.size();
  const auto reference = thin_rows(plot.reference, kMaxDrawnLines);
  const auto solution = thin_rows(plot.solution, kMaxDrawnLines);
  std::vector<double> lo(d, std::numeric_limits<double>::infinity()), hi(d, -lo[0]);
  for (const auto* set : {&plot.reference, &plot.solution})
    for (const auto& row : *set)
      for (std::size_t i = 0; i < d && i < row.size(); ++i)
        lo[i] = std::min(lo[i], row[i]), hi[i] = std::max(hi[i], row[i]);
  Svg svg(kWidth, kHeight);
  const double top = kTop + 10, bottom = kHeight - kBottom;
  const auto axis_x = [&](std::size_t i) {
    return d < 2 ? kLeft
                 : kLeft + (kWidth - kRight - kLeft) * static_cast<double>(i) /
                               static_cast<double>(d - 1);
  };
  const auto axis_y = [&](std::size_t i, double v) {
    return hi[i] > lo[i] ? bottom - fraction(v, lo[i], hi[i]) * (bottom - top) : (top + bottom) / 2;
  };
  svg.text(kWidth / 2 - (kRight - kLeft) / 2, 28, plot.title, "middle", kTitleFont);
  if (!plot.subtitle.empty())
    svg.text(kWidth / 2 - (kRight - kLeft) / 2, 48, plot.subtitle, "middle", kMinFontSize, 0,
             "#333");
  const auto draw = [&](const std::vector<std::vector<double>>& rows, const char* colour,
                        double width, double opacity) {
    for (const auto& row : rows) {
      std::string points;
      for (std::size_t i = 0; i < d && i < row.size(); ++i)
        points += Svg::number(axis_x(i)) + "," + Svg::number(axis_y(i, row[i])) + " ";
      if (!points.empty()) points.pop_back();
      svg.begin_group("stroke-opacity=\"" + Svg::number(opacity) + "\"");
      svg.polyline(points, colour, width);
      svg.end_group();
    }
  };
  draw(reference, kReferenceColour, 2.5, 0.5);
  draw(solution, kSolverColour, 1.2, 0.6);
  for (std::size_t i = 0; i < d; ++i) {
    svg.line(axis_x(i), top, axis_x(i), bottom, "#000", 1.5);
    svg.text(axis_x(i), bottom + 38, plot.axes[i], "middle", kLabelFont);
    if (std::isfinite(lo[i])) {
      svg.text(axis_x(i), bottom + 18, tick_label(lo[i]), "middle", kTickFont);
      svg.text(axis_x(i), top - 6, tick_label(hi[i]), "middle", kTickFont);
    }
  }
  std::vector<LegendEntry> entries;
  if (!plot.reference.empty())
    entries.push_back(front_entry('r', kReferenceColour, plot.reference_name, reference.size(),
                                  plot.reference.size()));
  if (!plot.solution.empty())
    entries.push_back(
        front_entry('r', kSolverColour, plot.solver_name, solution.size(), plot.solution.size()));
  legend(svg, entries);
  return svg.str();
}

}  // namespace mosb::plots
