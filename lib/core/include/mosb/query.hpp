#pragma once

#include <cstdint>

namespace mosb {

// One row of a `queries` section: 0-based start and goal vertex ids.
struct Query {
  std::uint32_t start;
  std::uint32_t goal;
  friend bool operator==(const Query&, const Query&) = default;
};
static_assert(sizeof(Query) == 8);

}  // namespace mosb
