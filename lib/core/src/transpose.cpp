#include "mosb/internal/transpose.hpp"

#include <algorithm>

namespace mosb {

bool derive_transpose(std::span<const std::uint64_t> offsets,
                      std::span<const std::uint32_t> targets, std::uint64_t* reverse_offsets,
                      std::uint32_t* reverse_sources, std::uint32_t* reverse_arcs) {
  if (offsets.empty()) return false;
  const std::uint64_t n = offsets.size() - 1, m = targets.size();
  if (n > UINT32_MAX || m > UINT32_MAX || offsets[0] != 0 || offsets[n] != m) return false;
  for (std::uint64_t u = 0; u < n; ++u)
    if (offsets[u] > offsets[u + 1]) return false;
  // reverse_offsets[v + 2] counts the arcs into v (v + 2 <= n); the running sum then leaves the
  // first entry of v in reverse_offsets[v + 1], which placing v's arcs advances to its end.
  std::fill_n(reverse_offsets, n + 1, std::uint64_t{0});
  for (const std::uint64_t v : targets) {
    if (v >= n) return false;
    if (v + 2 <= n) ++reverse_offsets[v + 2];
  }
  for (std::uint64_t v = 2; v <= n; ++v) reverse_offsets[v] += reverse_offsets[v - 1];
  for (std::uint64_t u = 0; u < n; ++u)
    for (std::uint64_t a = offsets[u]; a < offsets[u + 1]; ++a) {
      const std::uint64_t entry = reverse_offsets[std::uint64_t{targets[a]} + 1]++;
      reverse_sources[entry] = static_cast<std::uint32_t>(u);
      reverse_arcs[entry] = static_cast<std::uint32_t>(a);
    }
  return true;
}

}  // namespace mosb
