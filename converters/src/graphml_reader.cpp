#include "mosb/converters/graphml_reader.hpp"

#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <sstream>
#include <unordered_map>

#include "mosb/error.hpp"

namespace mosb::converters {

namespace {

using boost::property_tree::ptree;

constexpr std::size_t kMaxDepth = 64;
constexpr std::uint64_t kMaxCount = 0xFFFFFFFEULL;  // n at most 2^32 - 2 (FORMAT.md §4)

// Text shown in a one-line message: control bytes as '?', long text cut.
std::string shown(std::string_view s) {
  std::string out = "'";
  const std::size_t limit = 40;
  for (std::size_t i = 0; i < s.size() && i < limit; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    out += (c < 0x20 || c == 0x7F) ? '?' : static_cast<char>(c);
  }
  if (s.size() > limit) out += "...";
  return out + "'";
}

std::string trimmed(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return std::string(s);
}

// The XML parser recurses once per nesting level, so hostile nesting must be refused before it
// runs. Over-counts rather than under-counts: every start tag opens a level, every end tag closes
// one.
std::size_t element_depth(std::string_view text) {
  std::size_t depth = 0, deepest = 0, i = 0;
  const auto skip_past = [&](std::string_view end) {
    const auto at = text.find(end, i);
    i = at == std::string_view::npos ? text.size() : at + end.size();
  };
  while (i < text.size()) {
    if (text[i] != '<') {
      ++i;
      continue;
    }
    const auto rest = text.substr(i);
    if (rest.starts_with("<!--")) {
      skip_past("-->");
      continue;
    }
    if (rest.starts_with("<![CDATA[")) {
      skip_past("]]>");
      continue;
    }
    if (rest.starts_with("<?")) {
      skip_past("?>");
      continue;
    }
    if (rest.starts_with("<!")) {
      skip_past(">");
      continue;
    }
    const bool closing = rest.starts_with("</");
    ++i;
    char quote = 0;
    bool self_closing = false;
    while (i < text.size()) {
      const char c = text[i++];
      if (quote) {
        if (c == quote) quote = 0;
        continue;
      }
      if (c == '"' || c == '\'') {
        quote = c;
        continue;
      }
      if (c == '>') {
        self_closing = i >= 2 && text[i - 2] == '/';
        break;
      }
    }
    if (closing) {
      if (depth > 0) --depth;
    } else if (!self_closing) {
      deepest = std::max(deepest, ++depth);
    }
  }
  return deepest;
}

std::string attribute(const ptree& element, const char* name) {
  const auto attrs = element.get_child_optional("<xmlattr>");
  if (!attrs) return {};
  // '/' as the path separator: attribute names such as attr.name contain the default '.'.
  const auto value = attrs->get_optional<std::string>(ptree::path_type(name, '/'));
  return value ? *value : std::string();
}

bool has_attribute(const ptree& element, const char* name) {
  const auto attrs = element.get_child_optional("<xmlattr>");
  return attrs && attrs->get_child_optional(ptree::path_type(name, '/'));
}

struct KeyIndex {
  std::unordered_map<std::string, std::size_t> node, edge;
};

// Fills `values` (one slot per key of the domain) from the <data key=...> children of `element`.
void read_data(const ptree& element, const std::unordered_map<std::string, std::size_t>& keys,
               std::vector<std::optional<std::string>>& values, const std::string& file,
               const std::string& what) {
  for (const auto& [tag, child] : element) {
    if (tag != "data") continue;
    const auto key = attribute(child, "key");
    const auto it = keys.find(key);
    if (it == keys.end())
      throw Error(file + ": " + what + ": <data key=" + shown(key) +
                  "> names no key declared for it");
    if (values[it->second])
      throw Error(file + ": " + what + ": second <data> for key " + shown(key));
    values[it->second] = trimmed(child.data());
  }
}

}  // namespace

std::optional<std::size_t> GraphmlGraph::node_key(std::string_view name) const {
  for (std::size_t k = 0; k < node_keys.size(); ++k)
    if (node_keys[k].name == name) return k;
  return std::nullopt;
}

std::optional<std::size_t> GraphmlGraph::edge_key(std::string_view name) const {
  for (std::size_t k = 0; k < edge_keys.size(); ++k)
    if (edge_keys[k].name == name) return k;
  return std::nullopt;
}

const std::optional<std::string>& GraphmlGraph::edge_value(std::size_t e, std::size_t key) const {
  const auto& own = edges[e].data[key];
  return own ? own : edge_keys[key].default_value;
}

const std::optional<std::string>& GraphmlGraph::node_value(std::size_t v, std::size_t key) const {
  const auto& own = node_data[v][key];
  return own ? own : node_keys[key].default_value;
}

std::string GraphmlGraph::describe_edge(std::size_t e) const {
  const auto& edge = edges[e];
  const std::string name =
      edge.id.empty() ? "edge #" + std::to_string(e) : "edge " + shown(edge.id);
  return name + " (" + shown(node_ids[edge.source]) + " -> " + shown(node_ids[edge.target]) + ")";
}

GraphmlGraph parse_graphml(std::string_view text, const std::string& display_name) {
  const auto& file = display_name;
  if (text.find('\0') != std::string_view::npos)
    throw Error(file + ": a NUL byte at offset " + std::to_string(text.find('\0')) +
                " (not XML text)");
  if (element_depth(text) > kMaxDepth)
    throw Error(file + ": elements nested deeper than " + std::to_string(kMaxDepth) + " levels");
  ptree doc;
  try {
    std::istringstream in{std::string(text)};
    boost::property_tree::read_xml(in, doc, boost::property_tree::xml_parser::no_comments);
  } catch (const boost::property_tree::xml_parser_error& e) {
    throw Error(file + ":" + std::to_string(e.line()) + ": XML error: " + e.message());
  } catch (const boost::property_tree::ptree_error& e) {
    throw Error(file + ": XML error: " + std::string(e.what()));
  }
  const auto root = doc.get_child_optional("graphml");
  if (!root) throw Error(file + ": no <graphml> root element");

  GraphmlGraph g;
  KeyIndex index;
  const ptree* graph = nullptr;
  for (const auto& [tag, child] : *root) {
    if (tag == "key") {
      GraphmlKey key{
          attribute(child, "id"), attribute(child, "attr.name"), attribute(child, "attr.type"), {}};
      if (key.id.empty()) throw Error(file + ": a <key> without an id");
      if (const auto d = child.get_child_optional("default"))
        key.default_value = trimmed(d->data());
      const auto domain = attribute(child, "for");
      const bool node = domain == "node" || domain == "all",
                 edge = domain == "edge" || domain == "all";
      if ((node && index.node.count(key.id)) || (edge && index.edge.count(key.id)))
        throw Error(file + ": key " + shown(key.id) + " declared twice");
      if (node) index.node.emplace(key.id, g.node_keys.size()), g.node_keys.push_back(key);
      if (edge) index.edge.emplace(key.id, g.edge_keys.size()), g.edge_keys.push_back(key);
    } else if (tag == "graph") {
      if (graph) throw Error(file + ": more than one <graph> (one roadmap per file)");
      graph = &child;
    }
  }
  if (!graph) throw Error(file + ": no <graph> element");
  const auto edge_default = attribute(*graph, "edgedefault");
  if (edge_default != "directed" && edge_default != "undirected")
    throw Error(file + ": <graph edgedefault=" + shown(edge_default) +
                ">: expected 'directed' or 'undirected'");
  g.edge_default_directed = edge_default == "directed";

  // Nodes first: GraphML lets edges precede the nodes they name.
  std::unordered_map<std::string, std::uint32_t> vertex_of;
  for (const auto& [tag, child] : *graph) {
    if (tag == "hyperedge") throw Error(file + ": <hyperedge> is not a roadmap edge");
    if (tag != "node") continue;
    if (child.get_child_optional("graph")) throw Error(file + ": nested <graph> inside a node");
    auto id = attribute(child, "id");
    if (g.node_ids.size() >= kMaxCount)
      throw Error(file + ": more than " + std::to_string(kMaxCount) + " nodes");
    if (!vertex_of.emplace(id, static_cast<std::uint32_t>(g.node_ids.size())).second)
      throw Error(file + ": node id " + shown(id) + " appears twice");
    g.node_data.emplace_back(g.node_keys.size());
    read_data(child, index.node, g.node_data.back(), file, "node " + shown(id));
    g.node_ids.push_back(std::move(id));
  }
  for (const auto& [tag, child] : *graph) {
    if (tag != "edge") continue;
    GraphmlEdge edge;
    edge.id = attribute(child, "id");
    const std::string what =
        edge.id.empty() ? "edge #" + std::to_string(g.edges.size()) : "edge " + shown(edge.id);
    for (const auto* end : {"source", "target"}) {
      const auto name = attribute(child, end);
      const auto it = vertex_of.find(name);
      if (it == vertex_of.end())
        throw Error(file + ": " + what + ": " + end + " " + shown(name) + " is no node");
      (std::string_view(end) == "source" ? edge.source : edge.target) = it->second;
    }
    edge.directed = g.edge_default_directed;
    if (has_attribute(child, "directed")) {
      const auto d = attribute(child, "directed");
      if (d != "true" && d != "false")
        throw Error(file + ": " + what + ": directed=" + shown(d) + ": expected 'true' or 'false'");
      edge.directed = d == "true";
    }
    edge.data.resize(g.edge_keys.size());
    read_data(child, index.edge, edge.data, file, what);
    g.edges.push_back(std::move(edge));
  }
  return g;
}

}  // namespace mosb::converters
