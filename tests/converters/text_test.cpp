// The helpers every converter shares: NAME[:UNIT] objective specs and the narrowest data column.
#include <doctest/doctest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mosb/converters/narrow_column.hpp"
#include "mosb/converters/objective.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/error.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;
using namespace mosb::converters;

TEST_CASE("objective specs: NAME and NAME:UNIT, the unit after the first colon") {
  const auto plain = parse_objective("distance", "convert x");
  CHECK(plain.name == "distance");
  CHECK(plain.unit.empty());
  const auto with_unit = parse_objective("time:s:approx", "convert x");
  CHECK(with_unit.name == "time");
  CHECK(with_unit.unit == "s:approx");
  CHECK_THROWS_WITH_AS(parse_objective(":m", "convert x"),
                       "convert x: objective ':m' has an empty name", Error);
  CHECK_THROWS_AS(parse_objective("", "convert x"), Error);
  CHECK(objective_list({plain, with_unit, {"risk", ""}}) == "distance,time:s:approx,risk");
  CHECK(objective_list({}).empty());
}

TEST_CASE("narrowest data column: the first candidate holding every value") {
  using u8 = std::uint8_t;
  using u16 = std::uint16_t;
  using u32 = std::uint32_t;
  using u64 = std::uint64_t;
  const auto u = [](std::vector<u64> v) { return narrowest_column<u8, u16, u32, u64>("c", 1, v); };
  CHECK(u({}).type == format::ElementType::u8);
  CHECK(u({0, 255}).type == format::ElementType::u8);
  CHECK(u({0, 256}).type == format::ElementType::u16);
  CHECK(u({65536}).type == format::ElementType::u32);
  CHECK(u({std::uint64_t{1} << 32}).type == format::ElementType::u64);
  const auto c = u({1, 300});
  CHECK(c.bytes.size() == 4);
  CHECK(c.name == "c");
  const auto s = [](std::vector<std::int64_t> v) {
    return narrowest_column<std::int32_t, std::int64_t>("s", 2, v);
  };
  CHECK(s({-5, 7}).type == format::ElementType::i32);
  CHECK(s({std::numeric_limits<std::int32_t>::min(), 0}).type == format::ElementType::i32);
  CHECK(s({std::int64_t{std::numeric_limits<std::int32_t>::min()} - 1, 0}).type ==
        format::ElementType::i64);
  CHECK(s({std::int64_t{1} << 31, 0}).type == format::ElementType::i64);
  CHECK(s({1, 2}).width == 2);
  // A smallest candidate: cells are at least u16, whatever the values.
  const auto cells = narrowest_column<u16, u32>("cell", 2, std::vector<u32>{3, 4});
  CHECK(cells.type == format::ElementType::u16);
  CHECK(narrowest_column<u16, u32>("cell", 2, std::vector<u32>{65536, 0}).type ==
        format::ElementType::u32);
}

TEST_CASE("plain input streams in chunks that end after a newline and rejoin to the file") {
  testing::TempDir dir;
  // 20 MiB of numbered lines, then one line longer than a chunk (10 MiB), then no final newline.
  std::string text;
  for (std::size_t i = 0; text.size() < (std::size_t{20} << 20); ++i)
    text += "a " + std::to_string(i) + " " + std::to_string(i * 7919 % 100003) + "\n";
  text += std::string(std::size_t{10} << 20, 'x') + "\n";
  text += "last line";
  testing::write_text(dir / "big.txt", text);
  InputFile input(dir / "big.txt");
  std::string joined;
  std::size_t chunks = 0;
  std::string_view chunk;
  bool ends_ok = true;
  while (input.next_chunk(chunk)) {
    ++chunks;
    joined += chunk;
    if (joined.size() < text.size() && chunk.back() != '\n') ends_ok = false;
  }
  CHECK(chunks >= 3);
  CHECK(ends_ok);
  CHECK(joined == text);
  // Released pages come back from the file when the text is read again.
  input.rewind();
  std::string again;
  while (input.next_chunk(chunk)) again += chunk;
  CHECK(again == text);
}
