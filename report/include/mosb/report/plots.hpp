// The figures of `mosb plot` (spec/EVALUATION.md): each returns a complete SVG document.
// Axes have ticks at 1-2-5 steps, labels and a legend; the same input gives the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mosb::plots {

struct Point2 {
  double x = 0, y = 0;
};

// A 2-D front: reference and solver vectors of two objectives, and the ε-box of each reference
// vector q (the rectangle from q to (1+ε)·q: a solver vector inside it or below-left of q covers
// q).
struct FrontPlot {
  std::string title, x_label, y_label;
  std::vector<Point2> reference, solution;
  std::optional<double> epsilon;  // no boxes when absent or 0
};
// Past kMaxDrawnPoints vectors a set is thinned (thin_points) so a million-vector front stays a
// figure of a few hundred kB; the legend then says "showing k of n".
std::string plot_front(const FrontPlot& plot);
inline constexpr std::size_t kMaxDrawnPoints = 5000;
// The points drawn of a set: all of them up to `limit`; past it, in order of (x, y), every
// ceil(n / limit)-th point plus both extreme points of each objective (smallest and largest x and
// y), so the front's ends are always shown. Deterministic; at most limit + 4 points.
std::vector<Point2> thin_points(const std::vector<Point2>& points, std::size_t limit);

// Front size per query, sorted increasing (query hardness); a log scale when sizes span more than
// two decades. Values of unsolved queries are left out by the caller.
struct CardinalityPlot {
  std::string title;
  std::vector<std::uint64_t> sizes;
};
std::string plot_cardinality(const CardinalityPlot& plot);

// Pearson correlation matrix of the objectives as a heat map, −1 blue, 0 white, +1 red, each cell
// labelled with its value ("n/a" when undefined). rho[i][j], symmetric, diagonal 1.
struct CorrelationPlot {
  std::string title;
  std::vector<std::string> names;
  std::vector<std::vector<std::optional<double>>> rho;
};
std::string plot_correlation(const CorrelationPlot& plot);

// A grid map: blocked cells dark, passable cells shaded by exposure (white = lowest, deep orange
// = highest; light grey when unknown), and paths as cell sequences.
struct MapPlot {
  std::string title;
  std::uint32_t width = 0, height = 0;
  std::vector<bool> passable;              // row-major, width * height
  std::vector<double> exposure;            // row-major; NaN = unknown; empty = no shading
  std::vector<std::vector<Point2>> paths;  // cell coordinates (x, y)
};
std::string plot_map(const MapPlot& plot);

// Ticks at 1, 2 or 5 times a power of ten covering [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

}  // namespace mosb::plots
