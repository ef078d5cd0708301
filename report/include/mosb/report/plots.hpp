// The figures of `mosb plot` (spec/EVALUATION.md §5): each returns a complete SVG document.
// Axes have ticks at 1-2-5 steps, labels and a legend; the same input gives the same bytes. No text
// is smaller than kMinFontSize px; categories take Okabe–Ito colours (kOkabeIto), continuous scales
// viridis; a linear value axis starts at 0 (at the data minimum only when that is negative).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mosb::plots {

struct Point2 {
  double x = 0, y = 0;
};

inline constexpr double kMinFontSize = 13;
// Okabe & Ito's colour-blind-safe categorical palette: orange, sky blue, bluish green, yellow,
// blue, vermillion, reddish purple, black.
inline constexpr const char* kOkabeIto[] = {"#E69F00", "#56B4E9", "#009E73", "#F0E442",
                                            "#0072B2", "#D55E00", "#CC79A7", "#000000"};
// Viridis at t in [0, 1] (0 dark purple, 1 yellow), as "#rrggbb".
std::string viridis(double t);
// "name [unit]", or the name alone when the unit is empty.
std::string axis_label(const std::string& name, const std::string& unit);

// A 2-D front: reference and solver vectors of two objectives, and the ε-box of each reference
// vector q (the rectangle from q to (1+ε)·q: a solver vector inside it or below-left of q covers
// q). Reference vectors are hollow blue rings, solver vectors smaller filled vermillion dots at 75%
// opacity, so coincident vectors stay visible; further fronts (`approximations`, an ε sweep's)
// are hollow squares, larger per series so shared vectors show nested, each its own colour
// (bluish green, reddish purple, orange, black; past
// kMaxApproximations the legend says how many more were not drawn). The legend says
// "NAME (n vectors)". With objective_count > 2 a subtitle says the figure is a projection on the
// two drawn objectives.
struct FrontSeries {
  std::string name;
  std::vector<Point2> points;
};
inline constexpr std::size_t kMaxApproximations = 4;
struct FrontPlot {
  std::string title, x_label, y_label;  // axis labels: the objective names
  std::string x_unit, y_unit;           // shown as "name [unit]" when not empty
  std::string solver_name = "solver", reference_name = "reference";
  std::size_t objective_count = 2;
  std::vector<Point2> reference, solution;
  std::vector<FrontSeries> approximations;
  std::optional<double> epsilon;  // no boxes when absent or 0
  std::size_t max_points = 5000;  // per set, past which it is thinned (kMaxDrawnPoints)
};
// Past kMaxDrawnPoints vectors a set is thinned (thin_points) so a million-vector front stays a
// figure of a few hundred kB; the legend then says "showing k of n" under the entry.
std::string plot_front(const FrontPlot& plot);
inline constexpr std::size_t kMaxDrawnPoints = 5000;
// The points drawn of a set: all of them up to `limit`; past it, in order of (x, y), every
// ceil(n / limit)-th point plus both extreme points of each objective (smallest and largest x and
// y), so the front's ends are always shown. Deterministic; at most limit + 4 points.
std::vector<Point2> thin_points(const std::vector<Point2>& points, std::size_t limit);

// Front size per query, sorted increasing (query hardness); a log scale when sizes span more than
// two decades. Unsolved queries have no front size: the caller leaves them out and counts them in
// `left_out`, which the title then says ("(N unsolved queries left out)").
struct CardinalityPlot {
  std::string title;
  std::vector<std::uint64_t> sizes;
  std::uint64_t left_out = 0;
};
std::string plot_cardinality(const CardinalityPlot& plot);

// Pearson correlation matrix of the objectives as a heat map, −1 blue, 0 white, +1 red (ColorBrewer
// RdBu ends, readable with the common colour-vision deficiencies), each cell labelled with its
// value ("n/a" when undefined). rho[i][j], symmetric, diagonal 1.
struct CorrelationPlot {
  std::string title;
  std::vector<std::string> names;
  std::vector<std::vector<std::optional<double>>> rho;
};
std::string plot_correlation(const CorrelationPlot& plot);

// A start/goal pair drawn on a map: the start a bluish-green dot, the goal a vermillion square,
// labelled with the query's number.
struct MapQuery {
  std::uint64_t query = 0;
  Point2 start, goal;  // cell coordinates
};

// A grid map: blocked cells dark grey, passable cells shaded by exposure on reversed viridis
// (lowest yellow, highest dark purple; light grey when unknown; white when there is no exposure),
// and paths as cell sequences in Okabe–Ito colours. The legend gives the colour of every exposure
// value when there are at most 8 distinct values, else of 5 evenly spaced values lowest to highest.
struct MapPlot {
  std::string title;
  std::string exposure_unit;  // the legend's heading "exposure [unit]" when not empty
  std::uint32_t width = 0, height = 0;
  std::vector<bool> passable;  // row-major, width * height
  // Row-major beside `passable` when block > 1 (else empty): the share of a square's cells that
  // are passable. A passable square with some blocked is drawn grey, darker the more are, so a
  // wall one cell thick stays visible in squares.
  std::vector<double> passable_share;
  std::vector<double> exposure;            // row-major; NaN = unknown; empty = no shading
  std::vector<std::vector<Point2>> paths;  // cell coordinates (x, y)
  std::vector<MapQuery> queries;           // start and goal markers
  std::vector<Point2> guards;              // cells where guards stand (metadata map.guards)
  // Cells per drawn square per side (MapSquares), said in the legend: width, height, passable,
  // exposure, paths, queries and guards are then of squares, not cells.
  std::uint32_t block = 1;
};
std::string plot_map(const MapPlot& plot);

// The squares a map of width x height cells is drawn with: k x k cells each, k the smallest that
// leaves no side more than max_side squares (max_side at least 1; k = 1: a square per cell). A
// square is passable when at least half of its cells are (a randomly blocked map keeps its
// texture; passable_share says how many are, so a wall one cell thick stays visible), its
// exposure the highest given to its cells (NaN when none). Only the squares are
// held, never the cells: a map of billions of cells, mostly blocked, costs what its drawing does
// (at most max_side² squares). A 1024 x 1024 map of rooms and walls stays a figure of tens of
// kB; a randomly blocked one, whose neighbouring squares differ, about 1 MB at 160 a side.
class MapSquares {
 public:
  MapSquares(std::uint32_t width, std::uint32_t height, std::uint32_t max_side, bool shaded);
  // A passable cell (x < width, y < height), each at most once.
  void add_passable(std::uint32_t x, std::uint32_t y);
  // An exposure of a cell: the cost of a move into it (with `shaded` only).
  void add_exposure(std::uint32_t x, std::uint32_t y, double value);
  // Its squares as a map (width, height, block, passable and, when shaded, exposure set).
  MapPlot plot() const;

 private:
  std::size_t index(std::uint32_t x, std::uint32_t y) const;
  std::uint32_t width_, height_, block_, columns_, rows_;
  std::vector<std::uint32_t> open_;  // passable cells per square
  std::vector<double> exposure_;     // per square; empty when not shaded
};
// Squares per side of `mosb plot map`'s figure: every cell of a map up to 1024 cells a side,
// squares of several cells past that.
inline constexpr std::uint32_t kMapSideOfPlot = 1024;
// Where `map` draws cell `cell`: the square that holds it.
Point2 square_of(const MapPlot& map, Point2 cell);

// The paper's instance-space figure: one series per benchmark at its number of objectives d
// (y axis), a line from its smallest to its largest pairwise ρ (x axis, −1 to 1) with the ends
// marked and every pair a faint dot on it. Each series group carries data-series, data-d and
// data-rho (the values, comma-separated) attributes, so a page's reader can check the numbers.
struct InstanceSpaceSeries {
  std::string name;
  std::size_t objectives = 0;
  std::vector<double> rho;  // every defined pairwise ρ (of every instance of the benchmark)
};
struct InstanceSpacePlot {
  std::string title;
  std::vector<InstanceSpaceSeries> series;
  bool absolute = false;  // the series hold |ρ|: the axis is 0 to 1, labelled |ρ|
};
std::string plot_instance_space(const InstanceSpacePlot& plot);

// Vertices per out-degree as bars (index = degree).
struct DegreePlot {
  std::string title;
  std::vector<std::uint64_t> vertices_by_degree;
};
std::string plot_degrees(const DegreePlot& plot);

// Lines of several series (Okabe–Ito colours, a legend entry each): the cactus plot (queries
// solved against runtime) and the Dolan–Moré performance profile (steps). A log axis where asked;
// `y_max` fixes the top of a linear y axis (a fraction: 1).
struct LineSeries {
  std::string name;            // its legend entry; none when empty
  std::vector<Point2> points;  // in drawing order
  bool joined = true;          // false: small dots only (one per query, beside a joined median)
  int colour = -1;             // the category colour's index; -1: the series' position
};
struct LinePlot {
  std::string title, x_label, y_label;
  bool x_log = false, y_log = false, steps = false;
  std::optional<double> x_min, y_max;
  std::vector<LineSeries> series;
};
std::string plot_lines(const LinePlot& plot);

// Per-query runtimes of solver A (x) against solver B (y) on log–log axes with the same range and
// the diagonal drawn; points grouped (coloured) by benchmark; `note` is a line under the title.
struct ScatterPlot {
  std::string title, x_label, y_label, note;
  std::vector<LineSeries> groups;
};
std::string plot_runtime_scatter(const ScatterPlot& plot);

// Grouped bars: per category (an ε) one bar per series (a solver), values in [0, y_max].
struct BarSeries {
  std::string name;
  std::vector<double> values;  // one per category
};
struct BarPlot {
  std::string title, x_label, y_label;
  std::vector<std::string> categories;
  std::vector<BarSeries> series;
  double y_max = 1;
};
std::string plot_bars(const BarPlot& plot);

// Parallel coordinates of a front of d > 3 objectives: one polyline per vector across d vertical
// axes, each axis scaled from its smallest to its largest value (both written at its ends).
// Reference vectors blue, solver vectors vermillion; past kMaxDrawnLines a set is thinned
// (thin_rows) and the legend says "showing k of n".
struct ParallelPlot {
  std::string title, subtitle;
  std::vector<std::string> axes;
  std::vector<std::vector<double>> reference, solution;
  std::string solver_name = "solver", reference_name = "reference";
};
std::string plot_parallel(const ParallelPlot& plot);
inline constexpr std::size_t kMaxDrawnLines = 400;
// Rows kept: all up to `limit`; past it, in lexicographic order every ceil(n / limit)-th row plus,
// per objective, a row with its smallest and one with its largest value. Deterministic.
std::vector<std::vector<double>> thin_rows(const std::vector<std::vector<double>>& rows,
                                           std::size_t limit);

// Ticks at 1, 2 or 5 times a power of ten covering [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

}  // namespace mosb::plots
