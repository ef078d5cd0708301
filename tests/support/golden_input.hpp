// The input behind spec/golden/1.0/valid/small.mosb: every section kind and element type the
// format defines. Changing it changes the golden file, deliberately.
#pragma once

#include "mosb/graph_builder.hpp"

namespace mosb::testing {

inline GraphInput golden_input() {
  GraphInput g;
  g.vertex_count = 4;
  g.tails = {2, 0, 1, 0, 3, 2, 1};
  g.heads = {3, 1, 2, 2, 0, 2, 0};
  g.costs.push_back({"distance", "m", std::vector<std::uint64_t>{40, 10, 30, 20, 50, 5, 300}, {}});
  g.costs.push_back({"time", "s", std::vector<double>{1.5, 0.25, 2, 3.75, 4, 0.5, 8}, {}});
  g.costs.push_back({"risk", "", std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7}, {}});
  g.costs.push_back({"hops", "", std::vector<std::uint64_t>(7, 1), format::ElementType::u32});
  g.costs.push_back({"big", "", std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6, 1ULL << 33}, {}});
  g.vertex_data.push_back(
      DataColumn::from("coords", 2,
                       std::vector<std::int32_t>{-73000000, 40000000, -73100000, 40100000,
                                                 -73200000, 40200000, -73300000, 40300000}));
  g.vertex_data.push_back(DataColumn::from(
      "config", 3, std::vector<double>{0, 0.5, 1, 1, 1.5, 2, 2, 2.5, 3, 3, 3.5, 4}));
  g.vertex_data.push_back(
      DataColumn::from("original_id", 1, std::vector<std::uint64_t>{101, 102, 103, 104}));
  g.vertex_data.push_back(
      DataColumn::from("cell", 2, std::vector<std::uint16_t>{0, 0, 1, 0, 0, 1, 1, 1}));
  g.vertex_data.push_back(
      DataColumn::from("elevation", 1, std::vector<std::int16_t>{-5, 0, 12, 7}));
  g.vertex_data.push_back(
      DataColumn::from("height", 1, std::vector<float>{1.5f, 2.5f, 3.5f, 4.5f}));
  g.vertex_data.push_back(DataColumn::from("flags", 1, std::vector<std::int8_t>{-1, 0, 1, 2}));
  g.vertex_data.push_back(
      DataColumn::from("offset", 1, std::vector<std::int64_t>{-1, 0, 1, 1LL << 40}));
  g.arc_data.push_back(DataColumn::from("kind", 1, std::vector<std::uint8_t>{0, 1, 1, 0, 1, 0, 1}));
  g.arc_data.push_back(
      DataColumn::from("lanes", 1, std::vector<std::uint16_t>{1, 2, 3, 4, 5, 6, 7}));
  g.queries.push_back({"default", {{0, 3}, {1, 0}, {3, 3}}});
  g.queries.push_back({"reverse", {{3, 0}}});
  g.metadata.set("benchmark", "golden-small");
  g.metadata.set("family", "road");
  g.metadata.set("id_base", "1");
  g.metadata.set("note", "a value with \\ backslash,\nnewline and = sign");
  // The golden files were written by mosb 0.1.0; pinning the stamp keeps them valid across
  // releases.
  g.metadata.set("source.tool", "mosb 0.1.0");
  g.metadata.set("view.Small_2.objectives", "distance,time");
  g.metadata.set("view.Small_2.queries", "default");
  g.metadata.set("view.Small_5.objectives", "distance,time,risk,hops,big");
  g.metadata.set("view.Small_5.queries", "reverse");
  return g;
}

}  // namespace mosb::testing
