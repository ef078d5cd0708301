// The paper's NetMaker family ("Synthetic Graphs: NetMaker"): a random directed Hamiltonian cycle
// with low/medium/high costs permuted per arc, plus cheap arcs inside a vertex-id locality window.
// Every draw is fixed in spec/GENERATORS.md; ids here are 0-based (the paper's u is our u - 1).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "mosb/graph_builder.hpp"

namespace mosb::converters {

struct NetMakerParameters {
  std::uint32_t vertices = 10000;  // N
  std::uint32_t amin = 1;          // target out-degree is uniform in {amin + 1, ..., amax}
  std::uint32_t amax = 10;
  std::uint32_t locality = 20;  // I: the window is u +- floor(I / 2)
  std::uint64_t seed = 1;
  std::uint32_t queries = 50;
  std::uint32_t query_percent = 10;  // sources among the first, targets among the last P% of ids
  std::optional<std::string> name;   // benchmark; default NetMaker-N<N>-I<I>
};

// The view of a NetMaker instance (c1 … cd): one per size and d, as the paper's Table 1 splits
// NetMaker: NetMaker-10k_3 for 10,000 vertices and 3 objectives, NetMaker-300_2 for 300 and 2
// (thousands as "k" when 1,000 divides N). spec/suite.json's netmaker `views`.
std::string netmaker_view(std::uint64_t vertices, std::size_t objectives);

// Arc data section `kind` (u8): which part of the construction an arc comes from.
inline constexpr std::uint8_t kNetMakerCycleArc = 0;
inline constexpr std::uint8_t kNetMakerLocalityArc = 1;

// Arcs come out in tail order, so the instance streams into its file (write_graph) without an arc
// list in memory: only the cycle (4 bytes per vertex), the arc kinds (1 byte per arc) and the
// writer's reverse CSR are held.
StreamedGraph netmaker_graph(const NetMakerParameters& p);

// The same instance held in memory.
GraphInput generate_netmaker(const NetMakerParameters& p);

// An existing NetMaker file: a 0-based DIMACS-like .gr with one cost column per objective (plain
// or compressed). Its view netmaker_view = c1..cd, no query set (`mosb queries import` adds it).
GraphInput convert_netmaker(const std::filesystem::path& gr_file,
                            const std::optional<std::string>& name);

}  // namespace mosb::converters
