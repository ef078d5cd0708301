#include "mosb/file_writer.hpp"

#include <doctest/doctest.h>

#include <algorithm>

#include "file_patch.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "temp_dir.hpp"

using namespace mosb;

TEST_CASE("an abandoned write leaves neither the target nor a temporary file") {
  testing::TempDir dir;
  {
    FileWriter writer(dir / "out.mosb");
    const std::vector<std::uint32_t> values(1000, 7);
    writer.add_section(format::SectionKind::forward_targets, "forward_targets", 1,
                       std::span<const std::uint32_t>(values));
    CHECK_FALSE(std::filesystem::is_empty(dir.path()));  // the temporary exists while writing
  }
  CHECK(std::filesystem::is_empty(dir.path()));
}

TEST_CASE("a write into a missing directory fails naming the path") {
  testing::TempDir dir;
  CHECK_THROWS_WITH_AS(FileWriter(dir / "no" / "such" / "out.mosb"),
                       doctest::Contains("cannot create a temporary file in"), Error);
}

TEST_CASE("sections start 64-byte aligned and padding is zero") {
  testing::TempDir dir;
  {
    FileWriter writer(dir / "w.mosb");
    const std::vector<std::uint8_t> three = {1, 2, 3};
    writer.add_section(format::SectionKind::arc_data, "a", 1, std::span<const std::uint8_t>(three));
    writer.add_section(format::SectionKind::arc_data, "b", 3, std::span<const std::uint8_t>(three));
    writer.commit(0, 0);
  }
  const auto bytes = testing::read_bytes(dir / "w.mosb");
  const auto h = testing::header_of(bytes);
  CHECK(h.file_size == bytes.size());
  CHECK(h.section_count == 2);
  const auto a = testing::entry_of(bytes, 0), b = testing::entry_of(bytes, 1);
  CHECK(a.offset == 128);
  CHECK(b.offset == 192);
  CHECK(b.row_count == 1);
  for (std::size_t i = a.offset + 3; i < b.offset; ++i) CHECK(bytes[i] == std::byte{0});
  for (std::size_t i = 80; i < 120; ++i) CHECK(bytes[i] == std::byte{0});
}

TEST_CASE("write_graph sorts arcs listed out of order into the CSR, with arrays of megabytes") {
  // Every array of the build is past the size where it is mapped in huge pages
  // (lib/core/internal/mosb/internal/large_array.hpp), and the transpose is built on its own
  // thread: the result must not depend on either.
  constexpr std::uint32_t n = 150'000;
  constexpr std::size_t m = 400'000;
  GraphInput in;
  in.vertex_count = n;
  std::vector<std::uint64_t> distance(m), time(m);
  std::uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return state >> 33;
  };
  for (std::size_t a = 0; a < m; ++a) {
    in.tails.push_back(static_cast<std::uint32_t>(next() % n));
    in.heads.push_back(static_cast<std::uint32_t>(next() % n));
    distance[a] = next() % 60'000;
    time[a] = next() << 8;
  }
  in.costs.push_back({"distance", "m", distance, std::nullopt});
  in.costs.push_back({"time", "s", time, std::nullopt});
  testing::TempDir dir;
  write_graph(in, dir / "big.mosb");

  std::vector<std::uint32_t> order(m);  // the stable sort by tail the format asks for
  for (std::uint32_t a = 0; a < m; ++a) order[a] = a;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t x, std::uint32_t y) { return in.tails[x] < in.tails[y]; });
  const auto reader = GraphReader::open(dir / "big.mosb");
  CHECK_FALSE(verify(reader, VerifyLevel::full).has_value());
  REQUIRE(reader.arc_count() == m);
  const auto targets = reader.forward_targets();
  const auto d = reader.cost<std::uint16_t>("distance");
  const auto t = reader.cost<std::uint64_t>("time");
  std::size_t mismatches = 0;
  for (std::size_t p = 0; p < m; ++p)
    mismatches +=
        targets[p] != in.heads[order[p]] || d[p] != distance[order[p]] || t[p] != time[order[p]];
  CHECK(mismatches == 0);
  const auto offsets = reader.forward_offsets();
  for (std::uint32_t v : {0u, 1u, n / 2, n - 1})
    CHECK(offsets[v + 1] - offsets[v] ==
          static_cast<std::uint64_t>(std::count(in.tails.begin(), in.tails.end(), v)));
}
