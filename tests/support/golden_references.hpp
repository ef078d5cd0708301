// The input behind spec/golden/1.1/references/valid/references.mosb: the 1.0 golden input with a
// per-query reference (section kind 17, spec/SOLUTIONS.md §6) on its set `default`. The file stays
// version 1.0 (a 1.0 reader may ignore kind 17). Changing it changes the golden file, deliberately.
#pragma once

#include "golden_input.hpp"

namespace mosb::testing {

inline GraphInput golden_references_input() {
  auto g = golden_input();
  g.queries[0].reference = QueryReference{"distance", "golden", {2.5, 0, 1e-3}};
  return g;
}

}  // namespace mosb::testing
