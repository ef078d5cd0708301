// libFuzzer target: arbitrary bytes through the C ABI (mosb.h) as a solver uses it. The bytes are
// a file (a memfd, opened by its /proc path) given to mosb_open, mosb_open_verified at structure
// level and mosb_load_within; every accessor is called on each handle, with in-range and
// out-of-range indices, and on a handle verified at structure level the walks the example solvers
// do (forward and reverse arcs, costs, query endpoints) index by the file's own ids. Any outcome
// but a documented status (a crash, a sanitizer report, a read out of bounds) is a bug. Seeds: the
// golden files, valid, invalid and packed (tests/fuzz/run.sh).
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "header_checksum.hpp"
#include "mosb.h"

namespace {

std::size_t element_size(mosb_element_type type) {
  switch (type) {
    case MOSB_U8:
      return 1;
    case MOSB_U16:
      return 2;
    case MOSB_U32:
    case MOSB_F32:
      return 4;
    default:
      return 8;
  }
}

// Every accessor; `walk` (only for a handle verified at structure level) also follows the ids the
// file holds, as a solver does.
void use(const mosb_graph* g, bool walk) {
  volatile std::uint64_t sink = 0;
  std::uint64_t n = 0, m = 0;
  const char* text = nullptr;
  (void)mosb_digest(g, &text);
  if (mosb_vertex_count(g, &n) != MOSB_OK || mosb_arc_count(g, &m) != MOSB_OK) return;
  const std::uint64_t* offsets = nullptr;
  const std::uint32_t *targets = nullptr, *sources = nullptr, *arcs = nullptr;
  const bool forward = mosb_forward_csr(g, &offsets, &targets) == MOSB_OK;
  std::size_t d = 0;
  (void)mosb_objective_count(g, &d);
  std::vector<const void*> columns(d, nullptr);
  std::vector<mosb_element_type> types(d, MOSB_U8);
  for (std::size_t i = 0; i <= d; ++i) {  // one past the end: INVALID_ARGUMENT
    const char* name = nullptr;
    std::size_t found = 0;
    if (mosb_objective_name(g, i, &name) == MOSB_OK) (void)mosb_find_objective(g, name, &found);
    (void)mosb_objective_unit(g, i, &text);
    mosb_element_type type = MOSB_U8;
    (void)mosb_objective_type(g, i, &type);
    const void* values = nullptr;
    if (mosb_cost(g, i, &type, &values) == MOSB_OK && i < d) {
      columns[i] = values;
      types[i] = type;
    }
  }
  (void)mosb_find_objective(g, "c1", nullptr);
  if (m <= (std::uint64_t{1} << 16) && d > 0) {
    std::vector<std::uint64_t> u(m);
    std::vector<double> f(m);
    (void)mosb_cost_copy_u64(g, 0, u.data(), u.size());
    (void)mosb_cost_copy_f64(g, d - 1, f.data(), f.size());
    (void)mosb_cost_copy_f64(g, 0, f.data(), f.size() + 1);  // wrong count: INVALID_ARGUMENT
  }
  std::size_t views = 0;
  if (mosb_view_count(g, &views) == MOSB_OK)
    for (std::size_t v = 0; v <= views; ++v) {
      const char* name = nullptr;
      if (mosb_view_name(g, v, &name) != MOSB_OK) continue;
      const std::size_t* objectives = nullptr;
      std::size_t count = 0;
      if (mosb_view(g, name, &objectives, &count, &text) == MOSB_OK)
        for (std::size_t k = 0; k < count; ++k) sink = sink + objectives[k];
    }
  (void)mosb_view(g, "no such view", nullptr, nullptr, nullptr);
  std::size_t sets = 0;
  std::vector<std::pair<const std::uint32_t*, std::size_t>> query_sets;
  if (mosb_query_set_count(g, &sets) == MOSB_OK)
    for (std::size_t s = 0; s <= sets; ++s) {
      const char* name = nullptr;
      const std::uint32_t* pairs = nullptr;
      std::size_t count = 0;
      if (mosb_query_set_name(g, s, &name) == MOSB_OK &&
          mosb_queries(g, name, &pairs, &count) == MOSB_OK)
        query_sets.emplace_back(pairs, count);
    }
  std::size_t length = 0;
  (void)mosb_metadata(g, "source.tool", &text, &length);
  if (!walk) return;
  // Structure verified: offsets ascend to m, every id is below n; read everything they index.
  if (forward && n <= (std::uint64_t{1} << 20))
    for (std::uint64_t v = 0; v < n; ++v)
      for (std::uint64_t a = offsets[v]; a < offsets[v + 1]; ++a) {
        sink = sink + offsets[targets[a]];
        for (std::size_t i = 0; i < d; ++i)
          if (columns[i] != nullptr)
            sink = sink + static_cast<const unsigned char*>(columns[i])[a * element_size(types[i])];
      }
  if (forward && mosb_reverse_csr(g, &offsets, &sources, &arcs) == MOSB_OK &&
      n <= (std::uint64_t{1} << 20))
    for (std::uint64_t v = 0; v < n; ++v)
      for (std::uint64_t a = offsets[v]; a < offsets[v + 1]; ++a)
        sink = sink + offsets[sources[a]] + targets[arcs[a]];
  if (forward)
    for (const auto& [pairs, count] : query_sets)
      for (std::size_t q = 0; q < 2 * count; ++q) sink = sink + offsets[pairs[q]];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::byte> bytes(size);
  if (size > 0) std::memcpy(bytes.data(), data, size);
  mosb_fuzz::repair_header_checksum(bytes);
  const int fd = ::memfd_create("mosb-fuzz", 0);
  if (fd < 0) return 0;
  if (::write(fd, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size())) {
    const std::string path = "/proc/self/fd/" + std::to_string(fd);
    mosb_graph* g = nullptr;
    if (mosb_open(path.c_str(), &g) == MOSB_OK) {
      use(g, false);
      if (mosb_verify(g, MOSB_VERIFY_STRUCTURE) == MOSB_OK) use(g, true);
      mosb_close(g);
    }
    g = nullptr;
    // A cap well under libFuzzer's -rss_limit_mb: a bomb must be refused by it, not by the OOM.
    if (mosb_load_within(path.c_str(), std::uint64_t{256} << 20, &g) == MOSB_OK) {
      if (mosb_verify(g, MOSB_VERIFY_STRUCTURE) == MOSB_OK) use(g, true);
      mosb_close(g);
    }
  }
  ::close(fd);
  return 0;
}
