// GraphML (as written by boost::write_graphml, which OMPL's PlannerData::printGraphML uses) read
// into nodes, edges and their attribute values as text. Attribute names are resolved through the
// <key id=... for=... attr.name=...> declarations, never by matching the key ids themselves.
//
// Parsed with expat, a streaming (SAX) parser: nothing of the document is kept but the values
// themselves, in one text arena with an 8-byte reference per value (spec/families/robots.md,
// "Memory").
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/converters/text_scan.hpp"

namespace mosb::converters {

struct GraphmlKey {
  std::string id;
  std::string name;                          // attr.name
  std::string type;                          // attr.type, may be empty
  std::optional<std::string> default_value;  // <default>, trimmed
};

struct GraphmlEdge {
  std::uint32_t source = 0;
  std::uint32_t target = 0;
  bool directed = true;  // the edge's `directed` attribute, else the graph's edgedefault
};

class GraphmlGraph {
 public:
  bool edge_default_directed = true;
  std::vector<GraphmlKey> node_keys;  // keys for="node" or for="all"
  std::vector<GraphmlKey> edge_keys;  // keys for="edge" or for="all"
  std::vector<GraphmlEdge> edges;     // in document order

  std::size_t node_count() const { return node_ids_.size(); }
  std::string_view node_id(std::size_t v) const { return text(node_ids_[v]).value_or(""); }
  std::optional<std::size_t> node_key(std::string_view name) const;
  std::optional<std::size_t> edge_key(std::string_view name) const;
  // The trimmed value of key `key` on edge `e` (node `v`), or the key's default; nullopt when
  // neither exists. Views into the graph: valid while it lives.
  std::optional<std::string_view> edge_value(std::size_t e, std::size_t key) const;
  std::optional<std::string_view> node_value(std::size_t v, std::size_t key) const;
  // "edge 'e5' ('n2' -> 'n3')", or "edge #5 ('n2' -> 'n3')" when the edge has no id; for messages.
  std::string describe_edge(std::size_t e) const;

 private:
  friend class GraphmlBuilder;
  // A value in text_: offset and length; kAbsent as length when the element gave none.
  struct Ref {
    std::uint32_t offset = 0;
    std::uint32_t length = kAbsent;
  };
  static constexpr std::uint32_t kAbsent = 0xFFFFFFFFu;
  std::optional<std::string_view> text(Ref r) const;

  std::string text_;
  std::vector<Ref> node_ids_;
  std::vector<Ref> edge_ids_;
  std::vector<Ref> node_values_;  // node_count() x node_keys.size()
  std::vector<Ref> edge_values_;  // edges.size() x edge_keys.size()
};

// Parses GraphML text; throws mosb::Error "FILE: message" (or "FILE:LINE: message" for XML syntax
// errors) on malformed XML, nesting deeper than 64 elements, undeclared keys, unknown or duplicate
// node ids, hyperedges or nested graphs, or more than 4 GiB of value text.
// The text comes in chunks (an InputFile streams a file, decompressing it) or whole.
GraphmlGraph parse_graphml(text::TextSource& source, const std::string& display_name);
GraphmlGraph parse_graphml(std::string_view text, const std::string& display_name);

}  // namespace mosb::converters
