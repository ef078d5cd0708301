// GraphML (as written by boost::write_graphml, which OMPL's PlannerData::printGraphML uses) read
// into nodes, edges and their attribute values as text. Attribute names are resolved through the
// <key id=... for=... attr.name=...> declarations, never by matching the key ids themselves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mosb::converters {

struct GraphmlKey {
  std::string id;
  std::string name;                          // attr.name
  std::string type;                          // attr.type, may be empty
  std::optional<std::string> default_value;  // <default>, trimmed
};

struct GraphmlEdge {
  std::string id;  // may be empty (GraphML makes edge ids optional)
  std::uint32_t source = 0;
  std::uint32_t target = 0;
  bool directed = true;  // the edge's `directed` attribute, else the graph's edgedefault
  std::vector<std::optional<std::string>> data;  // per edge key, trimmed text; nullopt when absent
};

struct GraphmlGraph {
  bool edge_default_directed = true;
  std::vector<GraphmlKey> node_keys;  // keys for="node" or for="all"
  std::vector<GraphmlKey> edge_keys;  // keys for="edge" or for="all"
  std::vector<std::string> node_ids;  // in document order: vertex k is node_ids[k]
  std::vector<std::vector<std::optional<std::string>>> node_data;  // [vertex][node key]
  std::vector<GraphmlEdge> edges;                                  // in document order

  std::optional<std::size_t> node_key(std::string_view name) const;
  std::optional<std::size_t> edge_key(std::string_view name) const;
  // The value of edge key `key` on edge `e`, or the key's default; nullopt when neither exists.
  const std::optional<std::string>& edge_value(std::size_t e, std::size_t key) const;
  const std::optional<std::string>& node_value(std::size_t v, std::size_t key) const;
  // "edge 'e5' (n2 -> n3)", or "edge #5 (n2 -> n3)" when the edge has no id; for messages.
  std::string describe_edge(std::size_t e) const;
};

// Parses GraphML text; throws mosb::Error "FILE: message" (or "FILE:LINE: message" for XML syntax
// errors) on malformed XML, nesting deeper than 64 elements, undeclared keys, unknown or duplicate
// node ids, hyperedges or nested graphs.
GraphmlGraph parse_graphml(std::string_view text, const std::string& display_name);

}  // namespace mosb::converters
