// Turns an arc list with per-objective costs into a canonical mosb instance file: forward CSR
// (stable by tail), its exact transpose, one cost column per objective in the narrowest lossless
// type.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "mosb/format.hpp"
#include "mosb/metadata.hpp"
#include "mosb/progress.hpp"
#include "mosb/query.hpp"

namespace mosb {

struct CostColumn {
  std::string name;
  std::string unit;
  // Integers or reals, in input arc order.
  std::variant<std::vector<std::uint64_t>, std::vector<double>> values;
  std::optional<format::ElementType> forced_type;
};

// Raw little-endian rows of `width` elements of `type`; one row per vertex, or per input arc.
struct DataColumn {
  std::string name;
  format::ElementType type = format::ElementType::u32;
  std::uint32_t width = 1;
  std::vector<std::byte> bytes;

  template <class T>
  static DataColumn from(std::string name, std::uint32_t width, const std::vector<T>& values) {
    DataColumn c{std::move(name), format::element_type_of<T>(), width, {}};
    auto raw = std::as_bytes(std::span(values));
    c.bytes.assign(raw.begin(), raw.end());
    return c;
  }
};

// A published optimum per query of one objective (section kind 17, spec/SOLUTIONS.md §6), in the
// source's own unit; the writer adds the metadata `queries.<set>.reference.objective` and
// `.source`.
struct QueryReference {
  std::string objective;       // the cost section the values refer to
  std::string source;          // e.g. `movingai-optimal`
  std::vector<double> values;  // one per query, finite and >= 0
};

struct QuerySet {
  std::string name;
  std::vector<Query> pairs;
  std::optional<QueryReference> reference = std::nullopt;
};

class FileWriter;

// Writes a set's `queries` section and, when it has a reference, its `query_reference` section of
// the same name right after: the one place both write_graph and rewrite_instance write a set.
void write_query_set(FileWriter& writer, const QuerySet& set);

// Checks a set's reference against its pairs and the objectives (`what` prefixes the message) and
// records its metadata keys in `metadata`; throws mosb::Error.
void add_reference_metadata(Metadata& metadata, const QuerySet& set,
                            const std::vector<std::string>& objectives, const std::string& what);

struct GraphInput {
  std::uint64_t vertex_count = 0;
  std::vector<std::uint32_t> tails;
  std::vector<std::uint32_t> heads;
  std::vector<CostColumn> costs;
  std::vector<DataColumn> vertex_data;
  std::vector<DataColumn> arc_data;
  std::vector<QuerySet> queries;
  Metadata metadata;  // objective units and the writing tool are added by write_graph
};

// The type a cost column is stored in (forced, or the narrowest lossless one); throws mosb::Error
// naming the column when values do not fit, are negative or are not finite.
format::ElementType choose_cost_type(const CostColumn& column);

// Validates the input and writes the instance atomically to `path`. With `expect_digest` (32 hex
// digits) non-empty, a file whose content digest (FORMAT.md §8) differs is not written: throws
// mosb::Error showing both digests, and `path` is left as it was.
void write_graph(const GraphInput& input, const std::filesystem::path& path,
                 const Progress& progress = {}, std::string_view expect_digest = {});

// An instance whose generator can replay its arcs in ascending tail order (and its integer costs
// in the same order) as often as asked: written without holding the arc list, the permutation or
// the costs in memory; only the reverse CSR is built (memory: 8 (n + 1) + 8 m bytes, plus the
// arc and vertex data). Gives the
// same bytes as write_graph of materialize(graph).
struct StreamedGraph {
  using ArcSink = std::function<void(std::uint32_t tail, std::uint32_t head)>;
  using CostSink = std::function<void(std::uint64_t cost)>;
  struct Costs {
    std::string name;
    std::string unit;
    std::function<void(const CostSink&)> replay;  // one value per arc, in arc order
  };
  std::uint64_t vertex_count = 0;
  std::uint64_t arc_count = 0;
  std::function<void(const ArcSink&)> replay_arcs;  // tails ascending, the same sequence every call
  std::vector<Costs> costs;
  std::vector<DataColumn> arc_data;     // held in memory: one row per arc, in arc order
  std::vector<DataColumn> vertex_data;  // held in memory: one row per vertex
  std::vector<QuerySet> queries;
  Metadata metadata;
};

void write_graph(const StreamedGraph& graph, const std::filesystem::path& path,
                 const Progress& progress = {}, std::string_view expect_digest = {});

// The same instance as a GraphInput (for tests and for callers that edit it before writing).
GraphInput materialize(const StreamedGraph& graph);

}  // namespace mosb
