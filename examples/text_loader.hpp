// The benchmark's baseline for namoa (namoa_text): what solvers commonly do instead of mapping a
// file: read DIMACS .gr text with iostreams, hold every arc in vectors, then build the forward and
// reverse CSR. INSTANCE is one .gr or several joined by ',' (one per objective, same arcs in the
// same order); a file may carry several cost columns. Vertex ids are 1-based, as in DIMACS.
#pragma once

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "example_common.hpp"

namespace examples {

struct TextGraph {
  std::vector<std::uint64_t> offsets, reverse_offsets;
  std::vector<std::uint32_t> targets, reverse_sources, reverse_arcs;
  std::vector<std::vector<std::uint32_t>> costs;
};

inline Instance open_text(const Options& o) {
  if (!o.view.empty() || !o.query_set.empty() || !o.objectives.empty() || o.queries.empty())
    usage_error(o.program, "a text instance takes --query S T only");
  auto text = std::make_shared<TextGraph>();
  std::vector<std::uint32_t> tails, heads;
  std::uint64_t n = 0;
  for (std::size_t pos = 0; pos <= o.instance.size();) {
    const std::size_t comma = std::min(o.instance.find(',', pos), o.instance.size());
    const std::string file = o.instance.substr(pos, comma - pos);
    pos = comma + 1;
    std::ifstream in(file);
    if (!in) throw mosb::Error(file + ": cannot open");
    const bool first = tails.empty() && text->costs.empty();
    const std::size_t column0 = text->costs.size();
    std::string line;
    std::uint64_t line_number = 0, arc = 0;
    while (std::getline(in, line)) {
      ++line_number;
      auto fail = [&] {
        throw mosb::Error(file + ":" + std::to_string(line_number) + ": bad line");
      };
      std::istringstream fields(line);
      std::string kind;
      fields >> kind;
      if (kind == "p") {
        std::string sp;
        fields >> sp >> n;
        if (!fields) fail();
      } else if (kind == "a") {
        std::uint64_t u = 0, v = 0, c = 0;
        if (!(fields >> u >> v) || u < 1 || v < 1 || u > n || v > n) fail();
        std::size_t column = column0;
        while (fields >> c) {
          if (column == text->costs.size()) text->costs.emplace_back();
          text->costs[column++].push_back(static_cast<std::uint32_t>(c));
        }
        if (column == column0) fail();
        if (first) {
          tails.push_back(static_cast<std::uint32_t>(u - 1));
          heads.push_back(static_cast<std::uint32_t>(v - 1));
        } else if (arc >= tails.size() || tails[arc] != u - 1 || heads[arc] != v - 1) {
          throw mosb::Error(file + ":" + std::to_string(line_number) +
                            ": not the arc of the first file");
        }
        ++arc;
      }
    }
    for (std::size_t k = column0; k < text->costs.size(); ++k)
      if (text->costs[k].size() != tails.size()) throw mosb::Error(file + ": arc count differs");
  }
  // Forward and reverse CSR by counting sort; arcs keep their file order within a vertex.
  const std::size_t m = tails.size();
  text->offsets.assign(n + 1, 0);
  text->reverse_offsets.assign(n + 1, 0);
  for (std::size_t a = 0; a < m; ++a)
    ++text->offsets[tails[a] + 1], ++text->reverse_offsets[heads[a] + 1];
  for (std::size_t v = 0; v < n; ++v) {
    text->offsets[v + 1] += text->offsets[v];
    text->reverse_offsets[v + 1] += text->reverse_offsets[v];
  }
  std::vector<std::uint32_t> order(m);
  std::vector<std::uint64_t> next(text->offsets.begin(), text->offsets.end() - 1);
  for (std::size_t a = 0; a < m; ++a) order[next[tails[a]]++] = static_cast<std::uint32_t>(a);
  text->targets.resize(m);
  for (auto& column : text->costs) {
    std::vector<std::uint32_t> sorted(m);
    for (std::size_t a = 0; a < m; ++a) sorted[a] = column[order[a]];
    column.swap(sorted);
  }
  std::vector<std::uint32_t> position(m);  // file arc -> CSR arc
  for (std::size_t a = 0; a < m; ++a) text->targets[a] = heads[order[a]], position[order[a]] = a;
  text->reverse_sources.resize(m);
  text->reverse_arcs.resize(m);
  next.assign(text->reverse_offsets.begin(), text->reverse_offsets.end() - 1);
  for (std::size_t a = 0; a < m; ++a) {
    const std::uint64_t e = next[heads[order[a]]]++;
    text->reverse_sources[e] = tails[order[a]];
    text->reverse_arcs[e] = static_cast<std::uint32_t>(a);
  }
  Instance in;
  for (auto q : o.queries)
    if (q.start < 1 || q.goal < 1 || q.start > n || q.goal > n)
      throw mosb::Error(o.instance + ": query vertex out of range (ids are 1-based)");
    else
      in.queries.push_back({q.start - 1, q.goal - 1});
  Graph& g = in.graph;
  g.vertex_count = n;
  g.offsets = text->offsets;
  g.targets = text->targets;
  g.reverse_offsets = text->reverse_offsets;
  g.reverse_sources = text->reverse_sources;
  g.reverse_arcs = text->reverse_arcs;
  for (const auto& column : text->costs)
    g.costs.push_back(column_of(std::span<const std::uint32_t>(column)));
  in.owner = text;
  return in;
}

}  // namespace examples
