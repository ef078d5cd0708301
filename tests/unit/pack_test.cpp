#include "mosb/pack.hpp"

#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "golden_input.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "temp_dir.hpp"

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
