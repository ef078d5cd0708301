// `mosb stats`: the statistics of spec/STATS.md as an aligned table or as JSON.
#include "mosb/stats.hpp"

#include <CLI/CLI.hpp>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/number_text.hpp"

namespace mosb::cli {

namespace {

// Integer columns print exactly; float columns in the shortest text that reads back the same.
std::string cost_text(const std::optional<long double>& v, format::ElementType type) {
  if (!v) return "n/a";
  if (!format::is_float(type)) return std::to_string(static_cast<std::uint64_t>(*v));
  return shortest_text(static_cast<double>(*v));
}

std::string mean_text(const std::optional<long double>& v) {
  if (!v) return "n/a";
  std::ostringstream out;
  out << std::setprecision(8) << static_cast<double>(*v);
  return out.str();
}

std::string rho_text(const std::optional<double>& rho) {
  if (!rho) return "n/a";
  std::ostringstream out;
  out << std::fixed << std::setprecision(6) << *rho;
  return out.str();
}

std::string degree_text(const DegreeStats& d) {
  if (!d.min) return "n/a";
  std::ostringstream out;
  out << "min " << *d.min << "  mean " << std::setprecision(8) << *d.mean << "  max " << *d.max;
  return out.str();
}

void print_group_text(const ArcGroupStats& g, const std::string& indent) {
  std::size_t width = 9;  // "objective"
  for (const auto& o : g.objectives) width = std::max(width, o.name.size());
  std::cout << indent << std::left << std::setw(static_cast<int>(width)) << "objective"
            << "  type" << std::right << std::setw(14) << "min" << std::setw(14) << "mean"
            << std::setw(14) << "max" << '\n';
  for (const auto& o : g.objectives)
    std::cout << indent << std::left << std::setw(static_cast<int>(width)) << o.name << "  "
              << std::setw(4) << format::to_string(o.type) << std::right << std::setw(14)
              << cost_text(o.min, o.type) << std::setw(14) << mean_text(o.mean) << std::setw(14)
              << cost_text(o.max, o.type) << '\n';
  if (g.correlations.empty()) return;
  std::size_t pair_width = 4;
  auto pair_name = [&](const Correlation& c) {
    return g.objectives[c.first].name + " ~ " + g.objectives[c.second].name;
  };
  for (const auto& c : g.correlations) pair_width = std::max(pair_width, pair_name(c).size());
  std::cout << indent << std::left << std::setw(static_cast<int>(pair_width)) << "pair"
            << std::right << std::setw(12) << "rho" << '\n';
  for (const auto& c : g.correlations)
    std::cout << indent << std::left << std::setw(static_cast<int>(pair_width)) << pair_name(c)
              << std::right << std::setw(12) << rho_text(c.rho) << '\n';
}

void print_text(const GraphReader& r, const std::optional<std::string>& view, const GraphStats& s) {
  std::cout << std::left;
  auto row = [](const char* label) -> std::ostream& {
    return std::cout << std::left << std::setw(15) << label;
  };
  row("file") << r.display_name() << '\n';
  row("view") << view.value_or(s.all_arcs.objectives.size() == r.objective_count()
                                   ? "(all objectives)"
                                   : "(listed objectives)")
              << '\n';
  row("vertices") << s.vertex_count << '\n';
  row("arcs") << s.arc_count << '\n';
  row("objectives") << s.all_arcs.objectives.size() << '\n';
  row("self-loops") << s.self_loops << '\n';
  row("parallel arcs") << s.parallel_arcs << '\n';
  row("out-degree") << degree_text(s.out_degree) << '\n';
  row("in-degree") << degree_text(s.in_degree) << '\n';
  row("SCCs") << s.scc_count << " (largest " << s.largest_scc << " vertices)\n";
  std::cout << "\nall arcs (" << s.all_arcs.arc_count << ")\n";
  print_group_text(s.all_arcs, "  ");
  for (const auto& k : s.by_kind) {
    std::cout << "\nkind " << unsigned{k.kind} << " (" << k.stats.arc_count << " arcs)\n";
    print_group_text(k.stats, "  ");
  }
}

void optional_number(JsonWriter& json, const std::optional<long double>& v,
                     format::ElementType type) {
  if (!v)
    json.null();
  else if (!format::is_float(type))
    json.value(static_cast<std::uint64_t>(*v));
  else
    json.value(static_cast<double>(*v));
}

void group_json(JsonWriter& json, const ArcGroupStats& g) {
  json.key("arcs").value(g.arc_count);
  json.key("objectives").begin_array();
  for (const auto& o : g.objectives) {
    json.begin_object();
    json.key("name").value(o.name);
    json.key("type").value(format::to_string(o.type));
    json.key("min");
    optional_number(json, o.min, o.type);
    json.key("mean");
    if (o.mean)
      json.value(static_cast<double>(*o.mean));
    else
      json.null();
    json.key("max");
    optional_number(json, o.max, o.type);
    json.end_object();
  }
  json.end_array();
  json.key("correlations").begin_array();
  for (const auto& c : g.correlations) {
    json.begin_object();
    json.key("first").value(g.objectives[c.first].name);
    json.key("second").value(g.objectives[c.second].name);
    json.key("rho");
    if (c.rho)
      json.value(*c.rho);
    else
      json.null();
    json.end_object();
  }
  json.end_array();
}

void degree_json(JsonWriter& json, const DegreeStats& d) {
  json.begin_object();
  json.key("min");
  if (d.min)
    json.value(*d.min);
  else
    json.null();
  json.key("mean");
  if (d.mean)
    json.value(*d.mean);
  else
    json.null();
  json.key("max");
  if (d.max)
    json.value(*d.max);
  else
    json.null();
  json.end_object();
}

void print_json(const GraphReader& r, const std::optional<std::string>& view, const GraphStats& s) {
  JsonWriter json(std::cout);
  json.begin_object();
  json.key("file").value(r.display_name());
  json.key("view");
  if (view)
    json.value(*view);
  else
    json.null();
  json.key("vertices").value(s.vertex_count);
  json.key("self_loops").value(s.self_loops);
  json.key("parallel_arcs").value(s.parallel_arcs);
  json.key("out_degree");
  degree_json(json, s.out_degree);
  json.key("in_degree");
  degree_json(json, s.in_degree);
  json.key("scc").begin_object();
  json.key("count").value(s.scc_count);
  json.key("largest").value(s.largest_scc);
  json.end_object();
  group_json(json, s.all_arcs);
  if (!s.by_kind.empty()) {
    json.key("by_kind").begin_array();
    for (const auto& k : s.by_kind) {
      json.begin_object();
      json.key("kind").value(std::uint64_t{k.kind});
      group_json(json, k.stats);
      json.end_object();
    }
    json.end_array();
  }
  json.end_object();
}

}  // namespace

Command add_stats(CLI::App& app) {
  auto* sub =
      app.add_subcommand("stats", "Cost ranges, objective correlations, degrees and components");
  auto file = std::make_shared<std::string>();
  auto choice = std::make_shared<ViewChoice>();
  auto by_kind = std::make_shared<bool>(false);
  auto as_json = std::make_shared<bool>(false);
  sub->add_option("INSTANCE", *file, "a .mosb instance")->required();
  add_view_choice_options(sub, *choice, "only these objectives, in this order");
  sub->add_flag("--by-kind", *by_kind,
                "also per value of the u8 arc data 'kind' (NetMaker: 0 cycle, 1 locality)");
  add_json_flag(sub, *as_json);
  return {sub, [file, choice, by_kind, as_json] {
            const auto reader = GraphReader::open(*file, VerifyLevel::full);
            StatsOptions options;
            options.selection = *choice;
            options.by_kind = *by_kind;
            const auto stats = compute_stats(reader, options);
            const auto view = choice->view.empty() ? std::nullopt : std::optional(choice->view);
            if (*as_json)
              print_json(reader, view, stats);
            else
              print_text(reader, view, stats);
            return 0;
          }};
}

}  // namespace mosb::cli
