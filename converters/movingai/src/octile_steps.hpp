// Steps `convert movingai` and `convert guards` share (movingai.cpp), so both read maps and
// scenarios and record their metadata the same way. Private to the converters library.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "mosb/converters/movingai.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/metadata.hpp"

namespace mosb::converters::octile {

struct MapInput {
  OctileMap map;
  std::string display_name;
  std::string base_name;
};

// Reads and parses the map, recording it as input `index` in `inputs`; throws "FILE: ..." when the
// map has no passable cell (an instance without vertices is no benchmark).
MapInput read_map(const std::string& path, const TerrainRules& terrain, Metadata& inputs,
                  std::size_t index);

// Reads, parses and checks the scenario against the map (input `index`); appends query set `scen`.
void add_scenario(StreamedGraph& graph, const std::string& path, const MapInput& map,
                  Metadata& inputs, std::size_t index);

// The metadata both converters write: the recorded inputs, benchmark, family, id_base,
// source.command and the terrain readings.
void set_metadata(Metadata& m, const Metadata& inputs, const MapInput& map,
                  const std::optional<std::string>& name, const char* command,
                  const TerrainRules& terrain);

}  // namespace mosb::converters::octile
