#include <doctest/doctest.h>

#include "file_patch.hpp"
#include "mosb/error.hpp"
#include "mosb/file_writer.hpp"
#include "mosb/graph_reader.hpp"
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
