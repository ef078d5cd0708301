#include "mosb/converters/graphml_reader.hpp"

#include <expat.h>

#include <memory>
#include <unordered_map>

#include "mosb/error.hpp"
#include "mosb/format.hpp"

namespace mosb::converters {

namespace {

constexpr std::size_t kMaxDepth = 64;
using format::kMaxCount;

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

std::string_view trimmed(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

const char* attribute(const XML_Char** attributes, std::string_view name) {
  for (auto a = attributes; *a; a += 2)
    if (name == a[0]) return a[1];
  return nullptr;
}

std::string attribute_or_empty(const XML_Char** attributes, std::string_view name) {
  const char* value = attribute(attributes, name);
  return value ? value : "";
}

}  // namespace

// Receives expat's callbacks and builds the graph. Callbacks must not throw through expat (C): the
// first problem is kept, the parser stopped, and parse_graphml throws it.
class GraphmlBuilder {
 public:
  explicit GraphmlBuilder(const std::string& file) : file_(file) {}

  void start(std::string_view tag, const XML_Char** attributes) {
    const std::size_t depth = stack_.size() + 1;
    if (depth > kMaxDepth)
      return fail("elements nested deeper than " + std::to_string(kMaxDepth) + " levels");
    // A copy: the push below may reallocate the stack and move the parent's name.
    const std::string parent = stack_.empty() ? std::string() : stack_.back();
    stack_.emplace_back(tag);
    if (depth == 1) {
      in_root_ = tag == "graphml";
    } else if (!in_root_) {
      return;
    } else if (depth == 2 && tag == "key") {
      start_key(attributes);
    } else if (depth == 3 && parent == "key" && tag == "default") {
      target_ = Target::key_default;
      collect(depth);
    } else if (depth == 2 && tag == "graph") {
      start_graph(attributes);
    } else if (depth == 3 && in_graph_ && tag == "node") {
      start_node(attributes);
    } else if (depth == 3 && in_graph_ && tag == "edge") {
      start_edge(attributes);
    } else if (depth == 3 && in_graph_ && tag == "hyperedge") {
      fail("<hyperedge> is not a roadmap edge");
    } else if (depth == 4 && parent == "node" && tag == "graph") {
      fail("nested <graph> inside a node");
    } else if (depth == 4 && (parent == "node" || parent == "edge") && tag == "data" && in_graph_) {
      start_data(parent == "node", attributes);
    }
  }

  void end() {
    if (collecting_ && stack_.size() == collect_depth_) finish_value();
    if (stack_.size() == 2 && stack_.back() == "graph") in_graph_ = false;
    stack_.pop_back();
  }

  // The text directly inside the element being collected, as GraphML values are plain text.
  void characters(std::string_view text) {
    if (collecting_ && stack_.size() == collect_depth_) pending_ += text;
  }

  bool failed() const { return problem_.has_value(); }
  const std::string& problem() const { return *problem_; }
  void set_parser(XML_Parser parser) { parser_ = parser; }

  GraphmlGraph finish() {
    if (!in_root_) throw Error(file_ + ": no <graphml> root element");
    if (!seen_graph_) throw Error(file_ + ": no <graph> element");
    // Nodes first: GraphML lets edges precede the nodes they name.
    for (std::size_t e = 0; e < g_.edges.size(); ++e) {
      for (int side = 0; side < 2; ++side) {
        const auto name = *g_.text(edge_ends_[2 * e + side]);
        const auto it = vertex_of_.find(std::string(name));
        if (it == vertex_of_.end())
          throw Error(file_ + ": " + edge_label(e) + ": " + (side == 0 ? "source " : "target ") +
                      shown(name) + " is no node");
        (side == 0 ? g_.edges[e].source : g_.edges[e].target) = it->second;
      }
    }
    return std::move(g_);
  }

 private:
  void fail(const std::string& what) {
    if (problem_) return;
    problem_ = file_ + ": " + what;
    XML_StopParser(parser_, XML_FALSE);
  }

  GraphmlGraph::Ref store(std::string_view value) {
    if (g_.text_.size() + value.size() >= GraphmlGraph::kAbsent) {
      fail("more than 4 GiB of GraphML values");
      return {};
    }
    GraphmlGraph::Ref r{static_cast<std::uint32_t>(g_.text_.size()),
                        static_cast<std::uint32_t>(value.size())};
    g_.text_ += value;
    return r;
  }

  std::string edge_label(std::size_t e) const {
    const auto id = g_.text(g_.edge_ids_[e]);
    return id && !id->empty() ? "edge " + shown(*id) : "edge #" + std::to_string(e);
  }

  void start_key(const XML_Char** attributes) {
    GraphmlKey key{attribute_or_empty(attributes, "id"),
                   attribute_or_empty(attributes, "attr.name"),
                   attribute_or_empty(attributes, "attr.type"),
                   {}};
    if (key.id.empty()) return fail("a <key> without an id");
    const auto domain = attribute_or_empty(attributes, "for");
    key_is_node_ = domain == "node" || domain == "all";
    key_is_edge_ = domain == "edge" || domain == "all";
    if ((key_is_node_ && node_keys_.count(key.id)) || (key_is_edge_ && edge_keys_.count(key.id)))
      return fail("key " + shown(key.id) + " declared twice");
    if (key_is_node_) node_keys_.emplace(key.id, g_.node_keys.size()), g_.node_keys.push_back(key);
    if (key_is_edge_) edge_keys_.emplace(key.id, g_.edge_keys.size()), g_.edge_keys.push_back(key);
  }

  void start_graph(const XML_Char** attributes) {
    if (seen_graph_) return fail("more than one <graph> (one roadmap per file)");
    seen_graph_ = in_graph_ = true;
    const auto edge_default = attribute_or_empty(attributes, "edgedefault");
    if (edge_default != "directed" && edge_default != "undirected")
      return fail("<graph edgedefault=" + shown(edge_default) +
                  ">: expected 'directed' or 'undirected'");
    g_.edge_default_directed = edge_default == "directed";
  }

  void start_node(const XML_Char** attributes) {
    std::string id = attribute_or_empty(attributes, "id");
    if (g_.node_ids_.size() >= kMaxCount)
      return fail("more than " + std::to_string(kMaxCount) + " nodes");
    if (!vertex_of_.emplace(id, static_cast<std::uint32_t>(g_.node_ids_.size())).second)
      return fail("node id " + shown(id) + " appears twice");
    g_.node_ids_.push_back(store(id));
    g_.node_values_.resize(g_.node_values_.size() + g_.node_keys.size());
  }

  void start_edge(const XML_Char** attributes) {
    const std::size_t e = g_.edges.size();
    g_.edge_ids_.push_back(store(attribute_or_empty(attributes, "id")));
    edge_ends_.push_back(store(attribute_or_empty(attributes, "source")));
    edge_ends_.push_back(store(attribute_or_empty(attributes, "target")));
    GraphmlEdge edge;
    edge.directed = g_.edge_default_directed;
    if (const char* d = attribute(attributes, "directed")) {
      const std::string_view value = d;
      if (value != "true" && value != "false")
        return fail(edge_label(e) + ": directed=" + shown(value) + ": expected 'true' or 'false'");
      edge.directed = value == "true";
    }
    g_.edges.push_back(edge);
    g_.edge_values_.resize(g_.edge_values_.size() + g_.edge_keys.size());
  }

  void start_data(bool node, const XML_Char** attributes) {
    const auto key = attribute_or_empty(attributes, "key");
    const auto& keys = node ? node_keys_ : edge_keys_;
    const std::string what = node ? "node " + shown(g_.node_id(g_.node_ids_.size() - 1))
                                  : edge_label(g_.edges.size() - 1);
    const auto it = keys.find(key);
    if (it == keys.end())
      return fail(what + ": <data key=" + shown(key) + "> names no key declared for it");
    const std::size_t row = node ? g_.node_ids_.size() - 1 : g_.edges.size() - 1;
    const std::size_t width = node ? g_.node_keys.size() : g_.edge_keys.size();
    auto& slot = (node ? g_.node_values_ : g_.edge_values_)[row * width + it->second];
    if (slot.length != GraphmlGraph::kAbsent)
      return fail(what + ": second <data> for key " + shown(key));
    value_slot_ = &slot;
    target_ = Target::data;
    collect(4);
  }

  void collect(std::size_t depth) {
    collecting_ = true;
    collect_depth_ = depth;
    pending_.clear();
  }

  void finish_value() {
    collecting_ = false;
    const auto value = trimmed(pending_);
    if (target_ == Target::data) {
      *value_slot_ = store(value);
    } else {
      // A key's <default>: the key was just appended to its domain(s).
      if (key_is_node_) g_.node_keys.back().default_value = std::string(value);
      if (key_is_edge_) g_.edge_keys.back().default_value = std::string(value);
    }
    pending_.clear();
  }

  enum class Target { key_default, data };

  const std::string& file_;
  XML_Parser parser_ = nullptr;
  GraphmlGraph g_;
  std::vector<std::string> stack_;
  bool in_root_ = false, seen_graph_ = false, in_graph_ = false;
  bool key_is_node_ = false, key_is_edge_ = false;
  std::unordered_map<std::string, std::size_t> node_keys_, edge_keys_;
  std::unordered_map<std::string, std::uint32_t> vertex_of_;
  std::vector<GraphmlGraph::Ref> edge_ends_;  // source, target names per edge, resolved at the end
  bool collecting_ = false;
  std::size_t collect_depth_ = 0;
  Target target_ = Target::data;
  GraphmlGraph::Ref* value_slot_ = nullptr;
  std::string pending_;
  std::optional<std::string> problem_;
};

std::optional<std::string_view> GraphmlGraph::text(Ref r) const {
  if (r.length == kAbsent) return std::nullopt;
  return std::string_view(text_).substr(r.offset, r.length);
}

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

std::optional<std::string_view> GraphmlGraph::edge_value(std::size_t e, std::size_t key) const {
  if (auto own = text(edge_values_[e * edge_keys.size() + key])) return own;
  return edge_keys[key].default_value;
}

std::optional<std::string_view> GraphmlGraph::node_value(std::size_t v, std::size_t key) const {
  if (auto own = text(node_values_[v * node_keys.size() + key])) return own;
  return node_keys[key].default_value;
}

std::string GraphmlGraph::describe_edge(std::size_t e) const {
  const auto id = text(edge_ids_[e]);
  const std::string name = id && !id->empty() ? "edge " + shown(*id) : "edge #" + std::to_string(e);
  return name + " (" + shown(node_id(edges[e].source)) + " -> " + shown(node_id(edges[e].target)) +
         ")";
}

GraphmlGraph parse_graphml(text::TextSource& source, const std::string& display_name) {
  const auto& file = display_name;
  GraphmlBuilder builder(file);
  std::unique_ptr<XML_ParserStruct, decltype(&XML_ParserFree)> parser(XML_ParserCreate(nullptr),
                                                                      &XML_ParserFree);
  if (!parser) throw Error(file + ": out of memory creating the XML parser");
  builder.set_parser(parser.get());
  XML_SetUserData(parser.get(), &builder);
  XML_SetElementHandler(
      parser.get(),
      [](void* self, const XML_Char* tag, const XML_Char** attributes) {
        static_cast<GraphmlBuilder*>(self)->start(tag, attributes);
      },
      [](void* self, const XML_Char*) { static_cast<GraphmlBuilder*>(self)->end(); });
  XML_SetCharacterDataHandler(parser.get(), [](void* self, const XML_Char* s, int length) {
    static_cast<GraphmlBuilder*>(self)->characters({s, static_cast<std::size_t>(length)});
  });
  const auto feed = [&](std::string_view piece, bool last) {
    const auto status = XML_Parse(parser.get(), piece.data(), static_cast<int>(piece.size()), last);
    if (builder.failed()) throw Error(builder.problem());
    if (status != XML_STATUS_OK)
      throw Error(file + ":" + std::to_string(XML_GetCurrentLineNumber(parser.get())) +
                  ": XML error: " + XML_ErrorString(XML_GetErrorCode(parser.get())));
  };
  std::uint64_t offset = 0;
  std::string_view chunk;
  while (source.next_chunk(chunk)) {
    if (const auto nul = chunk.find('\0'); nul != std::string_view::npos)
      throw Error(file + ": a NUL byte at offset " + std::to_string(offset + nul) +
                  " (not XML text)");
    offset += chunk.size();
    // XML_Parse takes an int length.
    constexpr std::size_t kPiece = std::size_t{1} << 30;
    for (std::size_t at = 0; at < chunk.size(); at += kPiece) feed(chunk.substr(at, kPiece), false);
  }
  feed({}, true);
  return builder.finish();
}

GraphmlGraph parse_graphml(std::string_view text, const std::string& display_name) {
  struct WholeText final : text::TextSource {
    std::string_view text;
    bool given = false;
    bool next_chunk(std::string_view& chunk) override {
      if (given) return false;
      given = true;
      chunk = text;
      return true;
    }
  } source;
  source.text = text;
  return parse_graphml(source, display_name);
}

}  // namespace mosb::converters
