#include "mosb/converters/roadmap_converter.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "mosb/converters/dimacs_converter.hpp"
#include "mosb/converters/graphml_reader.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/internal/number_text.hpp"

namespace mosb::converters {

namespace {

using format::kMaxCount;

using namespace text;  // the shared primitives of text_scan.hpp

// Calls f(line_number, tokens, end_column) for each line: '\r' separates tokens like blanks and
// tabs, and the end column counts every byte of the line.
template <class F>
void for_each_line(std::string_view text_in, F&& f) {
  text::LineScanner lines(text_in, text::LineEnd::keep);
  std::string_view line;
  std::vector<Token> tokens;
  while (lines.next(line)) {
    text::tokenize(line, tokens, text::Separators::blanks_and_cr);
    f(lines.number(), tokens, line.size() + 1);
  }
}

// What a first pass over a .gr text finds: the `p sp n m` header and the largest vertex id.
struct GrScan {
  std::uint64_t header_line = 0;  // 0: none found (the parser reports it)
  std::uint64_t declared = 0;
  std::size_t count_offset = 0, count_length = 0;  // the n token, for --vertices-from-ids
  std::optional<std::uint64_t> largest;
  std::uint64_t largest_line = 0, largest_column = 0;
};

GrScan scan_gr(std::string_view text) {
  GrScan s;
  for_each_line(text, [&](std::uint64_t line, const std::vector<Token>& t, std::uint64_t) {
    if (t.empty()) return;
    if (t[0].text == "p" && t.size() >= 3 && t[1].text == "sp" && s.header_line == 0) {
      if (const auto n = to_u64(t[2].text)) {
        s.header_line = line;
        s.declared = *n;
        s.count_offset = static_cast<std::size_t>(t[2].text.data() - text.data());
        s.count_length = t[2].text.size();
      }
    } else if (t[0].text == "a") {
      for (std::size_t k = 1; k < 3 && k < t.size(); ++k) {
        const auto id = to_u64(t[k].text);
        if (id && (!s.largest || *id > *s.largest)) {
          s.largest = *id;
          s.largest_line = line;
          s.largest_column = t[k].column;
        }
      }
    }
  });
  return s;
}

// `problem`, then how vertices_from_ids would take the input instead.
Message with_from_ids_hint(std::string problem) {
  return {std::move(problem) + "; ", setting("vertices_from_ids"),
          " sizes the graph from the largest id instead"};
}

std::string declared_range(std::uint64_t declared) {
  return declared == 0 ? "(none)" : "0.." + std::to_string(declared - 1);
}

std::vector<double> vertex_configs(const VertexFile& vf, std::uint64_t n, const std::string& file) {
  std::vector<std::uint64_t> order(vf.ids.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return vf.ids[a] < vf.ids[b]; });
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto id = vf.ids[order[k]];
    if (id >= n)
      fail(file, vf.lines[order[k]], 1,
           "vertex id " + std::to_string(id) + " outside " + declared_range(n));
    if (k > 0 && vf.ids[order[k - 1]] == id)
      fail(file, vf.lines[order[k]], 1,
           "second line for vertex " + std::to_string(id) + " (the first is line " +
               std::to_string(vf.lines[order[k - 1]]) + ")");
    if (id != k) throw Error(file + ": no line for vertex " + std::to_string(k));
  }
  if (order.size() != n) throw Error(file + ": no line for vertex " + std::to_string(order.size()));
  std::vector<double> configs(vf.coords.size());
  for (std::size_t i = 0; i < vf.ids.size(); ++i)
    std::copy_n(vf.coords.begin() + static_cast<std::ptrdiff_t>(i * vf.dof), vf.dof,
                configs.begin() + static_cast<std::ptrdiff_t>(vf.ids[i] * vf.dof));
  return configs;
}

void name_objectives(GraphInput& out, const std::vector<Objective>& names) {
  if (names.empty()) return;
  if (names.size() != out.costs.size())
    throw Error(
        ErrorCode::other,
        {"convert roadmap: " + std::to_string(names.size()) + " ", setting("objective"),
         " names given, the input has " + std::to_string(out.costs.size()) + " objectives"});
  for (std::size_t j = 0; j < names.size(); ++j) {
    out.costs[j].name = names[j].name;
    out.costs[j].unit = names[j].unit;
  }
  out.metadata.set("source.param.objectives", objective_list(names));
}

GraphInput convert_gr_files(const RoadmapOptions& o) {
  GraphInput out;
  auto& m = out.metadata;
  std::vector<TextInput> inputs;
  std::vector<GrScan> scans;
  for (std::size_t i = 0; i < o.gr_files.size(); ++i) {
    inputs.push_back(read_text_input(o.gr_files[i]));
    record_input(m, i, inputs.back());
    scans.push_back(scan_gr(inputs.back().text));
    const auto& s = scans.back();
    if (i > 0 && s.header_line && scans[0].header_line && s.declared != scans[0].declared)
      fail(inputs[i].display_name, s.header_line, 1,
           "declares " + std::to_string(s.declared) + " vertices, " + inputs[0].display_name +
               " declares " + std::to_string(scans[0].declared));
  }
  std::optional<VertexFile> vertices;
  std::string vertex_name;
  std::uint64_t input_bytes = 0;  // of every text read: what --vertices-from-ids may add at most
  for (const auto& input : inputs) input_bytes += input.text.size();
  if (o.vertex_file) {
    const auto input = read_text_input(*o.vertex_file);
    record_input(m, inputs.size(), input);
    vertices = parse_vertex_file(input.text, input.display_name);
    vertex_name = input.display_name;
    input_bytes += input.text.size();
  }
  const std::uint64_t declared = scans[0].declared;
  std::uint64_t n = declared;
  if (scans[0].header_line) {
    // The id that sizes the graph beyond the header, and where it is.
    const std::string* largest_file = nullptr;
    std::uint64_t largest_line = 0, largest_column = 0;
    for (std::size_t i = 0; i < scans.size(); ++i) {
      const auto& s = scans[i];
      if (!s.largest || *s.largest < declared) continue;
      if (!o.vertices_from_ids)
        fail(inputs[i].display_name, s.largest_line, s.largest_column,
             with_from_ids_hint("the largest vertex id, " + std::to_string(*s.largest) +
                                ", is outside the " + std::to_string(declared) +
                                " vertices declared on line " + std::to_string(s.header_line) +
                                " (0-based ids " + declared_range(declared) + ")"));
      if (*s.largest + 1 > n) {
        n = *s.largest + 1;
        largest_file = &inputs[i].display_name, largest_line = s.largest_line,
        largest_column = s.largest_column;
      }
    }
    if (vertices && !vertices->ids.empty()) {
      const auto at =
          std::max_element(vertices->ids.begin(), vertices->ids.end()) - vertices->ids.begin();
      const auto largest = vertices->ids[static_cast<std::size_t>(at)];
      if (largest >= declared && !o.vertices_from_ids)
        fail(vertex_name, vertices->lines[static_cast<std::size_t>(at)], 1,
             with_from_ids_hint("the largest vertex id, " + std::to_string(largest) +
                                ", is outside the " + std::to_string(declared) +
                                " vertices declared on " + inputs[0].display_name + ":" +
                                std::to_string(scans[0].header_line) + " (0-based ids " +
                                declared_range(declared) + ")"));
      if (largest + 1 > n) {
        n = largest + 1;
        largest_file = &vertex_name, largest_line = vertices->lines[static_cast<std::size_t>(at)],
        largest_column = 1;
      }
    }
    // Untrusted ids: the vertices added beyond the header must be paid for by the input's bytes, so
    // one huge id cannot make the graph (and the memory it needs) unbounded.
    if (largest_file && (n > kMaxCount || n - declared > input_bytes))
      fail(*largest_file, largest_line, largest_column,
           {"vertex id " + std::to_string(n - 1) + " would size the graph to " + std::to_string(n) +
                " vertices: ",
            setting("vertices_from_ids"),
            " adds at most as many vertices beyond the " + std::to_string(declared) +
                " declared as the input has bytes (" + std::to_string(input_bytes) + ")"});
    if (n > kMaxCount)
      throw Error("convert roadmap: vertex ids reach " + std::to_string(n - 1) +
                  ", beyond the format's limit");
  }
  if (n > declared) {
    m.set("warning.vertex_count",
          "declared " + std::to_string(declared) + ", ids reach " + std::to_string(n - 1));
    // The DIMACS parser sizes the graph from the header: give it the header the ids call for.
    for (std::size_t i = 0; i < inputs.size(); ++i)
      if (scans[i].header_line != 0)
        inputs[i].text.replace(scans[i].count_offset, scans[i].count_length, std::to_string(n));
  }

  DimacsGraph first;
  std::vector<std::variant<std::vector<std::uint64_t>, std::vector<double>>> columns;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const DimacsReference ref{&inputs[0].display_name, &first};
    auto g = parse_dimacs_gr(inputs[i].text, inputs[i].display_name, 0, i == 0 ? nullptr : &ref);
    for (auto& c : g.columns) columns.push_back(std::move(c));
    g.columns.clear();
    if (i == 0) first = std::move(g);
  }
  out.vertex_count = first.vertex_count;
  out.tails = std::move(first.tails);
  out.heads = std::move(first.heads);
  for (std::size_t j = 0; j < columns.size(); ++j) {
    CostColumn c;
    c.name = "c" + std::to_string(j + 1);
    c.values = std::move(columns[j]);
    out.costs.push_back(std::move(c));
  }
  name_objectives(out, o.objectives);
  if (vertices) {
    out.vertex_data.push_back(
        DataColumn::from("config", vertices->dof, vertex_configs(*vertices, n, vertex_name)));
    m.set("roadmap.dof", std::to_string(vertices->dof));
  }
  m.set("benchmark",
        o.name ? *o.name : benchmark_name_from(inputs[0].base_name, {".gr", ".xml", ".graphml"}));
  m.set("source.param.vertices_from_ids", o.vertices_from_ids ? "true" : "false");
  return out;
}

// Parses a comma-separated configuration of a GraphML node.
std::vector<double> parse_coords(std::string_view text, const std::string& file,
                                 std::string_view node) {
  std::vector<double> q;
  std::size_t pos = 0;
  while (true) {
    auto end = text.find(',', pos);
    if (end == std::string_view::npos) end = text.size();
    auto part = text.substr(pos, end - pos);
    while (!part.empty() && (part.front() == ' ' || part.front() == '\t')) part.remove_prefix(1);
    while (!part.empty() && (part.back() == ' ' || part.back() == '\t')) part.remove_suffix(1);
    const auto value = to_real(part);
    if (!value)
      throw Error(file + ": node " + quoted(node) + ": coords " + quoted(text) +
                  ": expected comma-separated reals");
    q.push_back(*value);
    if (end == text.size()) return q;
    pos = end + 1;
  }
}

struct ClearanceKeys {
  std::optional<std::size_t> aggregate;  // `clearance`
  std::vector<std::size_t> links;        // `clearance_0` .. `clearance_{L-1}`
};

ClearanceKeys find_clearance_keys(const GraphmlGraph& g, const std::string& file) {
  ClearanceKeys keys;
  keys.aggregate = g.edge_key("clearance");
  std::vector<std::pair<std::uint64_t, std::size_t>> links;
  for (std::size_t k = 0; k < g.edge_keys.size(); ++k) {
    const std::string_view name = g.edge_keys[k].name;
    if (!name.starts_with("clearance_")) continue;
    const auto suffix = name.substr(10);
    const auto i = to_u64(suffix);
    if (!i || (suffix.size() > 1 && suffix[0] == '0') || *i > 1000)
      throw Error(file + ": edge key " + quoted(name) + ": expected clearance_0, clearance_1, ...");
    links.emplace_back(*i, k);
  }
  std::sort(links.begin(), links.end());
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].first != i)
      throw Error(file + ": edge key 'clearance_" + std::to_string(links[i].first) +
                  "' declared, 'clearance_" + std::to_string(i) +
                  "' is missing (links are numbered 0..L-1)");
    keys.links.push_back(links[i].second);
  }
  return keys;
}

// The configuration of every node (its `coords`, all with the same number of degrees of freedom),
// row by row.
struct Configurations {
  std::vector<double> values;
  std::size_t dof = 0;
};

Configurations read_configurations(const GraphmlGraph& g, const std::string& file) {
  const auto coords_key = g.node_key("coords");
  if (!coords_key)
    throw Error(file + ": no node key named 'coords' (the configurations the length needs)");
  Configurations c;
  for (std::size_t v = 0; v < g.node_count(); ++v) {
    const auto text = g.node_value(v, *coords_key);
    if (!text) throw Error(file + ": node " + quoted(g.node_id(v)) + " has no coords");
    const auto q = parse_coords(*text, file, g.node_id(v));
    if (v == 0) c.dof = q.size();
    if (q.size() != c.dof)
      throw Error(file + ": node " + quoted(g.node_id(v)) + " has " + std::to_string(q.size()) +
                  " coordinates, node " + quoted(g.node_id(0)) + " has " + std::to_string(c.dof));
    c.values.insert(c.values.end(), q.begin(), q.end());
  }
  return c;
}

// Which clearance objectives to write (--clearance, resolved against the keys the file has).
struct ClearanceChoice {
  ClearanceKeys keys;
  ClearanceMode mode = ClearanceMode::none;
  bool aggregate = false;  // write the aggregate penalty
  bool links = false;      // write one penalty per link
};

ClearanceChoice choose_clearance(const GraphmlGraph& g, const RoadmapOptions& o,
                                 const std::string& file, const std::string& base_name,
                                 Metadata& m) {
  ClearanceChoice c{find_clearance_keys(g, file)};
  const auto& keys = c.keys;
  c.mode = o.clearance;
  if (c.mode == ClearanceMode::automatic)
    c.mode = keys.aggregate || !keys.links.empty() ? ClearanceMode::aggregate : ClearanceMode::none;
  if (o.clearance == ClearanceMode::automatic && c.mode == ClearanceMode::none)
    m.set("warning.clearance",
          "no edge key 'clearance' or 'clearance_0'.. in " + base_name +
              ": no clearance objective is written (--clearance none: no warning)");
  c.aggregate = c.mode == ClearanceMode::aggregate || c.mode == ClearanceMode::both;
  c.links = c.mode == ClearanceMode::per_link || c.mode == ClearanceMode::both;
  if (c.aggregate && !keys.aggregate && keys.links.empty())
    throw Error(ErrorCode::other, {file + ": ", setting("clearance"),
                                   " " + std::string(kClearanceModeNames.name(c.mode)) +
                                       ": no edge key 'clearance' or 'clearance_0'..."});
  if (c.links && keys.links.empty())
    throw Error(ErrorCode::other, {file + ": ", setting("clearance"),
                                   " " + std::string(kClearanceModeNames.name(c.mode)) +
                                       ": no edge keys 'clearance_0' .. 'clearance_{L-1}'"});
  return c;
}

// The cost columns of the arcs, in arc order (an undirected edge is two arcs).
struct RoadmapColumns {
  std::vector<double> length, aggregate, weight;
  std::vector<std::vector<double>> per_link;
};

RoadmapColumns build_arcs(const GraphmlGraph& g, const Configurations& configs,
                          const ClearanceChoice& clearance, const RoadmapOptions& o,
                          const std::string& file, GraphInput& out) {
  const auto& keys = clearance.keys;
  const auto weight_key = g.edge_key("weight");  // present when o.weight (checked by the caller)
  const auto real_of = [&](std::size_t e, std::size_t key) {
    const auto text = g.edge_value(e, key);
    const auto& name = g.edge_keys[key].name;
    if (!text) throw Error(file + ": " + g.describe_edge(e) + " has no " + quoted(name));
    const auto value = to_real(*text);
    if (!value)
      throw Error(file + ": " + g.describe_edge(e) + ": " + name + " " + quoted(*text) +
                  " is not a finite real");
    return *value;
  };
  const auto clearance_of = [&](std::size_t e, std::size_t key) {
    const double d = real_of(e, key);
    if (d <= 0)
      throw Error(file + ": " + g.describe_edge(e) + ": " + g.edge_keys[key].name + " = " +
                  shortest_text(d) + " <= 0: a collision (roadmap edges must be collision-free)");
    return d;
  };

  const std::size_t links = clearance.links ? keys.links.size() : 0;
  RoadmapColumns c;
  c.per_link.resize(links);
  // Sized once: growing nine columns by doubling would need up to twice their final memory.
  std::size_t arcs = 0;
  for (const auto& edge : g.edges) arcs += edge.directed || edge.source == edge.target ? 1 : 2;
  if (arcs <= kMaxCount) {
    out.tails.reserve(arcs);
    out.heads.reserve(arcs);
    c.length.reserve(arcs);
    if (clearance.aggregate) c.aggregate.reserve(arcs);
    for (auto& column : c.per_link) column.reserve(arcs);
    if (o.weight) c.weight.reserve(arcs);
  }
  const std::size_t dof = configs.dof;
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    const auto& edge = g.edges[e];
    double squared = 0;
    for (std::size_t k = 0; k < dof; ++k) {
      const double diff =
          configs.values[edge.source * dof + k] - configs.values[edge.target * dof + k];
      squared += diff * diff;
    }
    const double len = std::sqrt(squared);
    if (!std::isfinite(len))
      throw Error(file + ": " + g.describe_edge(e) + ": the length overflows");
    std::vector<double> link_d(keys.links.size());
    if (clearance.links || (clearance.aggregate && !keys.aggregate))
      for (std::size_t i = 0; i < keys.links.size(); ++i)
        link_d[i] = clearance_of(e, keys.links[i]);
    double d_min = 0;
    if (clearance.aggregate)
      d_min = keys.aggregate ? clearance_of(e, *keys.aggregate)
                             : *std::min_element(link_d.begin(), link_d.end());
    double w = 0;
    if (o.weight) {
      w = real_of(e, *weight_key);
      if (w < 0)
        throw Error(file + ": " + g.describe_edge(e) + ": negative weight " +
                    quoted(*g.edge_value(e, *weight_key)));
    }
    // An undirected edge is two opposite arcs with the same costs; an undirected loop is one arc.
    const int copies = edge.directed || edge.source == edge.target ? 1 : 2;
    for (int copy = 0; copy < copies; ++copy) {
      if (out.tails.size() >= kMaxCount)
        throw Error(file + ": more than " + std::to_string(kMaxCount) + " arcs");
      out.tails.push_back(copy == 0 ? edge.source : edge.target);
      out.heads.push_back(copy == 0 ? edge.target : edge.source);
      c.length.push_back(len);
      if (clearance.aggregate) c.aggregate.push_back(clearance_penalty(d_min, o.delta));
      for (std::size_t i = 0; i < links; ++i)
        c.per_link[i].push_back(clearance_penalty(link_d[i], o.delta));
      if (o.weight) c.weight.push_back(w);
    }
  }
  return c;
}

GraphInput convert_graphml_file(const RoadmapOptions& o) {
  GraphInput out;
  auto& m = out.metadata;
  std::string file, base_name;
  GraphmlGraph g;
  {
    // Streamed: the text is never held whole; the values the conversion needs are in `g`.
    InputFile input(*o.graphml_file);
    ReadProgress read(o.progress, {*o.graphml_file});
    input.count_into(&read);
    file = input.display_name();
    base_name = input.facts().base_name;
    g = parse_graphml(input, file);
    record_input(m, 0, input.facts());
  }
  auto configs = read_configurations(g, file);
  const auto clearance = choose_clearance(g, o, file, base_name, m);
  if (o.weight && !g.edge_key("weight"))
    throw Error(ErrorCode::other, {file + ": ", setting("weight"), ": no edge key named 'weight'"});
  if (!(o.delta > 0) || !std::isfinite(o.delta))
    throw Error(ErrorCode::other,
                {"convert roadmap: ", setting("delta"), " must be a positive real"});
  auto columns = build_arcs(g, configs, clearance, o, file, out);
  const std::size_t links = columns.per_link.size();
  const bool want_aggregate = clearance.aggregate;
  const std::size_t dof = configs.dof;

  out.vertex_count = g.node_count();
  out.costs.push_back({"length", "", std::move(columns.length), std::nullopt});
  if (want_aggregate)
    out.costs.push_back({"clearance", "", std::move(columns.aggregate), std::nullopt});
  for (std::size_t i = 0; i < links; ++i)
    out.costs.push_back(
        {"clearance_" + std::to_string(i), "", std::move(columns.per_link[i]), std::nullopt});
  if (o.weight) out.costs.push_back({"weight", "", std::move(columns.weight), std::nullopt});
  name_objectives(out, o.objectives);
  // The paper's views: Panda-RRG_2 is (length, aggregate penalty), Panda-RRG_8 length and 7 links.
  if (want_aggregate)
    m.set("view.Panda-RRG_2.objectives", out.costs[0].name + "," + out.costs[1].name);
  if (links == 7) {
    std::string list = out.costs[0].name;
    const std::size_t first_link = want_aggregate ? 2 : 1;
    for (std::size_t i = 0; i < links; ++i) list += "," + out.costs[first_link + i].name;
    m.set("view.Panda-RRG_8.objectives", list);
  }
  if (dof > 0)
    out.vertex_data.push_back(
        DataColumn::from("config", static_cast<std::uint32_t>(dof), configs.values));
  m.set("benchmark",
        o.name ? *o.name : benchmark_name_from(base_name, {".gr", ".xml", ".graphml"}));
  m.set("roadmap.dof", std::to_string(dof));
  m.set("roadmap.edgedefault", g.edge_default_directed ? "directed" : "undirected");
  m.set("roadmap.edges", std::to_string(g.edges.size()));
  if (!clearance.keys.links.empty())
    m.set("roadmap.clearance_links", std::to_string(clearance.keys.links.size()));
  m.set("source.param.clearance", kClearanceModeNames.name(clearance.mode));
  if (clearance.aggregate || clearance.links) m.set("source.param.delta", shortest_text(o.delta));
  m.set("source.param.weight", o.weight ? "true" : "false");
  return out;
}

}  // namespace

double clearance_penalty(double d, double delta) {
  if (d >= delta) return 0.0;
  return (d - delta) * (d - delta) / (2.0 * delta);
}

VertexFile parse_vertex_file(std::string_view text, const std::string& display_name) {
  VertexFile vf;
  std::uint64_t first_line = 0;
  for_each_line(
      text, [&](std::uint64_t line, const std::vector<Token>& t, std::uint64_t end_column) {
        if (t.empty() || t[0].text.starts_with("#")) return;
        const auto id = to_u64(t[0].text);
        if (!id)
          fail(display_name, line, t[0].column, "expected a vertex id, found " + quoted(t[0].text));
        if (*id >= kMaxCount)
          fail(display_name, line, t[0].column,
               "vertex id " + quoted(t[0].text) + " exceeds " + std::to_string(kMaxCount - 1));
        if (first_line == 0) {
          if (t.size() < 2)
            fail(display_name, line, end_column, "missing field: a vertex line is 'id q1 .. qdof'");
          if (t.size() - 1 > 1000)
            fail(display_name, line, t[1001].column, "more than 1000 coordinates");
          vf.dof = static_cast<std::uint32_t>(t.size() - 1);
          first_line = line;
        } else if (t.size() - 1 != vf.dof) {
          const std::string expected = "expected " + std::to_string(vf.dof) +
                                       " coordinates as on line " + std::to_string(first_line);
          if (t.size() - 1 < vf.dof)
            fail(display_name, line, end_column, "missing field: " + expected);
          fail(display_name, line, t[1 + vf.dof].column,
               "extra field " + quoted(t[1 + vf.dof].text) + ": " + expected);
        }
        for (std::size_t k = 1; k < t.size(); ++k) {
          const auto value = to_real(t[k].text);
          if (!value)
            fail(display_name, line, t[k].column,
                 "expected a finite real coordinate, found " + quoted(t[k].text));
          vf.coords.push_back(*value);
        }
        vf.ids.push_back(*id);
        vf.lines.push_back(line);
      });
  return vf;
}

GraphInput convert_roadmap(const RoadmapOptions& options) {
  const bool text = !options.gr_files.empty();
  if (text == options.graphml_file.has_value())
    throw Error(ErrorCode::other, {"convert roadmap: give either ", setting("gr_files"),
                                   " files or one ", setting("graphml_file"), " file"});
  if (text && options.clearance != ClearanceMode::automatic &&
      options.clearance != ClearanceMode::none)
    throw Error(ErrorCode::other,
                {"convert roadmap: ", setting("clearance"), " applies to ", setting("graphml_file"),
                 " input (.gr files carry their costs)"});
  if (text && options.weight)
    throw Error(ErrorCode::other, {"convert roadmap: ", setting("weight"), " applies to ",
                                   setting("graphml_file"), " input"});
  if (!text && (options.vertex_file || options.vertices_from_ids))
    throw Error(ErrorCode::other,
                {"convert roadmap: ", setting("vertex_file"), " and ", setting("vertices_from_ids"),
                 " apply to ", setting("gr_files"), " input"});
  auto out = text ? convert_gr_files(options) : convert_graphml_file(options);
  auto& m = out.metadata;
  m.set("family", "robots");
  m.set("id_base", "0");
  m.set("source.command", "convert roadmap");
  if (options.name) m.set("source.param.name", *options.name);
  return out;
}

}  // namespace mosb::converters
