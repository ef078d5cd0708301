#include "mosb/report/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "mosb/error.hpp"
#include "mosb/report/figures.hpp"
#include "mosb/report/plots.hpp"
#include "mosb/report/svg.hpp"
#include "mosb/solution_summary.hpp"
#include "mosb/solver_comparison.hpp"
#include "mosb/stats.hpp"
#include "mosb/version.hpp"

namespace mosb::pages {

namespace {

using plots::Point2;
using plots::Svg;
using tables::Cell;
using tables::Table;

// One solution file bound to a benchmark's instance.
struct BoundFile {
  std::size_t file = 0;      // index into the solutions or references
  std::size_t instance = 0;  // index into the instances
};

struct Benchmark {
  std::string name, family;
  std::vector<std::size_t> instances;  // indices, in the order given
  std::vector<View> views;             // per entry of `instances`
  std::vector<BoundFile> references;
  std::map<std::string, std::vector<BoundFile>> solvers;  // by solver name
  std::vector<std::string> solver_order;                  // names in the order first given
};

// [a-z0-9_.] for a table key.
std::string key_of(const std::string& name) {
  std::string key;
  for (char c : name) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    key += (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ? c : '_';
  }
  return key;
}

std::string anchor(const std::string& name) {
  return "b-" + key_of(name);
}

std::string objective_names(const GraphReader& g, const View& v) {
  std::string out;
  for (auto i : v.objectives) out += (out.empty() ? "" : ", ") + g.objective(i).name;
  return out;
}

// The benchmarks of the instances: each view by name (instances sharing it aggregated), in the
// order of first appearance; an instance without views is one benchmark of all its objectives.
std::vector<Benchmark> benchmarks_of(std::span<const GraphReader> instances) {
  std::vector<Benchmark> out;
  std::map<std::string, std::size_t> by_name;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const auto& g = instances[i];
    auto views = g.views();
    if (views.empty()) {
      View all;
      all.name = g.metadata().get("benchmark").value_or(g.display_name());
      for (std::size_t k = 0; k < g.objective_count(); ++k) all.objectives.push_back(k);
      views.push_back(all);
    }
    for (auto& v : views) {
      auto [at, added] = by_name.emplace(v.name, out.size());
      if (added) {
        out.emplace_back();
        out.back().name = v.name;
        out.back().family = g.metadata().get("family").value_or("");
      }
      out[at->second].instances.push_back(i);
      out[at->second].views.push_back(std::move(v));
    }
  }
  return out;
}

// The benchmark and instance a solution file belongs to; throws naming the file when none.
std::pair<std::size_t, std::size_t> bind_file(const SolutionReader& file,
                                              std::span<const GraphReader> instances,
                                              const std::vector<Benchmark>& benchmarks) {
  for (std::size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].digest() != file.instance_digest()) continue;
    file.check_bound_to(instances[i]);
    const auto columns = file.instance_objectives(instances[i]);
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      for (std::size_t k = 0; k < benchmarks[b].instances.size(); ++k)
        if (benchmarks[b].instances[k] == i &&
            (file.view_name().empty() ? benchmarks[b].views[k].objectives == columns
                                      : benchmarks[b].views[k].name == file.view_name()))
          return {b, i};
    throw Error(
        ErrorCode::invalid_argument,
        file.display_name() + ": its objectives are no view of " + instances[i].display_name());
  }
  std::string names;
  for (const auto& g : instances) names += (names.empty() ? "" : ", ") + g.display_name();
  throw Error(ErrorCode::invalid_argument,
              file.display_name() + ": solutions of instance " + file.instance_digest() +
                  ", which is none of the report's instances (" + names + ")");
}

// A query of the suite: benchmark, instance, query set and position.
struct QueryKey {
  std::size_t benchmark = 0, instance = 0;
  std::string query_set;
  std::uint64_t query = 0;
  bool operator<(const QueryKey& o) const {
    return std::tie(benchmark, instance, query_set, query) <
           std::tie(o.benchmark, o.instance, o.query_set, o.query);
  }
};

struct Outcome {
  QueryStatus status = QueryStatus::not_run;
  std::optional<double> runtime;
  bool completed() const { return is_completed(status); }
};

// Every solver's outcome of every query it has a file for.
using Outcomes = std::map<QueryKey, std::map<std::string, Outcome>>;

// "a" or "a-b" over the instances of a benchmark.
Cell range_cell(std::uint64_t lo, std::uint64_t hi) {
  if (lo == hi) return Cell::of(lo);
  return Cell::of(std::to_string(lo) + "\u2013" + std::to_string(hi));
}

std::string inline_svg(const std::string& document) {
  return document.substr(document.find("<svg"));
}

class Page {
 public:
  explicit Page(std::vector<Figure>& figures) : figures_(figures) {}
  std::ostringstream out;
  void figure(const std::string& kind, const std::string& svg, const std::string& caption) {
    figures_.push_back({kind, svg});
    out << "<figure data-figure=\"" << Svg::escape(kind) << "\">\n"
        << inline_svg(svg) << "<figcaption>" << Svg::escape(caption)
        << "</figcaption>\n</figure>\n";
  }
  void paragraph(const std::string& text) { out << "<p>" << Svg::escape(text) << "</p>\n"; }

 private:
  std::vector<Figure>& figures_;
};

constexpr const char* kStyle =
    R"(body{font-family:"DejaVu Sans",Arial,sans-serif;margin:1.5em auto;max-width:1100px;padding:0 1em;color:#111}
h1{font-size:1.7em}h2{border-bottom:2px solid #0072B2;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;margin:1em 0;font-size:.85em}caption{text-align:left;font-weight:bold;padding:.3em 0}
th,td{border-bottom:1px solid #ccc;padding:.25em .6em}th{background:#eef3f8;cursor:pointer;text-align:left}
td.n{text-align:right;font-variant-numeric:tabular-nums}
th[aria-sort=ascending]::after{content:" \25B2"}th[aria-sort=descending]::after{content:" \25BC"}
figure{margin:.5em;display:inline-block;vertical-align:top;width:calc(50% - 1.2em);min-width:360px}
figure svg{width:100%;height:auto;border:1px solid #ddd}.scroll{overflow-x:auto}
figure[data-figure=instance-space]{width:calc(100% - 1.2em);max-width:900px}
figcaption{font-size:.85em;color:#333;max-width:800px}nav li{display:inline;margin-right:1em}
.note{color:#555;font-size:.9em}
)";

constexpr const char* kScript =
    R"(document.querySelectorAll("table.sortable th").forEach(function(th){th.tabIndex=0;
th.addEventListener("keydown",function(e){if(e.key==="Enter"||e.key===" "){e.preventDefault();th.click();}});
th.addEventListener("click",function(){
var row=th.parentNode,table=row.closest("table"),body=table.tBodies[0],col=Array.prototype.indexOf.call(row.children,th);
var up=th.getAttribute("aria-sort")!=="ascending";Array.prototype.forEach.call(row.children,function(h){h.removeAttribute("aria-sort");});
th.setAttribute("aria-sort",up?"ascending":"descending");
function key(tr){var c=tr.cells[col],v=c.getAttribute("data-v");return v===null?c.textContent:(v===""?-Infinity:parseFloat(v));}
var rows=Array.prototype.slice.call(body.rows);rows.sort(function(a,b){var x=key(a),y=key(b),r=typeof x==="number"&&typeof y==="number"?(x<y?-1:x>y?1:0):String(x).localeCompare(String(y));return up?r:-r;});
rows.forEach(function(r){body.appendChild(r);});});});
)";

// The queries whose fronts are drawn: the chosen ones that the file solved, or its smallest,
// median and largest solved non-empty front.
std::vector<std::uint64_t> chosen_queries(const SolutionReader& r,
                                          const std::vector<std::uint64_t>& wanted) {
  std::vector<std::uint64_t> out;
  if (!wanted.empty()) {
    for (auto q : wanted)
      if (q < r.query_count() && r.status(q) == QueryStatus::solved && r.front_size(q) > 0)
        out.push_back(q);
    return out;
  }
  std::vector<std::pair<std::uint64_t, std::uint64_t>> solved;  // (size, query)
  for (std::uint64_t q = 0; q < r.query_count(); ++q)
    if (r.status(q) == QueryStatus::solved && r.front_size(q) > 0)
      solved.emplace_back(r.front_size(q), q);
  if (solved.empty()) return out;
  std::sort(solved.begin(), solved.end());
  for (std::size_t k : {std::size_t{0}, solved.size() / 2, solved.size() - 1})
    if (std::find(out.begin(), out.end(), solved[k].second) == out.end())
      out.push_back(solved[k].second);
  return out;
}

std::vector<std::vector<double>> front_rows(const SolutionReader& r, std::uint64_t q) {
  std::vector<std::vector<double>> rows(r.front_size(q));
  const auto begin = r.front_begin(q);
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (std::size_t i = 0; i < r.objective_count(); ++i)
      rows[k].push_back(r.value_as_double(i, begin + k));
  return rows;
}

std::vector<Point2> pair_points(const std::vector<std::vector<double>>& rows, std::size_t a,
                                std::size_t b) {
  std::vector<Point2> out;
  out.reserve(rows.size());
  for (const auto& row : rows) out.push_back({row[a], row[b]});
  return out;
}

Report draw(std::span<const GraphReader> instances, std::span<const SolutionReader> solutions,
            std::span<const SolutionReader> references, const ReportOptions& options) {
  if (instances.empty()) throw Error(ErrorCode::invalid_argument, "a report needs an instance");
  auto benchmarks = benchmarks_of(instances);
  // Binding: every file to its benchmark; one file per solver and binding.
  std::set<std::tuple<std::string, std::size_t, std::size_t, std::string>> seen;
  const auto claim = [&](const std::string& who, std::size_t b, std::size_t i,
                         const SolutionReader& r) {
    if (!seen.emplace(who, b, i, r.query_set()).second)
      throw Error(ErrorCode::invalid_argument,
                  r.display_name() + ": a second file of " + who + " for " + benchmarks[b].name +
                      " on " + instances[i].display_name() + ", query set " + r.query_set());
  };
  for (std::size_t f = 0; f < references.size(); ++f) {
    const auto [b, i] = bind_file(references[f], instances, benchmarks);
    claim("the reference", b, i, references[f]);
    benchmarks[b].references.push_back({f, i});
  }
  std::vector<std::string> solver_names;  // in the order first given
  for (std::size_t f = 0; f < solutions.size(); ++f) {
    const auto [b, i] = bind_file(solutions[f], instances, benchmarks);
    const auto name = solver_name(solutions[f]);
    claim("solver " + name, b, i, solutions[f]);
    auto& files = benchmarks[b].solvers[name];
    if (files.empty()) benchmarks[b].solver_order.push_back(name);
    files.push_back({f, i});
    if (std::find(solver_names.begin(), solver_names.end(), name) == solver_names.end())
      solver_names.push_back(name);
  }

  Report report;
  Page page(report.figures);
  page.out << R"(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="mosb )"
           << kVersion << "\">\n<title>" << Svg::escape(options.title) << "</title>\n<style>\n"
           << kStyle << "</style>\n</head>\n<body>\n<h1>" << Svg::escape(options.title)
           << "</h1>\n";
  page.paragraph(
      std::to_string(instances.size()) + " instance" + (instances.size() == 1 ? "" : "s") + ", " +
      std::to_string(benchmarks.size()) + " benchmark" + (benchmarks.size() == 1 ? "" : "s") +
      ", " + std::to_string(solutions.size()) + " solution file" +
      (solutions.size() == 1 ? "" : "s") + ", " + std::to_string(references.size()) +
      " reference file" + (references.size() == 1 ? "" : "s") + "; written by mosb " + kVersion +
      ". Fronts are drawn with at most " + std::to_string(options.max_points) +
      " vectors per set (thinned past it, the "
      "extremes kept), so the page stays under " +
      std::to_string(options.max_bytes / 1000) + " kB. Click a column heading to sort a table.");
  page.out << "<nav><ul><li><a href=\"#suite\">Suite</a></li><li><a href=\"#instance-space\">"
              "Instance space</a></li>";
  for (const auto& b : benchmarks)
    page.out << "<li><a href=\"#" << anchor(b.name) << "\">" << Svg::escape(b.name) << "</a></li>";
  if (solver_names.size() >= 2)
    page.out << "<li><a href=\"#comparison\">Solver comparison</a></li>";
  page.out << "</ul></nav>\n";

  // Per instance: the ρ of every view's pairs (all arcs and, with a `kind` section, per kind).
  struct ViewStats {
    ArcGroupStats all;
    std::vector<KindGroupStats> by_kind;
  };
  std::vector<std::vector<ViewStats>> stats(benchmarks.size());
  for (std::size_t b = 0; b < benchmarks.size(); ++b)
    for (std::size_t k = 0; k < benchmarks[b].instances.size(); ++k) {
      const auto& g = instances[benchmarks[b].instances[k]];
      const auto& objectives = benchmarks[b].views[k].objectives;
      ViewStats s{objective_stats(g, objectives), {}};
      if (g.find(format::SectionKind::arc_data, "kind") != nullptr)
        s.by_kind = objective_stats_by_kind(g, objectives);
      stats[b].push_back(std::move(s));
    }

  // The suite table: the paper's Table 1, fronts and runtimes from the reference files (else the
  // first solver's).
  Outcomes outcomes;
  {
    Table& t = report.suite;
    t.caption =
        "Benchmarks: size, and the fronts and runtimes of the reference (else the first "
        "solver); front sizes and runtimes over completed queries";
    t.columns = {{"family", "Family", "family"},
                 {"benchmark", "Benchmark", "benchmark"},
                 {"instances", "Inst.", "instances"},
                 {"vertices", "Vertices", "vertices"},
                 {"arcs", "Edges", "arcs"},
                 {"objectives", "$d$", "d"},
                 {"queries", "Queries", "queries"},
                 {"fronts_of", "Fronts of", "fronts of"},
                 {"timeout", "Timeout", "timeout"},
                 {"memory_limit", "Mem-limit", "memory limit"},
                 {"front_min", "$|\\Pi^*|$ min", "front min"},
                 {"front_max", "$|\\Pi^*|$ max", "front max"},
                 {"front_mean", "$|\\Pi^*|$ mean", "front mean"},
                 {"front_median", "$|\\Pi^*|$ med.", "front median"},
                 {"runtime_median", "Med.\\ (s)", "median runtime [s]"},
                 {"runtime_max", "Max (s)", "max runtime [s]"}};
    for (const auto& bm : benchmarks) {
      std::uint64_t n_lo = UINT64_MAX, n_hi = 0, m_lo = UINT64_MAX, m_hi = 0, set_queries = 0;
      for (std::size_t k = 0; k < bm.instances.size(); ++k) {
        const auto& g = instances[bm.instances[k]];
        n_lo = std::min(n_lo, g.vertex_count()), n_hi = std::max(n_hi, g.vertex_count());
        m_lo = std::min(m_lo, g.arc_count()), m_hi = std::max(m_hi, g.arc_count());
        if (!bm.views[k].query_set.empty() &&
            g.find(format::SectionKind::queries, bm.views[k].query_set))
          set_queries += g.queries(bm.views[k].query_set).size();
      }
      std::vector<Cell> row{Cell::of(bm.family),
                            Cell::of(bm.name),
                            Cell::of(std::uint64_t{bm.instances.size()}),
                            range_cell(n_lo, n_hi),
                            range_cell(m_lo, m_hi),
                            Cell::of(std::uint64_t{bm.views.front().objectives.size()})};
      const std::vector<BoundFile>* files = nullptr;
      std::span<const SolutionReader> readers;
      std::string source;
      if (!bm.references.empty()) {
        files = &bm.references, readers = references, source = "reference";
        const auto n = solver_name(references[bm.references.front().file]);
        source += " (" + n + ")";
      } else if (!bm.solver_order.empty()) {
        files = &bm.solvers.at(bm.solver_order.front()), readers = solutions;
        source = bm.solver_order.front();
      }
      if (!files) {
        row.push_back(Cell::of(set_queries));
        row.resize(t.columns.size());
        t.rows.push_back(std::move(row));
        continue;
      }
      std::vector<const SolutionReader*> pooled;
      for (const auto& f : *files) pooled.push_back(&readers[f.file]);
      const auto summary = summarize_completed(pooled);
      row.push_back(Cell::of(summary.statuses.total()));
      row.push_back(Cell::of(source));
      row.push_back(Cell::of(summary.statuses[QueryStatus::timeout]));
      row.push_back(Cell::of(summary.statuses[QueryStatus::memory_limit]));
      if (const auto& d = summary.front_size) {
        row.push_back(Cell::of(d->min));
        row.push_back(Cell::of(d->max));
        row.push_back(Cell::of(d->mean));
        row.push_back(Cell::of(d->median));
      } else {
        row.resize(row.size() + 4);
      }
      const auto& rt = summary.runtime;
      row.push_back(rt ? Cell::of(rt->median) : Cell{});
      row.push_back(rt ? Cell::of(rt->max) : Cell{});
      t.rows.push_back(std::move(row));
    }
    page.out << "<section id=\"suite\">\n<h2>Suite</h2>\n";
    page.out << "<div class=\"scroll\">\n";
    tables::write_html(page.out, t, "suite-table");
    page.out << "</div>\n";
    page.out << "</section>\n";
  }

  // The instance space: ρ against d per benchmark, and per arc kind where the instances have one.
  {
    plots::InstanceSpacePlot plot;
    plot.title = "Instance space: objective correlation against d";
    Table& t = report.instance_space;
    t.caption =
        "Pairwise Pearson correlation of the objectives over the arcs of each benchmark's "
        "instances (and over the arcs of each kind where an instance has arc kinds)";
    t.columns = {{"series", "Benchmark", "benchmark"},
                 {"objectives", "$d$", "d"},
                 {"pairs", "Pairs", "pairs"},
                 {"rho_min", "$\\rho$ min", "ρ min"},
                 {"rho_mean", "$\\rho$ mean", "ρ mean"},
                 {"rho_max", "$\\rho$ max", "ρ max"}};
    for (std::size_t b = 0; b < benchmarks.size(); ++b) {
      const std::size_t d = benchmarks[b].views.front().objectives.size();
      std::vector<double> all;
      std::map<std::uint8_t, std::vector<double>> by_kind;
      for (const auto& s : stats[b]) {
        for (const auto& c : s.all.correlations)
          if (c.rho) all.push_back(*c.rho);
        for (const auto& k : s.by_kind)
          for (const auto& c : k.stats.correlations)
            if (c.rho) by_kind[k.kind].push_back(*c.rho);
      }
      const auto add = [&](std::string name, std::vector<double> rho) {
        std::vector<Cell> row{Cell::of(name), Cell::of(std::uint64_t{d}),
                              Cell::of(std::uint64_t{rho.size()})};
        if (rho.empty()) {
          row.resize(t.columns.size());
        } else {
          double sum = 0;
          for (double r : rho) sum += r;
          row.push_back(Cell::of(*std::min_element(rho.begin(), rho.end())));
          row.push_back(Cell::of(sum / static_cast<double>(rho.size())));
          row.push_back(Cell::of(*std::max_element(rho.begin(), rho.end())));
        }
        t.rows.push_back(std::move(row));
        plot.series.push_back({std::move(name), d, std::move(rho)});
      };
      add(benchmarks[b].name, all);
      if (by_kind.size() > 1)
        for (auto& [kind, rho] : by_kind)
          add(benchmarks[b].name + ", arcs of kind " + std::to_string(kind), rho);
    }
    page.out << "<section id=\"instance-space\">\n<h2>Instance space</h2>\n";
    page.figure("instance-space", plots::plot_instance_space(plot),
                "Each benchmark at its number of objectives d: the line spans its smallest to "
                "largest pairwise ρ (ends marked), each faint dot is one pair of one instance. "
                "Benchmarks with arc kinds (NetMaker: kind 0 the Hamiltonian cycle, kind 1 the "
                "locality arcs) also have a series per kind.");
    page.out << "<div class=\"scroll\">\n";
    tables::write_html(page.out, t, "instance-space-table");
    page.out << "</div>\n";
    page.out << "</section>\n";
  }

  // Per benchmark: ρ matrix, degrees, the map of a grid, the fronts of selected queries.
  for (std::size_t b = 0; b < benchmarks.size(); ++b) {
    const auto& bm = benchmarks[b];
    const auto& g = instances[bm.instances.front()];
    const auto& view = bm.views.front();
    page.out << "<section id=\"" << anchor(bm.name) << "\">\n<h2>" << Svg::escape(bm.name)
             << "</h2>\n";
    page.paragraph("family " + (bm.family.empty() ? std::string("unknown") : bm.family) + "; " +
                   std::to_string(bm.instances.size()) + " instance" +
                   (bm.instances.size() == 1 ? "" : "s") + "; objectives " +
                   objective_names(g, view) +
                   (bm.instances.size() > 1 ? "; the figures below are of " + g.display_name()
                                            : std::string()));
    plots::CorrelationPlot rho;
    rho.title = bm.name + ": objective correlation";
    const std::size_t d = view.objectives.size();
    rho.rho.assign(d, std::vector<std::optional<double>>(d));
    for (std::size_t i = 0; i < d; ++i) {
      rho.names.push_back(g.objective(view.objectives[i]).name);
      rho.rho[i][i] = 1.0;
    }
    for (const auto& c : stats[b].front().all.correlations)
      rho.rho[c.first][c.second] = rho.rho[c.second][c.first] = c.rho;
    if (d >= 2) page.figure("correlation", plots::plot_correlation(rho), "Pearson ρ over all arcs");

    plots::DegreePlot degrees;
    degrees.title = bm.name + ": out-degree distribution";
    const auto offsets = g.forward_offsets();
    for (std::size_t v = 0; v + 1 < offsets.size(); ++v) {
      const auto deg = offsets[v + 1] - offsets[v];
      if (deg >= degrees.vertices_by_degree.size()) degrees.vertices_by_degree.resize(deg + 1, 0);
      ++degrees.vertices_by_degree[deg];
    }
    page.figure("degrees", plots::plot_degrees(degrees), "Vertices per out-degree");

    // The file whose fronts are drawn, and the one overlaid on it.
    const SolutionReader* shown = nullptr;
    const SolutionReader* overlay = nullptr;
    std::size_t shown_instance = 0;
    if (!bm.references.empty()) {
      shown = &references[bm.references.front().file];
      shown_instance = bm.references.front().instance;
      // The first other solver's (the reference is often one of the solvers' files too).
      for (const auto& name : bm.solver_order)
        for (const auto& f : bm.solvers.at(name))
          if (!overlay && name != solver_name(*shown) && f.instance == shown_instance &&
              solutions[f.file].query_set() == shown->query_set())
            overlay = &solutions[f.file];
    } else if (!bm.solver_order.empty()) {
      const auto& f = bm.solvers.at(bm.solver_order.front()).front();
      shown = &solutions[f.file];
      shown_instance = f.instance;
    }
    const auto queries =
        shown ? chosen_queries(*shown, options.queries) : std::vector<std::uint64_t>{};

    if (g.metadata().get("map.width") && g.find(format::SectionKind::vertex_data, "cell")) {
      auto map = plots::map_of(g, "exposure");
      map.title = bm.name + ": map of " + g.display_name();
      map.exposure_unit = g.metadata().get("objective.exposure.unit").value_or("");
      // Start and goal of the drawn queries, else the first three of the view's query set (of
      // the instance's first set when the view names none).
      std::string set =
          shown && shown_instance == bm.instances.front() ? shown->query_set() : view.query_set;
      if (const auto sets = g.all(format::SectionKind::queries); set.empty() && !sets.empty())
        set = sets.front()->name;
      std::vector<std::uint64_t> marked =
          shown_instance == bm.instances.front() ? queries : std::vector<std::uint64_t>{};
      if (!set.empty() && g.find(format::SectionKind::queries, set)) {
        const auto qs = g.queries(set);
        if (marked.empty())
          for (std::uint64_t q = 0; q < qs.size() && q < 3; ++q) marked.push_back(q);
        plots::add_query_markers(map, g, set, marked);
      }
      map = plots::coarsen_map(map, options.max_map_side);
      page.figure("map", plots::plot_map(map),
                  map.guards.empty()
                      ? "Blocked cells dark grey, passable cells shaded by exposure; starts and "
                        "goals of the queries drawn below. No guard is marked: the instance "
                        "records each cell's exposure, not where guards stand (converted from an "
                        "exposure grid, or before mosb 0.2.0 wrote map.guards)."
                      : "Blocked cells dark grey, passable cells shaded by exposure, guards black "
                        "dots; starts and goals of the queries drawn below.");
    }

    if (!shown) {
      page.out << "<p class=\"note\">No solution file for this benchmark: no fronts.</p>\n";
    } else if (queries.empty()) {
      page.out << "<p class=\"note\">" << Svg::escape(shown->display_name())
               << ": no solved query with a non-empty front to draw.</p>\n";
    }
    if (shown)
      for (const auto q : options.queries)
        if (std::find(queries.begin(), queries.end(), q) == queries.end())
          page.out << "<p class=\"note\">Query " << q << ": not a solved query with a front in "
                   << Svg::escape(shown->display_name()) << ", not drawn.</p>\n";
    const auto shown_name = shown ? solver_name(*shown) : std::string();
    if (d < 2 && !queries.empty())
      page.out << "<p class=\"note\">One objective: each front is a single value, not drawn."
               << "</p>\n";
    for (const auto q : d < 2 ? std::vector<std::uint64_t>{} : queries) {
      const auto rows = front_rows(*shown, q);
      std::vector<std::vector<double>> other;
      if (overlay && q < overlay->query_count() && overlay->status(q) == QueryStatus::solved)
        other = front_rows(*overlay, q);
      const bool is_reference = !bm.references.empty();
      const std::string what = "query " + std::to_string(q) + " of " + shown->query_set() + " on " +
                               instances[shown_instance].display_name();
      const std::string counts =
          std::to_string(rows.size()) + " vectors" +
          (overlay ? ", " + solver_name(*overlay) + " " + std::to_string(other.size())
                   : std::string());
      if (d <= 3) {
        std::vector<std::pair<std::size_t, std::size_t>> pairs = {{0, 1}};
        if (d == 3) pairs = {{0, 1}, {0, 2}, {1, 2}};
        for (const auto& [a, c] : pairs) {
          plots::FrontPlot front;
          front.title = bm.name + ", " + what;
          front.x_label = shown->objective_name(a);
          front.y_label = shown->objective_name(c);
          front.objective_count = d;
          front.max_points = options.max_points;
          if (is_reference) {
            front.reference = pair_points(rows, a, c);
            front.reference_name = "reference " + shown_name;
            if (overlay) {
              front.solution = pair_points(other, a, c);
              front.solver_name = solver_name(*overlay);
            }
          } else {
            front.solution = pair_points(rows, a, c);
            front.solver_name = shown_name;
          }
          page.figure("front", plots::plot_front(front),
                      "Front of " + what + " (" + counts + ")" +
                          (d == 3 ? ": projection on " + front.x_label + ", " + front.y_label
                                  : std::string()));
        }
      } else {
        plots::ParallelPlot par;
        par.title = bm.name + ", " + what;
        par.subtitle = "parallel coordinates of " + std::to_string(d) + " objectives";
        for (std::size_t i = 0; i < d; ++i) par.axes.push_back(shown->objective_name(i));
        if (is_reference) {
          par.reference = rows;
          par.reference_name = "reference " + shown_name;
          if (overlay) par.solution = other, par.solver_name = solver_name(*overlay);
        } else {
          par.solution = rows;
          par.solver_name = shown_name;
        }
        page.figure("front", plots::plot_parallel(par), "Front of " + what + " (" + counts + ")");
      }
    }
    page.out << "</section>\n";
  }

  // Solver comparison.
  for (std::size_t b = 0; b < benchmarks.size(); ++b)
    for (const auto& [name, files] : benchmarks[b].solvers)
      for (const auto& f : files) {
        const auto& r = solutions[f.file];
        for (std::uint64_t q = 0; q < r.query_count(); ++q)
          outcomes[{b, f.instance, r.query_set(), q}][name] = {r.status(q), r.runtime_seconds(q)};
      }
  if (solver_names.size() >= 2) {
    page.out << "<section id=\"comparison\">\n<h2>Solver comparison</h2>\n";
    Table& t = report.comparison;
    t.caption =
        "Solvers per benchmark: timeouts and memory limits over each solver's queries; "
        "median and max runtime over the queries every solver of the benchmark completed";
    t.columns = {{"family", "Family", "family"},
                 {"benchmark", "Benchmark", "benchmark"},
                 {"queries", "Queries", "queries"},
                 {"common", "Common", "completed by all"}};
    for (const auto& s : solver_names) {
      const auto k = key_of(s);
      std::string latex;
      for (char c : s)
        latex += (c == '_' || c == '&' || c == '%' || c == '#') ? std::string("\\") + c
                                                                : std::string(1, c);
      t.columns.push_back({"timeout@" + k, latex + " Timeout", s + " timeout"});
      t.columns.push_back({"memory_limit@" + k, latex + " Mem-limit", s + " memory limit"});
      t.columns.push_back({"runtime_median@" + k, latex + " Med.\\ (s)", s + " median [s]"});
      t.columns.push_back({"runtime_max@" + k, latex + " Max (s)", s + " max [s]"});
    }
    for (std::size_t b = 0; b < benchmarks.size(); ++b) {
      if (benchmarks[b].solvers.empty()) continue;
      std::map<std::string, std::uint64_t> timeouts, memory;
      std::map<std::string, std::vector<double>> runtimes;
      std::uint64_t queries = 0, common = 0;
      for (const auto& [key, by_solver] : outcomes) {
        if (key.benchmark != b) continue;
        ++queries;
        bool all = by_solver.size() == benchmarks[b].solvers.size();
        for (const auto& [name, o] : by_solver) {
          timeouts[name] += o.status == QueryStatus::timeout;
          memory[name] += o.status == QueryStatus::memory_limit;
          all = all && o.completed() && o.runtime;
        }
        if (!all) continue;
        ++common;
        for (const auto& [name, o] : by_solver) runtimes[name].push_back(*o.runtime);
      }
      std::vector<Cell> row{Cell::of(benchmarks[b].family), Cell::of(benchmarks[b].name),
                            Cell::of(queries), Cell::of(common)};
      for (const auto& s : solver_names) {
        if (!benchmarks[b].solvers.contains(s)) {
          row.resize(row.size() + 4);
          continue;
        }
        row.push_back(Cell::of(timeouts[s]));
        row.push_back(Cell::of(memory[s]));
        const auto runtime = distribution_of(runtimes[s]);
        row.push_back(runtime ? Cell::of(runtime->median) : Cell{});
        row.push_back(runtime ? Cell::of(runtime->max) : Cell{});
      }
      t.rows.push_back(std::move(row));
    }
    page.out << "<div class=\"scroll\">\n";
    tables::write_html(page.out, t, "comparison-table");
    page.out << "</div>\n";

    // Cactus plot: each solver's solved queries by runtime.
    plots::LinePlot cactus;
    cactus.title = "Cactus plot: queries solved within a time";
    cactus.x_label = "queries solved";
    cactus.y_label = "runtime [s] (log scale)";
    cactus.y_log = true;
    for (const auto& s : solver_names) {
      std::vector<double> times;
      for (const auto& [key, by_solver] : outcomes) {
        const auto it = by_solver.find(s);
        if (it != by_solver.end() && it->second.status == QueryStatus::solved && it->second.runtime)
          times.push_back(*it->second.runtime);
      }
      std::sort(times.begin(), times.end());
      plots::LineSeries series{s + " (" + std::to_string(times.size()) + " solved)", {}};
      for (std::size_t k = 0; k < times.size(); ++k)
        series.points.push_back({static_cast<double>(k + 1), times[k]});
      cactus.series.push_back(std::move(series));
    }
    page.figure(
        "cactus", plots::plot_lines(cactus),
        "Each solver's solved queries sorted by runtime: a point (k, t) says k queries were "
        "solved within t seconds each. Lower and further right is better.");

    // Performance profile over the queries every solver has a file for and some solver solved.
    plots::LinePlot profile;
    profile.title = "Performance profile (Dolan–Moré)";
    profile.x_label = "τ: runtime / best runtime (log scale)";
    profile.y_label = "fraction of queries within τ";
    profile.x_log = true;
    profile.steps = true;
    profile.x_min = 1;
    profile.y_max = 1;
    std::map<std::string, std::vector<double>> ratios;
    std::size_t profiled = 0;
    for (const auto& [key, by_solver] : outcomes) {
      if (by_solver.size() != solver_names.size()) continue;
      double best = std::numeric_limits<double>::infinity();
      for (const auto& [name, o] : by_solver)
        if (o.status == QueryStatus::solved && o.runtime) best = std::min(best, *o.runtime);
      if (!std::isfinite(best)) continue;
      ++profiled;
      constexpr double kFloor = 1e-6;  // a runtime of 0 s still divides
      for (const auto& [name, o] : by_solver)
        if (o.status == QueryStatus::solved && o.runtime)
          ratios[name].push_back(std::max(*o.runtime, kFloor) / std::max(best, kFloor));
    }
    for (const auto& s : solver_names) {
      auto r = ratios[s];
      std::sort(r.begin(), r.end());
      plots::LineSeries series{s, {}};
      for (std::size_t k = 0; k < r.size(); ++k)
        if (k + 1 == r.size() || r[k + 1] != r[k])
          series.points.push_back(
              {r[k], static_cast<double>(k + 1) / static_cast<double>(profiled)});
      if (!series.points.empty() && series.points.front().x > 1)
        series.points.insert(series.points.begin(), {1, 0});
      profile.series.push_back(std::move(series));
    }
    page.figure("profile", plots::plot_lines(profile),
                "Over the " + std::to_string(profiled) +
                    " queries every solver ran and some solver solved: the fraction of them a "
                    "solver solved within τ times the best solver's runtime. Unsolved queries "
                    "never count.");

    // Runtime scatter: the first solver against each other one.
    for (std::size_t k = 1; k < solver_names.size(); ++k) {
      const auto& a = solver_names.front();
      const auto& c = solver_names[k];
      plots::ScatterPlot scatter;
      scatter.title = "Runtime per query: " + a + " against " + c;
      scatter.x_label = a + " runtime [s]";
      scatter.y_label = c + " runtime [s]";
      std::map<std::size_t, plots::LineSeries> groups;
      std::uint64_t one_only = 0;
      for (const auto& [key, by_solver] : outcomes) {
        const auto ia = by_solver.find(a), ic = by_solver.find(c);
        if (ia == by_solver.end() || ic == by_solver.end()) continue;
        const bool both = ia->second.completed() && ia->second.runtime && ic->second.completed() &&
                          ic->second.runtime;
        if (!both) {
          one_only += ia->second.completed() || ic->second.completed();
          continue;
        }
        auto& group = groups[key.benchmark];
        group.name = benchmarks[key.benchmark].name;
        group.points.push_back({*ia->second.runtime, *ic->second.runtime});
      }
      for (auto& [bi, group] : groups) scatter.groups.push_back(std::move(group));
      if (one_only > 0)
        scatter.note = std::to_string(one_only) + " quer" + (one_only == 1 ? "y" : "ies") +
                       " completed by one of the two only, not drawn";
      page.figure(
          "scatter", plots::plot_runtime_scatter(scatter),
          "One dot per query both completed, log–log; above the diagonal " + a + " was faster.");
    }

    // ε-coverage per solver, against each binding's reference.
    if (!options.epsilons.empty()) {
      std::map<std::string, std::vector<EpsilonOutcome>> coverage;
      for (const auto& bm : benchmarks)
        for (const auto& ref : bm.references) {
          const auto& reference = references[ref.file];
          std::vector<SolutionReader> group;
          for (const auto& name : bm.solver_order)
            for (const auto& f : bm.solvers.at(name))
              if (f.instance == ref.instance &&
                  solutions[f.file].query_set() == reference.query_set())
                group.push_back(solutions[f.file]);
          if (group.empty()) continue;
          const auto result = compare_solvers(reference, group, options.epsilons);
          for (const auto& s : result.solvers) {
            auto& total = coverage[solver_name(group[&s - result.solvers.data()])];
            total.resize(options.epsilons.size());
            for (std::size_t e = 0; e < total.size(); ++e) {
              total[e].covered += s.per_epsilon[e].covered;
              total[e].not_covered += s.per_epsilon[e].not_covered;
            }
          }
        }
      if (!coverage.empty()) {
        Table& c = report.coverage;
        c.caption =
            "ε-coverage: queries both the solver and the reference solved whose reference "
            "front the solver's covers at ε";
        c.columns = {{"solver", "Solver", "solver"}, {"evaluated", "Queries", "queries"}};
        for (const auto& e : options.epsilon_labels)
          c.columns.push_back(
              {"covered@" + e, "cov.\\ $\\varepsilon{=}" + e + "$", "covered at ε = " + e});
        plots::BarPlot bars;
        bars.title = "ε-coverage per solver";
        bars.x_label = "ε";
        bars.y_label = "fraction of queries covered";
        for (const auto& e : options.epsilon_labels) bars.categories.push_back("ε = " + e);
        for (const auto& s : solver_names) {
          const auto it = coverage.find(s);
          if (it == coverage.end()) continue;
          const auto evaluated = it->second.front().covered + it->second.front().not_covered;
          std::vector<Cell> row{Cell::of(s), Cell::of(evaluated)};
          plots::BarSeries series{s, {}};
          for (const auto& o : it->second) {
            row.push_back(Cell::of(o.covered));
            series.values.push_back(
                evaluated ? static_cast<double>(o.covered) / static_cast<double>(evaluated) : 0);
          }
          c.rows.push_back(std::move(row));
          bars.series.push_back(std::move(series));
        }
        page.figure("coverage", plots::plot_bars(bars),
                    "Per solver and ε, the share of the queries it and the reference solved whose "
                    "reference front it ε-covers (spec/EVALUATION.md §1).");
        page.out << "<div class=\"scroll\">\n";
        tables::write_html(page.out, c, "coverage-table");
        page.out << "</div>\n";
      }
    }
    page.out << "</section>\n";
  }
  page.out << "<script>\n" << kScript << "</script>\n</body>\n</html>\n";
  report.html = page.out.str();
  return report;
}

}  // namespace

Report make_report(std::span<const GraphReader> instances,
                   std::span<const SolutionReader> solutions,
                   std::span<const SolutionReader> references, const ReportOptions& options) {
  constexpr std::size_t kFewestPoints = 50;
  auto current = options;
  for (;;) {
    auto report = draw(instances, solutions, references, current);
    if (report.html.size() <= options.max_bytes) return report;
    if (current.max_points <= kFewestPoints)
      throw Error(ErrorCode::invalid_argument,
                  "the report would be " + std::to_string(report.html.size()) +
                      " bytes even with fronts thinned to " + std::to_string(current.max_points) +
                      " points, over the limit of " + std::to_string(options.max_bytes) +
                      " bytes: give a larger --max-size, or fewer instances or --queries");
    current.max_points = std::max(kFewestPoints, current.max_points / 2);
  }
}

}  // namespace mosb::pages
