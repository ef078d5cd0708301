#include "mosb/pack.hpp"

#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "golden_input.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "packed_faults.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;

namespace {

std::vector<char> bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <class T>
bool same(std::span<const T> a, std::span<const T> b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

}  // namespace

TEST_CASE("pack_file and unpack_file restore the exact bytes, load reads the packed file") {
  testing::TempDir dir;
  const auto plain = dir / "plain.mosb";
  const auto packed = dir / "packed.mosb";
  const auto unpacked = dir / "unpacked.mosb";
  write_graph(testing::golden_input(), plain);
  pack_file(plain, packed, PackOptions{19, 2});
  unpack_file(packed, unpacked);
  CHECK(bytes_of(unpacked) == bytes_of(plain));

  const auto original = GraphReader::open(plain, VerifyLevel::full);
  CHECK_FALSE(is_packed(original.header()));
  const auto loaded = GraphReader::load(packed, VerifyLevel::full);
  CHECK(is_packed(GraphReader::open(packed).header()));
  CHECK_FALSE(is_packed(loaded.header()));
  CHECK(loaded.digest() == original.digest());
  CHECK(reinterpret_cast<std::uintptr_t>(loaded.bytes().data()) % format::kAlignment == 0);
  CHECK(same(loaded.forward_offsets(), original.forward_offsets()));
  CHECK(same(loaded.forward_targets(), original.forward_targets()));
  CHECK(same(loaded.reverse_arcs(), original.reverse_arcs()));
  CHECK(loaded.objective_count() == original.objective_count());
  for (std::size_t i = 0; i < original.objective_count(); ++i) {
    CHECK(loaded.objective(i).name == original.objective(i).name);
    CHECK(std::memcmp(loaded.raw_bytes(loaded.objective(i)).data(),
                      original.raw_bytes(original.objective(i)).data(),
                      original.objective(i).decoded_length) == 0);
  }
  // The zero-copy reader refuses the packed file loudly.
  CHECK_THROWS_WITH_AS(GraphReader::open(packed, VerifyLevel::checksums),
                       doctest::Contains("zstd-packed"), Error);
  // Packing the packed file again gives the same bytes.
  pack_file(packed, dir / "again.mosb", PackOptions{});
  CHECK(bytes_of(dir / "again.mosb") == bytes_of(packed));
  // An unpacked file loads as it opens.
  CHECK(GraphReader::load(plain).bytes().size() == original.bytes().size());
}

TEST_CASE("pack_file refuses a bad level and leaves no output") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "plain.mosb");
  CHECK_THROWS_WITH_AS(pack_file(dir / "plain.mosb", dir / "out.mosb", PackOptions{0, 1}),
                       doctest::Contains("zstd level 0"), Error);
  CHECK_FALSE(std::filesystem::exists(dir / "out.mosb"));
}

namespace {
const std::filesystem::path kPackedGolden =
    std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "golden" / "1.1" / "packed";
}

TEST_CASE("the packed golden files unpack to verified instances and pack back to the same bytes") {
  testing::TempDir dir;
  std::set<format::Encoding> encodings;
  for (const char* name : {"small.packed.mosb", "grid.packed.mosb"}) {
    CAPTURE(name);
    const auto golden = kPackedGolden / "valid" / name;
    const auto packed = GraphReader::open(golden);  // header, table and metadata, not the frames
    for (const auto& s : packed.sections())
      encodings.insert(static_cast<format::Encoding>(s.entry.encoding));
    const auto loaded = GraphReader::load(golden, VerifyLevel::full);
    CHECK(loaded.digest() == packed.digest());
    unpack_file(golden, dir / "plain.mosb");
    pack_file(dir / "plain.mosb", dir / "again.mosb", {});
    CHECK_MESSAGE(bytes_of(dir / "again.mosb") == bytes_of(golden),
                  "mosb pack no longer reproduces the golden packed file: a change of the "
                  "packer or of libzstd's output; packed suites would change their bytes");
  }
  CHECK(encodings.count(format::Encoding::zstd) == 1);
  CHECK(encodings.count(format::Encoding::shuffle_zstd) == 1);
  CHECK(encodings.count(format::Encoding::delta_zstd) == 1);
  const auto small = GraphReader::load(kPackedGolden / "valid" / "small.packed.mosb");
  unpack_file(kPackedGolden / "valid" / "small.packed.mosb", dir / "small.mosb");
  CHECK(bytes_of(dir / "small.mosb") ==
        bytes_of(std::filesystem::path(MOSB_SOURCE_DIR) / "spec/golden/1.0/valid/small.mosb"));
  CHECK(small.digest() == GraphReader::open(dir / "small.mosb").digest());
}

TEST_CASE("every invalid packed golden file is refused where EXPECTED.tsv says") {
  std::size_t files = 0;
  testing::TempDir dir;
  for (const auto& row : testing::expected_rows(kPackedGolden / "invalid" / "EXPECTED.tsv")) {
    REQUIRE(row.size() == 2);
    const auto file = kPackedGolden / "invalid" / row[0];
    const auto& expected = row[1];
    CAPTURE(file);
    ++files;
    std::string message;
    try {
      (void)GraphReader::load(file, VerifyLevel::full);
    } catch (const Error& error) {
      message = error.what();
    }
    CHECK_MESSAGE(message.find(expected) != std::string::npos, message);
    CHECK_MESSAGE(message.find(file.string()) == 0, message);
    CHECK_THROWS_AS(unpack_file(file, dir / "out.mosb"), Error);
    CHECK_FALSE(std::filesystem::exists(dir / "out.mosb"));
  }
  CHECK(files == std::size(testing::kPackedFaults));
}
