#include "mosb/report/report.hpp"

#include <algorithm>
#include <cmath>
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
#include "mosb/runtime_figures.hpp"
#include "mosb/solution_summary.hpp"
#include "mosb/solver_comparison.hpp"
#include "mosb/stats.hpp"
#include "mosb/version.hpp"

namespace mosb::pages {

namespace {

using plots::Svg;
using tables::Cell;
using tables::Column;
using tables::Table;

// One solution file bound to a benchmark's instance.
struct BoundFile {
  std::size_t file = 0;      // index into the solutions or references
  std::size_t instance = 0;  // index into the instances
};

struct Benchmark {
  std::string name, family;
  std::string key;                     // [a-z0-9_.], unique on the page (unique_keys)
  std::string anchor;                  // its section's id: "b-" and its key
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

// The keys of `names`, in order: each name's key_of, with _2, _3, ... appended where an earlier
// name took it (names that differ only by case or punctuation), so that no two names share a key.
std::vector<std::string> unique_keys(const std::vector<std::string>& names) {
  std::set<std::string> taken;
  std::vector<std::string> keys;
  for (const auto& name : names) {
    std::string key = key_of(name);
    for (std::size_t n = 2; !taken.insert(key).second; ++n)
      key = key_of(name) + "_" + std::to_string(n);
    keys.push_back(std::move(key));
  }
  return keys;
}

std::string objective_names(const GraphReader& g, const View& v) {
  std::string out;
  for (auto i : v.objectives) out += (out.empty() ? "" : ", ") + g.objective(i).name;
  return out;
}

// A view the suite names as a benchmark of its own, NAME_d with d its number of objectives
// (Grid_2, NetMaker-10k_3, Games-GUARDS_2, DIMACS-Extended-NY_4): the suite groups every instance
// that has it into that one benchmark. Any other view ("length", a Moving AI map's) is a view of
// one instance's own benchmark.
bool is_suite_benchmark_view(const View& v) {
  const auto separator = v.name.rfind('_');
  return separator != std::string::npos && separator > 0 &&
         v.name.substr(separator + 1) == std::to_string(v.objectives.size());
}

// The instance's name on the page: its `benchmark` metadata, else its file's display name.
std::string instance_name(const GraphReader& g) {
  return g.metadata().get("benchmark").value_or(g.display_name());
}

// The benchmarks of the instances, in the order of first appearance: a suite benchmark view
// (is_suite_benchmark_view) groups the instances that have it under the view's name; any other
// view is the benchmark of its instance, named by the instance (INSTANCE/VIEW when the instance
// has more than one such view); an instance without views is one benchmark of all its objectives.
std::vector<Benchmark> benchmarks_of(std::span<const GraphReader> instances,
                                     const ReportOptions& options) {
  std::vector<Benchmark> out;
  std::map<std::string, std::size_t> by_name;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const auto& g = instances[i];
    auto views = g.views();
    // An experiment's instances: only the views it ran (ReportOptions::views).
    if (const auto only = options.views.find(g.digest()); only != options.views.end())
      std::erase_if(views, [&](const View& v) { return !only->second.contains(v.name); });
    if (views.empty()) {
      View all;
      all.name = instance_name(g);
      for (std::size_t k = 0; k < g.objective_count(); ++k) all.objectives.push_back(k);
      views.push_back(all);
    }
    const auto own_views = std::count_if(views.begin(), views.end(),
                                         [](const View& v) { return !is_suite_benchmark_view(v); });
    for (auto& v : views) {
      const auto name = is_suite_benchmark_view(v) || g.views().empty() ? v.name
                        : own_views > 1 ? instance_name(g) + "/" + v.name
                                        : instance_name(g);
      auto [at, added] = by_name.emplace(name, out.size());
      if (added) {
        out.emplace_back();
        out.back().name = name;
        out.back().family = g.metadata().get("family").value_or("");
      }
      out[at->second].instances.push_back(i);
      out[at->second].views.push_back(std::move(v));
    }
  }
  std::vector<std::string> names;
  names.reserve(out.size());
  for (const auto& b : out) names.push_back(b.name);
  const auto keys = unique_keys(names);
  for (std::size_t b = 0; b < out.size(); ++b) {
    out[b].key = keys[b];
    out[b].anchor = "b-" + keys[b];
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
    R"(document.querySelectorAll("table.sortable thead tr:last-child th").forEach(function(th){th.tabIndex=0;
th.addEventListener("keydown",function(e){if(e.key==="Enter"||e.key===" "){e.preventDefault();th.click();}});
th.addEventListener("click",function(){
var row=th.parentNode,table=row.closest("table"),body=table.tBodies[0],col=Array.prototype.indexOf.call(row.children,th);
var up=th.getAttribute("aria-sort")!=="ascending";Array.prototype.forEach.call(row.children,function(h){h.removeAttribute("aria-sort");});
th.setAttribute("aria-sort",up?"ascending":"descending");
function key(tr){var c=tr.cells[col],v=c.getAttribute("data-v");return v===null?c.textContent:(v===""?-Infinity:parseFloat(v));}
var rows=Array.prototype.slice.call(body.rows);rows.sort(function(a,b){var x=key(a),y=key(b),r=typeof x==="number"&&typeof y==="number"?(x<y?-1:x>y?1:0):String(x).localeCompare(String(y));return up?r:-r;});
rows.forEach(function(r){body.appendChild(r);});});});
)";

// The page being written: its HTML and, for --figures, --latex and --csv, each of its figures and
// tables alone (kept in the report).
class Page {
 public:
  explicit Page(Report& report) : report_(report) {}
  std::ostringstream out;
  void section(const std::string& id, const std::string& heading) {
    out << "<section id=\"" << id << "\">\n<h2>" << Svg::escape(heading) << "</h2>\n";
  }
  void end_section() { out << "</section>\n"; }
  void paragraph(const std::string& text) { out << "<p>" << Svg::escape(text) << "</p>\n"; }
  void note(const std::string& text) {
    out << "<p class=\"note\">" << Svg::escape(text) << "</p>\n";
  }
  void figure(const std::string& kind, const std::string& svg, const std::string& caption,
              const std::string& name = {}) {
    report_.figures.push_back({kind, svg, name.empty() ? kind : name});
    out << "<figure data-figure=\"" << Svg::escape(kind) << "\">\n"
        << inline_svg(svg) << "<figcaption>" << Svg::escape(caption)
        << "</figcaption>\n</figure>\n";
  }
  // Writes `table` (in a box that scrolls sideways) and keeps it as the report's `kept`.
  void table(Table Report::*kept, Table table, const std::string& id) {
    report_.*kept = std::move(table);
    out << "<div class=\"scroll\">\n";
    tables::write_html(out, report_.*kept, id);
    out << "</div>\n";
  }

 private:
  Report& report_;
};

// Per instance of a benchmark: the ρ of its view's pairs over all arcs and, where the instance
// has a `kind` section, over the arcs of each kind.
struct ViewStats {
  ArcGroupStats all;
  std::vector<KindGroupStats> by_kind;
};

// What the page's sections read: the inputs, bound into benchmarks, and what is computed of them
// once. The sections only write to `page` (a reference, so they take the context as const).
struct Context {
  std::span<const GraphReader> instances;
  std::span<const SolutionReader> solutions, references;
  const ReportOptions& options;
  Page& page;
  std::vector<Benchmark> benchmarks;            // each with its solution and reference files
  std::span<const std::string> notes;           // about the inputs, under the head's paragraph
  std::vector<std::string> solver_names;        // every solver, in the order first given
  std::vector<std::string> solver_keys;         // of each solver, for file names: unique_keys
  RuntimeSource runtime = RuntimeSource::wall;  // what every runtime shown is (choose_runtime)
  std::string runtime_text;                     // how captions name it (runtime_caption)
  std::vector<std::vector<ViewStats>> stats;    // per benchmark, per instance
  Outcomes outcomes;
  // Per benchmark, per solver its ε-coverage (one entry per options.epsilons) summed over the
  // benchmark's bindings that have a reference; empty without references or ε.
  std::vector<std::map<std::string, std::vector<EpsilonOutcome>>> coverage;
  bool approximation = false;  // some benchmark has an approximate solver and a reference
};

// Binds every file to its benchmark (one file per solver, or reference, and binding) and names
// the solvers; throws naming the first file that does not belong.
void bind_files(Context& c) {
  std::set<std::tuple<std::string, std::size_t, std::size_t, std::string>> seen;
  const auto claim = [&](const std::string& who, std::size_t b, std::size_t i,
                         const SolutionReader& r) {
    if (!seen.emplace(who, b, i, r.query_set()).second)
      throw Error(ErrorCode::invalid_argument,
                  r.display_name() + ": a second file of " + who + " for " + c.benchmarks[b].name +
                      " on " + c.instances[i].display_name() + ", query set " + r.query_set());
  };
  for (std::size_t f = 0; f < c.references.size(); ++f) {
    const auto [b, i] = bind_file(c.references[f], c.instances, c.benchmarks);
    claim("the reference", b, i, c.references[f]);
    c.benchmarks[b].references.push_back({f, i});
  }
  for (std::size_t f = 0; f < c.solutions.size(); ++f) {
    const auto [b, i] = bind_file(c.solutions[f], c.instances, c.benchmarks);
    const auto name = solver_name(c.solutions[f]);
    claim("solver " + name, b, i, c.solutions[f]);
    auto& files = c.benchmarks[b].solvers[name];
    if (files.empty()) c.benchmarks[b].solver_order.push_back(name);
    files.push_back({f, i});
    if (std::find(c.solver_names.begin(), c.solver_names.end(), name) == c.solver_names.end())
      c.solver_names.push_back(name);
  }
  c.solver_keys = unique_keys(c.solver_names);
  // The solvers' runtimes decide; without solvers, the references' (their first solver's).
  std::vector<const SolutionReader*> files;
  for (const auto& f : c.solutions.empty() ? c.references : c.solutions) files.push_back(&f);
  c.runtime = choose_runtime(files, c.options.runtime);
  c.runtime_text = runtime_caption(c.runtime, files);
  const auto& baseline = c.options.baseline;
  if (!baseline.empty() &&
      std::find(c.solver_names.begin(), c.solver_names.end(), baseline) == c.solver_names.end()) {
    std::string names;
    for (const auto& n : c.solver_names) names += (names.empty() ? "" : ", ") + n;
    throw Error(ErrorCode::invalid_argument,
                "baseline " + baseline + ": no solution file of that solver (the solvers: " +
                    (names.empty() ? "none" : names) + ")");
  }
}

// Computed once: the instance space and each benchmark's ρ matrix read them.
std::vector<std::vector<ViewStats>> view_stats(const Context& c) {
  std::vector<std::vector<ViewStats>> stats(c.benchmarks.size());
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b)
    for (std::size_t k = 0; k < c.benchmarks[b].instances.size(); ++k) {
      const auto& g = c.instances[c.benchmarks[b].instances[k]];
      const auto& objectives = c.benchmarks[b].views[k].objectives;
      ViewStats s{objective_stats(g, objectives), {}};
      if (g.find(format::SectionKind::arc_data, "kind") != nullptr)
        s.by_kind = objective_stats_by_kind(g, objectives);
      stats[b].push_back(std::move(s));
    }
  return stats;
}

// Every solver's status and runtime of every query it has a file for: the comparison's data.
Outcomes outcomes_of(const Context& c) {
  Outcomes outcomes;
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b)
    for (const auto& [name, files] : c.benchmarks[b].solvers)
      for (const auto& f : files) {
        const auto& r = c.solutions[f.file];
        for (std::uint64_t q = 0; q < r.query_count(); ++q)
          outcomes[{b, f.instance, r.query_set(), q}][name] = {
              r.status(q), r.seconds_statistic(runtime_statistic(c.runtime), q)};
      }
  return outcomes;
}

// "1 instance", "2 instances".
std::string count_of(std::size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// The files whose fronts and runtimes a benchmark's summary and figures show: its reference files,
// else its first solver's; none when it has neither.
struct FrontFiles {
  const std::vector<BoundFile>* files = nullptr;
  std::span<const SolutionReader> readers;  // what `files` index
  bool of_reference = false;
};

FrontFiles front_files(const Context& c, const Benchmark& bm) {
  if (!bm.references.empty()) return {&bm.references, c.references, true};
  if (!bm.solver_order.empty()) return {&bm.solvers.at(bm.solver_order.front()), c.solutions};
  return {};
}

// --- The head: title, what the page holds, the sections' links.

void write_head(const Context& c) {
  const auto& title = c.options.title;
  c.page.out << R"(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="mosb )"
             << kVersion << "\">\n<title>" << Svg::escape(title) << "</title>\n<style>\n"
             << kStyle << "</style>\n</head>\n<body>\n<h1>" << Svg::escape(title) << "</h1>\n";
  c.page.paragraph(
      count_of(c.instances.size(), "instance") + ", " + count_of(c.benchmarks.size(), "benchmark") +
      ", " + count_of(c.solutions.size(), "solution file") + ", " +
      count_of(c.references.size(), "reference file") + "; written by mosb " + kVersion +
      ". Fronts are drawn with at most " + std::to_string(c.options.max_points) +
      " vectors per set (thinned past it, the extremes kept), so the page stays under " +
      std::to_string(c.options.max_bytes / 1000) + " kB. Click a column heading to sort a table.");
  for (const auto& note : c.notes) c.page.note(note);
  c.page.out << "<nav><ul><li><a href=\"#suite\">Suite</a></li><li><a href=\"#instance-space\">"
                "Instance space</a></li>";
  for (const auto& b : c.benchmarks)
    c.page.out << "<li><a href=\"#" << b.anchor << "\">" << Svg::escape(b.name) << "</a></li>";
  if (c.solver_names.size() >= 2)
    c.page.out << "<li><a href=\"#comparison\">Solver comparison</a></li>";
  if (c.approximation) c.page.out << "<li><a href=\"#approximation\">Approximation</a></li>";
  c.page.out << "</ul></nav>\n";
}

// --- The fronts' spread per objective (the paper's spread table).

// Per objective of benchmark b, the spread max/min of each front of its front_files along it, over
// the solved queries whose front has two vectors or more and a minimum above 0 there (a spread is
// otherwise not defined: degenerate).
void spread_rows(const Context& c, std::size_t b, std::vector<std::vector<Cell>>& rows) {
  const auto& bm = c.benchmarks[b];
  const auto fronts = front_files(c, bm);
  if (!fronts.files) return;
  const auto& first = fronts.readers[fronts.files->front().file];
  const std::size_t d = first.objective_count();
  std::vector<std::vector<double>> spreads(d);
  for (const auto& f : *fronts.files) {
    const auto& r = fronts.readers[f.file];
    for (std::uint64_t q = 0; q < r.query_count(); ++q) {
      if (r.status(q) != QueryStatus::solved || r.front_size(q) < 2) continue;
      const auto begin = r.front_begin(q), end = begin + r.front_size(q);
      for (std::size_t i = 0; i < d; ++i) {
        double lo = std::numeric_limits<double>::infinity(), hi = 0;
        for (auto row = begin; row < end; ++row) {
          const double v = r.value_as_double(i, row);
          lo = std::min(lo, v), hi = std::max(hi, v);
        }
        if (lo > 0) spreads[i].push_back(hi / lo);
      }
    }
  }
  for (std::size_t i = 0; i < d; ++i) {
    const auto dist = distribution_of(spreads[i]);
    rows.push_back({Cell::of(bm.family), Cell::of(bm.name), Cell::of(first.objective_name(i)),
                    Cell::of(std::uint64_t{spreads[i].size()}),
                    dist ? Cell::of(dist->mean) : Cell{}, dist ? Cell::of(dist->median) : Cell{},
                    dist ? Cell::of(dist->max) : Cell{}});
  }
}

void write_spread(const Context& c) {
  Table t;
  t.caption =
      "Spread (max/min ratio) of the fronts (of the reference, else the first solver) "
      "along each objective, over the solved queries with a defined spread (two vectors "
      "or more, a minimum above 0)";
  t.columns = {{"family", "Family", "family"},
               {"benchmark", "Benchmark", "benchmark"},
               {"objective", "Objective", "objective"},
               {"queries", "Queries", "queries"},
               {"spread_mean", "Avg.\\ spread", "mean spread"},
               {"spread_median", "Med.\\ spread", "median spread"},
               {"spread_max", "Max spread", "max spread"}};
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b) spread_rows(c, b, t.rows);
  if (t.rows.empty()) return;
  c.page.paragraph("How far each objective varies along the fronts:");
  c.page.table(&Report::spread, std::move(t), "spread-table");
}

// --- The suite table: the paper's Table 1.

// A runtime distribution's median and max cells, absent without one.
void add_median_and_max(std::vector<Cell>& row, const std::optional<Distribution>& d) {
  row.push_back(d ? Cell::of(d->median) : Cell{});
  row.push_back(d ? Cell::of(d->max) : Cell{});
}

// Bytes as megabytes (10^6), as the paper states memory.
std::optional<Distribution> megabytes(std::optional<Distribution> d) {
  if (!d) return d;
  for (double* v : {&d->median, &d->mean, &d->max, &d->min}) *v /= 1e6;
  return d;
}

// Whose fronts and statistics a file of the suite table holds: a reference from `solutions
// reference` names the solvers that agreed and the one whose statistics it carries
// (solution.solver.param.solvers and .statistics); any other file is one solver's, both its own.
struct FrontsSource {
  std::string fronts, statistics;
};

FrontsSource fronts_source(const SolutionReader& file, bool of_reference) {
  const auto name = solver_name(file);
  if (!of_reference) return {name, name};
  const auto info = file.solver();
  std::string names;
  for (const auto& solver : front_solvers(file)) names += (names.empty() ? "" : ", ") + solver;
  if (info.parameters.find("solvers") == info.parameters.end())
    return {"reference (" + names + ")", name};
  const auto statistics = info.parameters.find("statistics");
  return {"reference (" + names + ")",
          statistics == info.parameters.end() ? std::string() : statistics->second};
}

// A benchmark's row: its size, then the fronts and runtimes of its front_files.
std::vector<Cell> suite_row(const Context& c, const Benchmark& bm, std::size_t columns) {
  std::uint64_t n_lo = UINT64_MAX, n_hi = 0, m_lo = UINT64_MAX, m_hi = 0, set_queries = 0;
  for (std::size_t k = 0; k < bm.instances.size(); ++k) {
    const auto& g = c.instances[bm.instances[k]];
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
  const auto fronts = front_files(c, bm);
  if (!fronts.files) {
    row.push_back(Cell::of(set_queries));
    row.resize(columns);
    return row;
  }
  std::vector<const SolutionReader*> pooled;
  for (const auto& f : *fronts.files) pooled.push_back(&fronts.readers[f.file]);
  const auto summary = summarize_completed(pooled);
  row.push_back(Cell::of(summary.statuses.total()));
  const auto fronts_of = fronts_source(*pooled.front(), fronts.of_reference);
  row.push_back(Cell::of(fronts_of.fronts));
  row.push_back(fronts_of.statistics.empty() ? Cell{} : Cell::of(fronts_of.statistics));
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
  add_median_and_max(row, summary.runtime_of(c.runtime));
  add_median_and_max(row, megabytes(summary.peak_memory_bytes));
  return row;
}

void write_suite(const Context& c) {
  Table t;
  t.caption =
      "Benchmarks (the paper's Table 1): size, and the fronts of the reference (else the "
      "first solver) with the " +
      c.runtime_text +
      " and peak memory of the solver whose statistics it carries, over completed queries";
  t.columns = {{"family", "Family", "family"},
               {"benchmark", "Benchmark", "benchmark"},
               {"instances", "Inst.", "instances"},
               {"vertices", "Vertices", "vertices"},
               {"arcs", "Edges", "arcs"},
               {"objectives", "$d$", "d"},
               {"queries", "Queries", "queries"},
               {"fronts_of", "Fronts of", "fronts of"},
               {"statistics_of", "Runtimes of", "runtimes of"},
               {"timeout", "Timeout", "timeout"},
               {"memory_limit", "Mem-limit", "memory limit"},
               {"front_min", "$|\\Pi^*|$ min", "front min"},
               {"front_max", "$|\\Pi^*|$ max", "front max"},
               {"front_mean", "$|\\Pi^*|$ mean", "front mean"},
               {"front_median", "$|\\Pi^*|$ med.", "front median"},
               {"runtime_median", "Med.\\ (s)", "median runtime [s]"},
               {"runtime_max", "Max (s)", "max runtime [s]"},
               {"memory_median", "Mem.\\ med.\\ (MB)", "median peak memory [MB]"},
               {"memory_max", "Mem.\\ max (MB)", "max peak memory [MB]"}};
  for (const auto& bm : c.benchmarks) t.rows.push_back(suite_row(c, bm, t.columns.size()));
  c.page.section("suite", "Suite");
  c.page.table(&Report::suite, std::move(t), "suite-table");
  write_spread(c);
  c.page.end_section();
}

// --- The solvers per benchmark: the paper's Table 5.

// A solver's row of the solver table over its files of benchmark b.
std::vector<Cell> solver_row(const Context& c, std::size_t b, const std::string& name) {
  const auto& bm = c.benchmarks[b];
  std::vector<const SolutionReader*> files;
  for (const auto& f : bm.solvers.at(name)) files.push_back(&c.solutions[f.file]);
  const auto summary = summarize_completed(files);
  const auto& statuses = summary.statuses;
  std::vector<Cell> row{Cell::of(bm.family),
                        Cell::of(bm.name),
                        Cell::of(name),
                        Cell::of(std::uint64_t{files.size()}),
                        Cell::of(statuses.total()),
                        Cell::of(statuses.completed()),
                        Cell::of(statuses[QueryStatus::timeout]),
                        Cell::of(statuses[QueryStatus::memory_limit]),
                        Cell::of(statuses[QueryStatus::failed]),
                        Cell::of(statuses[QueryStatus::not_run])};
  add_median_and_max(row, summary.runtime_of(c.runtime));
  const auto memory = megabytes(summary.peak_memory_bytes);
  row.push_back(memory ? Cell::of(memory->median) : Cell{});
  row.push_back(summary.expanded ? Cell::of(summary.expanded->median) : Cell{});
  if (c.references.empty() || c.options.epsilons.empty()) return row;
  const auto it = c.coverage[b].find(name);
  if (it == c.coverage[b].end()) {
    row.resize(row.size() + 1 + c.options.epsilons.size());
    return row;
  }
  row.push_back(Cell::of(it->second.front().evaluated()));
  for (const auto& o : it->second) row.push_back(Cell::of(o.covered));
  return row;
}

// One row per benchmark and solver (in the order first given): its files, queries and their
// statuses, the median and max runtime (c.runtime) over its completed queries, and with
// references its ε-coverage against them.
Table solver_table(const Context& c) {
  Table t;
  t.caption =
      "Solvers per benchmark (the paper's Table 5): statuses of each solver's queries; "
      "median and max " +
      c.runtime_text + ", over the queries it completed";
  t.columns = {{"family", "Family", "family"},
               {"benchmark", "Benchmark", "benchmark"},
               {"solver", "Solver", "solver"},
               {"files", "Files", "files"},
               {"queries", "Queries", "queries"},
               {"completed", "Completed", "completed"},
               {"timeout", "Timeout", "timeout"},
               {"memory_limit", "Mem-limit", "memory limit"},
               {"failed", "Failed", "failed"},
               {"not_run", "Not run", "not run"},
               {"runtime_median", "Med.\\ (s)", "median runtime [s]"},
               {"runtime_max", "Max (s)", "max runtime [s]"},
               {"memory_median", "Mem.\\ med.\\ (MB)", "median peak memory [MB]"},
               {"expanded_median", "Exp.\\ med.", "median expanded"}};
  if (!c.references.empty() && !c.options.epsilons.empty()) {
    t.columns.push_back({"evaluated", "Evaluated", "queries evaluated against the reference"});
    for (const auto& e : c.options.epsilon_labels)
      t.columns.push_back(tables::coverage_column(tables::Coverage::covered, e));
  }
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b)
    for (const auto& name : c.benchmarks[b].solver_order) t.rows.push_back(solver_row(c, b, name));
  return t;
}

void write_solvers(const Context& c) {
  if (c.solver_names.empty()) return;
  c.page.section("solvers", "Solvers");
  c.page.table(&Report::solvers, solver_table(c), "solvers-table");
  c.page.end_section();
}

// --- The instance space: ρ against d per benchmark, and per arc kind where it has kinds.

// A benchmark's series: the defined ρ of every pair of every instance over all arcs, and, when
// its instances have more than one arc kind, over each kind's arcs.
std::vector<plots::InstanceSpaceSeries> rho_series(const Context& c, std::size_t b) {
  const auto& bm = c.benchmarks[b];
  const std::size_t d = bm.views.front().objectives.size();
  std::vector<double> all;
  std::map<std::uint8_t, std::vector<double>> by_kind;
  for (const auto& s : c.stats[b]) {
    for (const auto& corr : s.all.correlations)
      if (corr.rho) all.push_back(*corr.rho);
    for (const auto& k : s.by_kind)
      for (const auto& corr : k.stats.correlations)
        if (corr.rho) by_kind[k.kind].push_back(*corr.rho);
  }
  std::vector<plots::InstanceSpaceSeries> series{{bm.name, d, std::move(all)}};
  if (by_kind.size() > 1)
    for (auto& [kind, rho] : by_kind)
      series.push_back({bm.name + ", arcs of kind " + std::to_string(kind), d, std::move(rho)});
  if (!c.options.signed_rho)
    for (auto& s : series)
      for (double& r : s.rho) r = std::fabs(r);
  return series;
}

std::vector<Cell> rho_row(const plots::InstanceSpaceSeries& s, std::size_t columns) {
  std::vector<Cell> row{Cell::of(s.name), Cell::of(std::uint64_t{s.objectives}),
                        Cell::of(std::uint64_t{s.rho.size()})};
  if (s.rho.empty()) {
    row.resize(columns);
    return row;
  }
  double sum = 0;
  for (double r : s.rho) sum += r;
  row.push_back(Cell::of(*std::min_element(s.rho.begin(), s.rho.end())));
  row.push_back(Cell::of(sum / static_cast<double>(s.rho.size())));
  row.push_back(Cell::of(*std::max_element(s.rho.begin(), s.rho.end())));
  return row;
}

// The figure and its table of ρ min, mean and max per series.
void instance_space_figure(const Context& c) {
  const bool absolute = !c.options.signed_rho;
  plots::InstanceSpacePlot plot;
  plot.title = "Instance space: objective correlation against d";
  plot.absolute = absolute;
  Table t;
  t.caption = std::string(absolute ? "Absolute pairwise" : "Pairwise") +
              " Pearson correlation of the objectives over the arcs of each benchmark's "
              "instances (and over the arcs of each kind where an instance has arc kinds)";
  const std::string rho = absolute ? "|ρ|" : "ρ", latex = absolute ? "$|\\rho|$" : "$\\rho$";
  const std::string key = absolute ? "abs_rho" : "rho";
  t.columns = {{"series", "Benchmark", "benchmark"},
               {"objectives", "$d$", "d"},
               {"pairs", "Pairs", "pairs"},
               {key + "_min", latex + " min", rho + " min"},
               {key + "_mean", latex + " mean", rho + " mean"},
               {key + "_max", latex + " max", rho + " max"}};
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b)
    for (auto& s : rho_series(c, b)) {
      t.rows.push_back(rho_row(s, t.columns.size()));
      plot.series.push_back(std::move(s));
    }
  c.page.figure("instance-space", plots::plot_instance_space(plot),
                "Each benchmark at its number of objectives d: the line spans its smallest to "
                "largest pairwise " +
                    rho +
                    " (ends marked), each faint dot is one pair of one instance. "
                    "Benchmarks with arc kinds (NetMaker: kind 0 the Hamiltonian cycle, kind 1 the "
                    "locality arcs) also have a series per kind.");
  c.page.table(&Report::instance_space, std::move(t), "instance-space-table");
}

void write_instance_space(const Context& c) {
  c.page.section("instance-space", "Instance space");
  instance_space_figure(c);
  c.page.end_section();
}

// --- Per benchmark, of its first instance: ρ matrix, degrees, the map of a grid, fronts.

void correlation_figure(const Context& c, std::size_t b) {
  auto rho = plots::correlation_of(c.stats[b].front().all);
  rho.title = c.benchmarks[b].name + ": objective correlation";
  if (rho.names.size() >= 2)
    c.page.figure("correlation", plots::plot_correlation(rho), "Pearson ρ over all arcs",
                  "correlation-" + c.benchmarks[b].key);
}

void degrees_figure(const Context& c, const Benchmark& bm) {
  auto degrees = plots::degrees_of(c.instances[bm.instances.front()]);
  degrees.title = bm.name + ": out-degree distribution";
  c.page.figure("degrees", plots::plot_degrees(degrees), "Vertices per out-degree",
                "degrees-" + bm.key);
}

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

// The fronts a benchmark's section draws: of the first of its front_files, with the first other
// solver's front of the same instance and query set over them when the first is a reference's.
struct DrawnFronts {
  const SolutionReader* shown = nullptr;
  const SolutionReader* overlay = nullptr;
  std::vector<const SolutionReader*> approximations;  // files claiming ε > 0, in solver order
  std::size_t instance = 0;                           // the instance `shown` is bound to
  bool of_reference = false;
  std::vector<std::uint64_t> queries;  // chosen_queries of `shown`
};

DrawnFronts drawn_fronts(const Context& c, const Benchmark& bm) {
  const auto files = front_files(c, bm);
  if (!files.files) return {};
  DrawnFronts fronts;
  fronts.shown = &files.readers[files.files->front().file];
  fronts.instance = files.files->front().instance;
  fronts.of_reference = files.of_reference;
  // Over the reference, the first other exact solver's front (the reference is often a
  // solver's file too) and every approximate solver's (an ε sweep's).
  for (const auto& name : bm.solver_order)
    for (const auto& f : bm.solvers.at(name)) {
      const auto& s = c.solutions[f.file];
      if (&s == fronts.shown || f.instance != fronts.instance ||
          s.query_set() != fronts.shown->query_set())
        continue;
      if (parse_epsilon(s.solver().epsilon).num != 0)
        fronts.approximations.push_back(&s);
      else if (files.of_reference && !fronts.overlay && name != solver_name(*fronts.shown))
        fronts.overlay = &s;
    }
  fronts.queries = chosen_queries(*fronts.shown, c.options.queries);
  return fronts;
}

// The map of a benchmark's first instance with the starts and goals of the drawn queries, else of
// the first three of the view's query set (of the instance's first set when the view names none).
plots::MapPlot marked_map(const Context& c, const Benchmark& bm, const DrawnFronts& fronts) {
  const auto& g = c.instances[bm.instances.front()];
  auto map = plots::map_of(g, "exposure", c.options.max_map_side);
  map.title = bm.name + ": map of " + instance_name(g);  // no path: it would be clipped
  const bool drawn_here = fronts.shown && fronts.instance == bm.instances.front();
  std::string set = drawn_here ? fronts.shown->query_set() : bm.views.front().query_set;
  if (const auto sets = g.all(format::SectionKind::queries); set.empty() && !sets.empty())
    set = sets.front()->name;
  std::vector<std::uint64_t> marked =
      fronts.instance == bm.instances.front() ? fronts.queries : std::vector<std::uint64_t>{};
  if (!set.empty() && g.find(format::SectionKind::queries, set)) {
    const auto qs = g.queries(set);
    if (marked.empty())
      for (std::uint64_t q = 0; q < qs.size() && q < 3; ++q) marked.push_back(q);
    plots::add_query_markers(map, g, set, marked);
  }
  return map;
}

// A grid's map; one whose metadata does not fit the instance (map_of's errors) is left out, the
// page saying why, and the rest of the report is drawn.
void map_figure(const Context& c, const Benchmark& bm, const DrawnFronts& fronts) {
  const auto& g = c.instances[bm.instances.front()];
  if (!g.metadata().get("map.width") || !g.find(format::SectionKind::vertex_data, "cell")) return;
  plots::MapPlot map;
  try {
    map = marked_map(c, bm, fronts);
  } catch (const Error& e) {
    c.page.note(std::string("No map: ") + e.what());
    return;
  }
  const std::string cells =
      map.block > 1 ? "Squares of " + std::to_string(map.block) + "x" + std::to_string(map.block) +
                          " cells: dark grey when most of their cells are blocked, grey when "
                          "some are (lighter: fewer), else shaded by exposure"
                    : "Blocked cells dark grey, passable cells shaded by exposure";
  c.page.figure("map", plots::plot_map(map),
                cells + (map.guards.empty()
                             ? "; starts and goals of the queries drawn below. No guard is "
                               "marked: the instance records each cell's exposure, not where "
                               "guards stand (converted from an exposure grid, or by mosb 0.2.0 "
                               "or earlier, which did not write map.guards)."
                             : ", guards black dots; starts and goals of the queries drawn below."),
                "map-" + bm.key);
}

// Query q's fronts as the figures draw them: the reference's set under the solver's, from the
// shown file (the reference's, else the solver's) and the overlaid one.
struct QueryFronts {
  std::vector<std::vector<double>> reference, solution;  // rows of objective values
  std::string reference_name = "reference", solver_name = "solver";
  // The approximate solvers' fronts of the query (drawn in the 2-D figures), by solver name.
  std::vector<std::pair<std::string, std::vector<std::vector<double>>>> approximations;
  std::string title, caption, name;
};

QueryFronts query_fronts(const Context& c, const Benchmark& bm, const DrawnFronts& fronts,
                         std::uint64_t q) {
  const SolutionReader& shown = *fronts.shown;
  auto rows = plots::front_rows(shown, q);
  std::vector<std::vector<double>> other;
  if (fronts.overlay && q < fronts.overlay->query_count() &&
      fronts.overlay->status(q) == QueryStatus::solved)
    other = plots::front_rows(*fronts.overlay, q);
  const std::string what = "query " + std::to_string(q) + " of " + shown.query_set() + " on " +
                           c.instances[fronts.instance].display_name();
  QueryFronts f;
  std::string approximated;                                       // their sizes, for the caption
  const bool pairwise = bm.views.front().objectives.size() <= 3;  // parallel coordinates: not
  for (const auto* a : fronts.approximations)
    if (pairwise && q < a->query_count() && a->status(q) == QueryStatus::solved) {
      f.approximations.emplace_back(solver_name(*a), plots::front_rows(*a, q));
      approximated +=
          ", " + solver_name(*a) + " " + std::to_string(f.approximations.back().second.size());
    }
  // The title names no path: it is drawn in the figure, at its width.
  f.title = bm.name + ", query " + std::to_string(q) +
            (bm.instances.size() > 1 ? " on " + instance_name(c.instances[fronts.instance])
                                     : std::string());
  f.name = "front-" + bm.key + "-q" + std::to_string(q);
  f.caption =
      "Front of " + what + " (" + std::to_string(rows.size()) + " vectors" +
      (fronts.overlay ? ", " + solver_name(*fronts.overlay) + " " + std::to_string(other.size())
                      : std::string()) +
      approximated + ")";
  if (!fronts.of_reference) {
    f.solution = std::move(rows);
    f.solver_name = solver_name(shown);
    return f;
  }
  f.reference = std::move(rows);
  if (fronts.overlay) {
    f.solution = std::move(other);
    f.solver_name = solver_name(*fronts.overlay);
  }
  return f;
}

// d = 2: one scatter; d = 3: the three pairwise projections, each saying so.
void pair_figures(const Context& c, const DrawnFronts& fronts, std::size_t d,
                  const QueryFronts& f) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs = {{0, 1}};
  if (d == 3) pairs = {{0, 1}, {0, 2}, {1, 2}};
  for (const auto& [a, b] : pairs) {
    auto front = plots::front_axes(*fronts.shown, &c.instances[fronts.instance], a, b);
    front.title = f.title;
    front.max_points = c.options.max_points;
    front.reference = plots::pair_points(f.reference, a, b);
    front.solution = plots::pair_points(f.solution, a, b);
    front.reference_name = f.reference_name;
    front.solver_name = f.solver_name;
    for (const auto& [name, rows] : f.approximations)
      front.approximations.push_back({name, plots::pair_points(rows, a, b)});
    c.page.figure(
        "front", plots::plot_front(front),
        f.caption +
            (d == 3 ? ": projection on " + front.x_label + ", " + front.y_label : std::string()),
        f.name + (d == 3 ? "-" + std::to_string(a + 1) + std::to_string(b + 1) : std::string()));
  }
}

// d > 3: parallel coordinates.
void parallel_figure(const Context& c, const SolutionReader& shown, std::size_t d, QueryFronts f) {
  plots::ParallelPlot par;
  par.title = f.title;
  par.subtitle = "parallel coordinates of " + std::to_string(d) + " objectives";
  for (std::size_t i = 0; i < d; ++i) par.axes.push_back(shown.objective_name(i));
  par.reference = std::move(f.reference);
  par.solution = std::move(f.solution);
  par.reference_name = f.reference_name;
  par.solver_name = f.solver_name;
  c.page.figure("front", plots::plot_parallel(par), f.caption, f.name);
}

void front_figures(const Context& c, const Benchmark& bm, const DrawnFronts& fronts) {
  if (!fronts.shown) {
    c.page.note("No solution file for this benchmark: no fronts.");
    return;
  }
  if (fronts.queries.empty())
    c.page.note(fronts.shown->display_name() + ": no solved query with a non-empty front to draw.");
  for (const auto q : c.options.queries)
    if (std::find(fronts.queries.begin(), fronts.queries.end(), q) == fronts.queries.end())
      c.page.note("Query " + std::to_string(q) + ": not a solved query with a front in " +
                  fronts.shown->display_name() + ", not drawn.");
  const std::size_t d = bm.views.front().objectives.size();
  if (d < 2) {
    if (!fronts.queries.empty())
      c.page.note("One objective: each front is a single value, not drawn.");
    return;
  }
  for (const auto q : fronts.queries) {
    auto f = query_fronts(c, bm, fronts, q);
    if (d > 3)
      parallel_figure(c, *fronts.shown, d, std::move(f));
    else
      pair_figures(c, fronts, d, f);
  }
}

void write_benchmark(const Context& c, std::size_t b) {
  const auto& bm = c.benchmarks[b];
  const auto& g = c.instances[bm.instances.front()];
  c.page.section(bm.anchor, bm.name);
  std::string names;
  for (auto i : bm.instances) names += (names.empty() ? "" : ", ") + instance_name(c.instances[i]);
  c.page.paragraph(
      "family " + (bm.family.empty() ? std::string("unknown") : bm.family) + "; " +
      count_of(bm.instances.size(), "instance") + " (" + names + "); objectives " +
      objective_names(g, bm.views.front()) +
      (bm.instances.size() > 1 ? "; the figures below are of " + g.display_name() : std::string()));
  correlation_figure(c, b);
  degrees_figure(c, bm);
  const auto fronts = drawn_fronts(c, bm);
  map_figure(c, bm, fronts);
  front_figures(c, bm, fronts);
  c.page.end_section();
}

// --- Solver comparison, with two or more solvers.

// Benchmark b's numbers for comparison_table: its queries, those every solver of it completed,
// and per solver its statuses over its queries and its runtimes over the common ones.
struct BenchmarkComparison {
  std::uint64_t queries = 0, common = 0;
  std::map<std::string, StatusCounts> statuses;
  std::map<std::string, std::vector<double>> runtimes;
};

BenchmarkComparison compare_solvers(const Context& c, std::size_t b) {
  BenchmarkComparison out;
  for (const auto& [key, by_solver] : c.outcomes) {
    if (key.benchmark != b) continue;
    ++out.queries;
    bool all = by_solver.size() == c.benchmarks[b].solvers.size();
    for (const auto& [name, o] : by_solver) {
      ++out.statuses[name][o.status];
      all = all && o.completed() && o.runtime;
    }
    if (!all) continue;
    ++out.common;
    for (const auto& [name, o] : by_solver) out.runtimes[name].push_back(*o.runtime);
  }
  return out;
}

// A solver's four cells: timeouts, memory limits, median and max runtime over the common queries.
void add_solver_cells(std::vector<Cell>& row, BenchmarkComparison& bc, const std::string& s) {
  row.push_back(Cell::of(bc.statuses[s][QueryStatus::timeout]));
  row.push_back(Cell::of(bc.statuses[s][QueryStatus::memory_limit]));
  add_median_and_max(row, distribution_of(bc.runtimes[s]));
}

const std::vector<Column> kSolverColumns = {{"timeout", "Timeout", "timeout"},
                                            {"memory_limit", "Mem-limit", "memory limit"},
                                            {"runtime_median", "Med.\\ (s)", "median runtime [s]"},
                                            {"runtime_max", "Max (s)", "max runtime [s]"}};

// The paper's layout (ReportOptions::comparison_by_benchmark): a row per benchmark, each solver's
// four columns under its name; a solver without files for a benchmark has no numbers there.
void by_benchmark(const Context& c, Table& t) {
  t.columns.erase(t.columns.begin() + 2);  // no solver column
  for (std::size_t s = 0; s < c.solver_names.size(); ++s) {
    t.groups.push_back({t.columns.size(), kSolverColumns.size(), c.solver_names[s]});
    for (auto column : kSolverColumns) {
      column.key += "@" + c.solver_keys[s];
      column.html = c.solver_names[s] + ": " + column.html;
      t.columns.push_back(std::move(column));
    }
  }
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b) {
    const auto& bm = c.benchmarks[b];
    if (bm.solver_order.empty()) continue;
    auto bc = compare_solvers(c, b);
    std::vector<Cell> row{Cell::of(bm.family), Cell::of(bm.name), Cell::of(bc.queries),
                          Cell::of(bc.common)};
    for (const auto& s : c.solver_names) {
      if (bm.solvers.contains(s))
        add_solver_cells(row, bc, s);
      else
        row.resize(row.size() + kSolverColumns.size());
    }
    t.rows.push_back(std::move(row));
  }
}

// The paper's comparison of exact solvers (its appendix table): the benchmark's queries, those
// every solver of it completed, each solver's timeouts and memory limits over its queries, and
// its median and max runtime over the common queries (the only runtimes that compare). One row
// per benchmark and solver, so that it reads at any number of solvers; the paper's layout with
// ReportOptions::comparison_by_benchmark.
Table comparison_table(const Context& c) {
  Table t;
  t.caption =
      "Solvers per benchmark: timeouts and memory limits over each solver's queries; "
      "median and max " +
      c.runtime_text + " over the queries every solver of the benchmark completed";
  t.columns = {{"family", "Family", "family"},
               {"benchmark", "Benchmark", "benchmark"},
               {"solver", "Solver", "solver"},
               {"queries", "Queries", "queries"},
               {"common", "Common", "completed by all"}};
  if (c.options.comparison_by_benchmark) {
    by_benchmark(c, t);
    return t;
  }
  t.columns.insert(t.columns.end(), kSolverColumns.begin(), kSolverColumns.end());
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b) {
    const auto& bm = c.benchmarks[b];
    auto bc = compare_solvers(c, b);
    for (const auto& s : bm.solver_order) {
      std::vector<Cell> row{Cell::of(bm.family), Cell::of(bm.name), Cell::of(s),
                            Cell::of(bc.queries), Cell::of(bc.common)};
      add_solver_cells(row, bc, s);
      t.rows.push_back(std::move(row));
    }
  }
  return t;
}

// The solvers and queries one figure of the comparison shows: one benchmark's (its solvers in
// the order first given), or every benchmark's pooled.
struct Scope {
  std::optional<std::size_t> benchmark;  // nullopt: pooled
  const std::vector<std::string>* solvers = nullptr;
  std::string title_suffix, name_suffix;
  bool holds(const QueryKey& key) const { return !benchmark || key.benchmark == *benchmark; }
};

Scope benchmark_scope(const Context& c, std::size_t b) {
  const auto& bm = c.benchmarks[b];
  return {b, &bm.solver_order, ", " + bm.name, "-" + bm.key};
}

Scope pooled_scope(const Context& c) {
  return {std::nullopt, &c.solver_names, ", every benchmark", ""};
}

// A figure's points as a drawing's.
std::vector<plots::Point2> drawn(const std::vector<FigurePoint>& points) {
  std::vector<plots::Point2> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back({p.x, p.y});
  return out;
}

QueryRun run_of(const Outcome& o) {
  return {o.status, o.runtime};
}

// Each solver's solved queries by runtime (cactus_series).
void cactus_figure(const Context& c, const Scope& scope) {
  plots::LinePlot cactus;
  cactus.title = "Cactus plot" + scope.title_suffix;
  cactus.x_label = "queries solved";
  cactus.y_label = "runtime [s] (log scale)";
  cactus.y_log = true;
  for (const auto& s : *scope.solvers) {
    std::vector<QueryRun> runs;
    for (const auto& [key, by_solver] : c.outcomes) {
      if (!scope.holds(key)) continue;
      if (const auto it = by_solver.find(s); it != by_solver.end())
        runs.push_back(run_of(it->second));
    }
    const auto data = cactus_series(runs);
    cactus.series.push_back(
        {s + " (" + std::to_string(data.solved) + " solved" +
             (data.zero ? ", " + std::to_string(data.zero) + " in 0 s not drawn" : "") + ")",
         drawn(data.points)});
  }
  c.page.figure("cactus", plots::plot_lines(cactus),
                "Each solver's solved queries sorted by " + c.runtime_text +
                    ": a point (k, t) says k queries were solved within t seconds each. Lower "
                    "and further right is better.",
                "cactus" + scope.name_suffix);
}

// The Dolan–Moré performance profile (performance_profile) over the queries every solver of the
// scope has a file for and some solver solved.
void profile_figure(const Context& c, const Scope& scope) {
  plots::LinePlot profile;
  profile.title = "Performance profile" + scope.title_suffix;
  profile.x_label = "τ: runtime / best runtime (log scale)";
  profile.y_label = "fraction of queries within τ";
  profile.x_log = true;
  profile.steps = true;
  profile.x_min = 1;
  profile.y_max = 1;
  std::vector<std::vector<QueryRun>> runs;
  for (const auto& [key, by_solver] : c.outcomes) {
    if (!scope.holds(key) || by_solver.size() != scope.solvers->size()) continue;
    auto& row = runs.emplace_back();
    for (const auto& s : *scope.solvers) row.push_back(run_of(by_solver.at(s)));
  }
  const auto data = performance_profile(runs, scope.solvers->size());
  for (std::size_t k = 0; k < scope.solvers->size(); ++k)
    profile.series.push_back({(*scope.solvers)[k], drawn(data.series[k])});
  c.page.figure("profile", plots::plot_lines(profile),
                "Dolan–Moré, over the " + std::to_string(data.queries) +
                    " queries every solver ran and some solver solved: the fraction of them a "
                    "solver solved within τ times the best solver's " +
                    c.runtime_text + ". Unsolved queries never count.",
                "profile" + scope.name_suffix);
}

// The baseline solver's runtime (ReportOptions::baseline, else the first solver's) against each
// other one's, per query both completed (runtime_scatter), the benchmarks told apart.
void scatter_figures(const Context& c) {
  const auto& a = c.options.baseline.empty() ? c.solver_names.front() : c.options.baseline;
  const auto file_key = [&](const std::string& name) {
    return c.solver_keys[static_cast<std::size_t>(
        std::find(c.solver_names.begin(), c.solver_names.end(), name) - c.solver_names.begin())];
  };
  for (const auto& other : c.solver_names) {
    if (other == a) continue;
    plots::ScatterPlot scatter;
    scatter.title = "Runtime per query: " + a + " against " + other;
    scatter.x_label = a + " runtime [s]";
    scatter.y_label = other + " runtime [s]";
    std::vector<QueryRun> runs_a, runs_other;
    std::vector<std::size_t> benchmark;  // per query
    for (const auto& [key, by_solver] : c.outcomes) {
      const auto ia = by_solver.find(a), io = by_solver.find(other);
      if (ia == by_solver.end() || io == by_solver.end()) continue;
      runs_a.push_back(run_of(ia->second));
      runs_other.push_back(run_of(io->second));
      benchmark.push_back(key.benchmark);
    }
    const auto data = runtime_scatter(runs_a, runs_other);
    std::map<std::size_t, plots::LineSeries> groups;  // by benchmark
    for (std::size_t k = 0; k < data.points.size(); ++k) {
      auto& group = groups[benchmark[data.query[k]]];
      group.name = c.benchmarks[benchmark[data.query[k]]].name;
      group.points.push_back({data.points[k].x, data.points[k].y});
    }
    for (auto& [b, group] : groups) scatter.groups.push_back(std::move(group));
    if (data.one_only > 0)
      scatter.note = std::to_string(data.one_only) + " quer" + (data.one_only == 1 ? "y" : "ies") +
                     " completed by one of the two only, not drawn";
    if (data.zero > 0)
      scatter.note += (scatter.note.empty() ? "" : "; ") + std::to_string(data.zero) + " quer" +
                      (data.zero == 1 ? "y" : "ies") + " with a runtime of 0 s, not drawn";
    c.page.figure("scatter", plots::plot_runtime_scatter(scatter),
                  "One dot per query both completed, " + c.runtime_text +
                      ", log–log; above the diagonal " + a + " was faster.",
                  "scatter-" + file_key(a) + "-" + file_key(other));
  }
}

// Per benchmark, per solver its ε-coverage summed over the benchmark's bindings that have a
// reference (compare_solvers per instance, view and query set).
std::vector<std::map<std::string, std::vector<EpsilonOutcome>>> coverage_by_benchmark(
    const Context& c) {
  std::vector<std::map<std::string, std::vector<EpsilonOutcome>>> out(c.benchmarks.size());
  if (c.options.epsilons.empty()) return out;
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b) {
    const auto& bm = c.benchmarks[b];
    for (const auto& ref : bm.references) {
      const auto& reference = c.references[ref.file];
      std::vector<SolutionReader> group;
      for (const auto& name : bm.solver_order)
        for (const auto& f : bm.solvers.at(name))
          if (f.instance == ref.instance &&
              c.solutions[f.file].query_set() == reference.query_set())
            group.push_back(c.solutions[f.file]);
      if (group.empty()) continue;
      const auto result = compare_solvers(reference, group, c.options.epsilons);
      for (std::size_t k = 0; k < result.solvers.size(); ++k) {
        auto& total = out[b][solver_name(group[k])];
        total.resize(c.options.epsilons.size());
        for (std::size_t e = 0; e < total.size(); ++e) {
          total[e].covered += result.solvers[k].per_epsilon[e].covered;
          total[e].not_covered += result.solvers[k].per_epsilon[e].not_covered;
          total[e].dominated += result.solvers[k].per_epsilon[e].dominated;
        }
      }
    }
  }
  return out;
}

// Per solver, its ε-coverage summed over every benchmark.
std::map<std::string, std::vector<EpsilonOutcome>> coverage_of(const Context& c) {
  std::map<std::string, std::vector<EpsilonOutcome>> coverage;
  for (const auto& of_benchmark : c.coverage)
    for (const auto& [name, outcomes] : of_benchmark) {
      auto& total = coverage[name];
      total.resize(outcomes.size());
      for (std::size_t e = 0; e < total.size(); ++e) {
        total[e].covered += outcomes[e].covered;
        total[e].not_covered += outcomes[e].not_covered;
        total[e].dominated += outcomes[e].dominated;
      }
    }
  return coverage;
}

// The ε-coverage per solver and ε, as bars and a table.
void coverage_figure(const Context& c) {
  if (c.options.epsilons.empty()) return;
  const auto coverage = coverage_of(c);
  if (coverage.empty()) return;
  Table t;
  t.caption =
      "ε-coverage: queries both the solver and the reference solved whose reference "
      "front the solver's covers at ε";
  t.columns = {{"solver", "Solver", "solver"}, {"evaluated", "Queries", "queries"}};
  for (const auto& e : c.options.epsilon_labels)
    t.columns.push_back(tables::coverage_column(tables::Coverage::covered, e));
  plots::BarPlot bars;
  bars.title = "ε-coverage per solver";
  bars.x_label = "ε";
  bars.y_label = "fraction of queries covered";
  for (const auto& e : c.options.epsilon_labels) bars.categories.push_back("ε = " + e);
  for (const auto& s : c.solver_names) {
    const auto it = coverage.find(s);
    if (it == coverage.end()) continue;
    const auto evaluated = it->second.front().evaluated();
    std::vector<Cell> row{Cell::of(s), Cell::of(evaluated)};
    plots::BarSeries series{s, {}};
    for (const auto& o : it->second) {
      row.push_back(Cell::of(o.covered));
      series.values.push_back(
          evaluated ? static_cast<double>(o.covered) / static_cast<double>(evaluated) : 0);
    }
    t.rows.push_back(std::move(row));
    bars.series.push_back(std::move(series));
  }
  c.page.figure("coverage", plots::plot_bars(bars),
                "Per solver and ε, the share of the queries it and the reference solved whose "
                "reference front it ε-covers (spec/EVALUATION.md §1).");
  c.page.table(&Report::coverage, std::move(t), "coverage-table");
}

// --- Approximation: Pareto-set size against ε (the paper's figure), per benchmark.

// The sweep a solver belongs to: its name without the "-epsE" an experiment's ε array appends
// (spec/EXPERIMENT.md), E its file's ε; else its name.
std::string sweep_of(const std::string& name, const std::string& epsilon) {
  const auto suffix = "-eps" + epsilon;
  return name.size() > suffix.size() && name.ends_with(suffix)
             ? name.substr(0, name.size() - suffix.size())
             : name;
}

// One approximate solver's front sizes on a benchmark, beside the reference's, per query both
// solved.
struct SweepPoint {
  std::string solver, epsilon_text;
  double epsilon = 0;
  std::vector<double> sizes, exact_sizes;
};

// Per sweep (in the order first given), its solvers' points on benchmark b.
std::vector<std::pair<std::string, std::vector<SweepPoint>>> sweeps_of(const Context& c,
                                                                       std::size_t b) {
  const auto& bm = c.benchmarks[b];
  std::vector<std::pair<std::string, std::vector<SweepPoint>>> sweeps;
  for (const auto& name : bm.solver_order) {
    const auto& files = bm.solvers.at(name);
    const auto epsilon_text = c.solutions[files.front().file].solver().epsilon;
    const auto epsilon = parse_epsilon(epsilon_text);
    if (epsilon.num == 0) continue;
    SweepPoint point{name, epsilon_text, epsilon.to_double(), {}, {}};
    for (const auto& f : files)
      for (const auto& ref : bm.references) {
        const auto& r = c.references[ref.file];
        const auto& s = c.solutions[f.file];
        if (ref.instance != f.instance || r.query_set() != s.query_set()) continue;
        for (std::uint64_t q = 0; q < s.query_count() && q < r.query_count(); ++q)
          if (s.status(q) == QueryStatus::solved && r.status(q) == QueryStatus::solved) {
            point.sizes.push_back(static_cast<double>(s.front_size(q)));
            point.exact_sizes.push_back(static_cast<double>(r.front_size(q)));
          }
      }
    if (point.sizes.empty()) continue;
    const auto sweep = sweep_of(name, epsilon_text);
    auto at =
        std::find_if(sweeps.begin(), sweeps.end(), [&](const auto& x) { return x.first == sweep; });
    if (at == sweeps.end()) at = sweeps.insert(sweeps.end(), {sweep, {}});
    at->second.push_back(std::move(point));
  }
  for (auto& [sweep, points] : sweeps)
    std::stable_sort(points.begin(), points.end(), [](const SweepPoint& x, const SweepPoint& y) {
      return x.epsilon < y.epsilon;
    });
  return sweeps;
}

double median_of(std::vector<double> values) {
  return distribution_of(std::move(values))->median;  // never empty here
}

// The figure (front size per query against ε, log scale, each sweep's median joined from the
// exact fronts at ε = 0) and its table rows.
void epsilon_figure(const Context& c, std::size_t b, Table& table) {
  const auto& bm = c.benchmarks[b];
  const auto sweeps = sweeps_of(c, b);
  if (sweeps.empty()) return;
  plots::LinePlot plot;
  plot.title = "Pareto-set size against ε, " + bm.name;
  plot.x_label = "ε";
  plot.y_label = "front size (log scale)";
  plot.y_log = true;
  plot.x_min = 0;
  std::string reductions;
  std::vector<plots::LineSeries> lines;  // drawn over every sweep's dots
  for (std::size_t k = 0; k < sweeps.size(); ++k) {
    const auto& [sweep, points] = sweeps[k];
    const auto colour = static_cast<int>(k);
    plots::LineSeries dots{"", {}, false, colour};
    plots::LineSeries medians{sweep, {}, true, colour};
    // ε = 0: the reference's sizes over the queries the first point also solved.
    for (double size : points.front().exact_sizes) dots.points.push_back({0, size});
    const double exact_median = median_of(points.front().exact_sizes);
    medians.points.push_back({0, exact_median});
    table.rows.push_back({Cell::of(bm.family), Cell::of(bm.name), Cell::of(sweep),
                          Cell::of(std::string("reference")), Cell::of(0.0),
                          Cell::of(std::uint64_t{points.front().exact_sizes.size()}),
                          Cell::of(exact_median), Cell{}});
    for (const auto& p : points) {
      for (double size : p.sizes) dots.points.push_back({p.epsilon, size});
      const double median = median_of(p.sizes), exact = median_of(p.exact_sizes);
      const double reduction = exact > 0 ? 100 * (1 - median / exact) : 0;
      medians.points.push_back({p.epsilon, median});
      table.rows.push_back({Cell::of(bm.family), Cell::of(bm.name), Cell::of(sweep),
                            Cell::of(p.solver), Cell::of(p.epsilon),
                            Cell::of(std::uint64_t{p.sizes.size()}), Cell::of(median),
                            Cell::of(reduction)});
    }
    const auto& last = points.back();
    char text[64];
    std::snprintf(text, sizeof text, "%.1f%%",
                  100 * (1 - median_of(last.sizes) / median_of(last.exact_sizes)));
    reductions += (reductions.empty() ? "" : "; ") + sweep +
                  ": the median front size at ε = " + last.epsilon_text + " is " + text +
                  " below the exact one over the " + std::to_string(last.sizes.size()) +
                  " queries both solved";
    plot.series.push_back(std::move(dots));
    lines.push_back(std::move(medians));
  }
  for (auto& line : lines) plot.series.push_back(std::move(line));
  c.page.figure("epsilon", plots::plot_lines(plot),
                "One dot per query and ε (at ε = 0 the reference's exact fronts), each sweep's "
                "median joined. " +
                    reductions + ".",
                "epsilon-" + bm.key);
}

void write_approximation(const Context& c) {
  Table t;
  t.caption =
      "Front size against ε: per benchmark, sweep (a solver's ε array) and ε, the "
      "queries it and the reference solved, the median front size, and its reduction "
      "against the exact median over the same queries";
  t.columns = {{"family", "Family", "family"},
               {"benchmark", "Benchmark", "benchmark"},
               {"sweep", "Sweep", "sweep"},
               {"solver", "Solver", "solver"},
               {"epsilon", "$\\varepsilon$", "ε"},
               {"queries", "Queries", "queries"},
               {"front_median", "$|\\Pi|$ med.", "median front size"},
               {"reduction_percent", "Red.\\ (\\%)", "reduction [%]"}};
  if (!c.approximation) return;
  c.page.section("approximation", "Approximation");
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b) epsilon_figure(c, b, t);
  c.page.table(&Report::epsilon_sizes, std::move(t), "epsilon-table");
  c.page.end_section();
}

void write_comparison(const Context& c) {
  if (c.solver_names.size() < 2) return;
  c.page.section("comparison", "Solver comparison");
  c.page.table(&Report::comparison, comparison_table(c), "comparison-table");
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b)
    if (c.benchmarks[b].solver_order.size() >= 2) {
      cactus_figure(c, benchmark_scope(c, b));
      profile_figure(c, benchmark_scope(c, b));
    }
  if (c.options.pooled_figures) {
    cactus_figure(c, pooled_scope(c));
    profile_figure(c, pooled_scope(c));
  }
  scatter_figures(c);
  coverage_figure(c);
  c.page.end_section();
}

// The instances, each once: a second copy of one (the same content digest, under another path or
// the same) is left out, and a note names both.
std::vector<GraphReader> distinct_instances(std::span<const GraphReader> instances,
                                            std::vector<std::string>& notes) {
  std::vector<GraphReader> distinct;
  std::map<std::string, std::size_t> by_digest;
  for (const auto& g : instances) {
    const auto [at, added] = by_digest.emplace(g.digest(), distinct.size());
    if (added)
      distinct.push_back(g);
    else
      notes.push_back(g.display_name() + " is the same instance as " +
                      distinct[at->second].display_name() + " (content digest " + g.digest() +
                      "): counted once");
  }
  return distinct;
}

Report draw(std::span<const GraphReader> instances, std::span<const SolutionReader> solutions,
            std::span<const SolutionReader> references, const ReportOptions& options,
            const std::vector<std::string>& notes) {
  if (instances.empty()) throw Error(ErrorCode::invalid_argument, "a report needs an instance");
  Report report;
  report.notes = notes;
  Page page(report);
  Context c{instances, solutions, references, options, page, benchmarks_of(instances, options),
            notes,     {},        {},         {},      {},   {},
            {},        {},        false};
  bind_files(c);
  c.stats = view_stats(c);
  c.outcomes = outcomes_of(c);
  c.coverage = coverage_by_benchmark(c);
  for (std::size_t b = 0; b < c.benchmarks.size() && !c.approximation; ++b)
    c.approximation = !sweeps_of(c, b).empty();
  write_head(c);
  write_suite(c);
  write_solvers(c);
  write_instance_space(c);
  for (std::size_t b = 0; b < c.benchmarks.size(); ++b) write_benchmark(c, b);
  write_comparison(c);
  write_approximation(c);
  page.out << "<script>\n" << kScript << "</script>\n</body>\n</html>\n";
  report.html = page.out.str();
  return report;
}

}  // namespace

tables::Table solver_table(std::span<const GraphReader> instances,
                           std::span<const SolutionReader> solutions,
                           std::span<const SolutionReader> references, const ReportOptions& options,
                           SolverTable kind) {
  if (instances.empty()) throw Error(ErrorCode::invalid_argument, "no instance");
  std::vector<std::string> notes;
  const auto distinct = distinct_instances(instances, notes);
  Report unused;
  Page page(unused);
  Context c{distinct, solutions, references, options, page, benchmarks_of(distinct, options),
            notes,    {},        {},         {},      {},   {},
            {},       {},        false};
  bind_files(c);
  if (kind == SolverTable::common_queries) {
    c.outcomes = outcomes_of(c);
    return comparison_table(c);
  }
  c.coverage = coverage_by_benchmark(c);
  return solver_table(c);
}

Report make_report(std::span<const GraphReader> instances,
                   std::span<const SolutionReader> solutions,
                   std::span<const SolutionReader> references, const ReportOptions& options) {
  constexpr std::size_t kFewestPoints = 50;
  std::vector<std::string> notes;
  const auto distinct = distinct_instances(instances, notes);
  auto current = options;
  for (;;) {
    auto report = draw(distinct, solutions, references, current, notes);
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
