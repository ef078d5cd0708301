#include "mosb/pack.hpp"

#include <doctest/doctest.h>
#include <xxhash.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <string>

#include "file_patch.hpp"
#include "golden_input.hpp"
#include "mosb/file_writer.hpp"
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
  const auto loaded = mosb::load(packed, VerifyLevel::full);
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
  CHECK(mosb::load(plain).bytes().size() == original.bytes().size());
}

TEST_CASE("pack_file refuses a bad level and leaves no output") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "plain.mosb");
  CHECK_THROWS_WITH_AS(pack_file(dir / "plain.mosb", dir / "out.mosb", PackOptions{0, 1}),
                       doctest::Contains("zstd level 0"), Error);
  CHECK_FALSE(std::filesystem::exists(dir / "out.mosb"));
}

namespace {
const std::filesystem::path kGolden = std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "golden";
const std::filesystem::path kPackedGolden = kGolden / "1.1" / "packed";

PackOptions keeping_reverse() {
  PackOptions options;
  options.derive_reverse = false;
  return options;
}
}  // namespace

TEST_CASE("the packed golden files unpack to verified instances and pack back to the same bytes") {
  testing::TempDir dir;
  std::set<format::Encoding> encodings;
  struct Golden {
    std::filesystem::path file;
    PackOptions options;  // what packs it again: 1.1 files keep their reverse CSR
    std::uint16_t minor;
  };
  for (const auto& entry :
       {Golden{kPackedGolden / "valid" / "small.packed.mosb", keeping_reverse(), 1},
        Golden{kPackedGolden / "valid" / "grid.packed.mosb", keeping_reverse(), 1},
        Golden{kGolden / "1.2" / "packed" / "valid" / "grid.packed.mosb", {}, 2}}) {
    // Not a structured binding: CAPTURE (a lambda) cannot name one in clang 14.
    const auto& golden = entry.file;
    const auto& options = entry.options;
    const auto minor = entry.minor;
    CAPTURE(golden);
    const auto packed = GraphReader::open(golden);  // header, table and metadata, not the frames
    CHECK(packed.header().version_minor == minor);
    for (const auto& s : packed.sections())
      encodings.insert(static_cast<format::Encoding>(s.entry.encoding));
    const auto loaded = mosb::load(golden, VerifyLevel::full);
    CHECK(loaded.digest() == packed.digest());
    unpack_file(golden, dir / "plain.mosb");
    pack_file(dir / "plain.mosb", dir / "again.mosb", options);
    CHECK_MESSAGE(bytes_of(dir / "again.mosb") == bytes_of(golden),
                  "mosb pack no longer reproduces the golden packed file: a change of the "
                  "packer or of libzstd's output; packed suites would change their bytes");
  }
  CHECK(encodings.count(format::Encoding::zstd) == 1);
  CHECK(encodings.count(format::Encoding::shuffle_zstd) == 1);
  CHECK(encodings.count(format::Encoding::delta_zstd) == 1);
  CHECK(encodings.count(format::Encoding::transpose) == 1);
  const auto small = mosb::load(kPackedGolden / "valid" / "small.packed.mosb");
  unpack_file(kPackedGolden / "valid" / "small.packed.mosb", dir / "small.mosb");
  CHECK(bytes_of(dir / "small.mosb") ==
        bytes_of(std::filesystem::path(MOSB_SOURCE_DIR) / "spec/golden/1.0/valid/small.mosb"));
  CHECK(small.digest() == GraphReader::open(dir / "small.mosb").digest());
}

TEST_CASE("every invalid packed golden file is refused where EXPECTED.tsv says") {
  std::size_t files = 0;
  testing::TempDir dir;
  for (const auto& invalid : {kPackedGolden / "invalid", kGolden / "1.2" / "packed" / "invalid"})
    for (const auto& row : testing::expected_rows(invalid / "EXPECTED.tsv")) {
      REQUIRE(row.size() == 2);
      const auto file = invalid / row[0];
      const auto& expected = row[1];
      CAPTURE(file);
      ++files;
      std::string message;
      try {
        (void)mosb::load(file, VerifyLevel::full);
      } catch (const Error& error) {
        message = error.what();
      }
      CHECK_MESSAGE(message.find(expected) != std::string::npos, message);
      CHECK_MESSAGE(message.find(file.string()) == 0, message);
      CHECK_THROWS_AS(unpack_file(file, dir / "out.mosb"), Error);
      CHECK_FALSE(std::filesystem::exists(dir / "out.mosb"));
    }
  CHECK(files == std::size(testing::kPackedFaults) + std::size(testing::kTransposeFaults));
}

namespace {
std::vector<format::Encoding> encodings_of(const std::filesystem::path& file) {
  std::vector<format::Encoding> encodings;
  const auto reader = GraphReader::open(file);
  for (const auto& s : reader.sections())
    encodings.push_back(static_cast<format::Encoding>(s.entry.encoding));
  return encodings;
}
bool is_reverse(const Section& s) {
  return s.kind == format::SectionKind::reverse_offsets ||
         s.kind == format::SectionKind::reverse_sources ||
         s.kind == format::SectionKind::reverse_arcs;
}
}  // namespace

TEST_CASE("pack derives the reverse CSR by default and --keep-reverse stores it") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "plain.mosb");
  pack_file(dir / "plain.mosb", dir / "derived.mosb", {});
  pack_file(dir / "plain.mosb", dir / "kept.mosb", keeping_reverse());
  const auto derived = GraphReader::open(dir / "derived.mosb");
  CHECK(derived.header().version_minor == 2);
  CHECK((derived.header().required_features & format::kFeatureTransposeSections) != 0);
  std::size_t derived_sections = 0;
  for (const auto& s : derived.sections()) {
    const bool transposed =
        s.entry.encoding == static_cast<std::uint8_t>(format::Encoding::transpose);
    CHECK(transposed == is_reverse(s));
    if (transposed) CHECK(s.entry.stored_length == 0);
    derived_sections += transposed;
  }
  CHECK(derived_sections == 3);
  const auto kept = encodings_of(dir / "kept.mosb");
  CHECK(std::count(kept.begin(), kept.end(), format::Encoding::transpose) == 0);
  CHECK(std::filesystem::file_size(dir / "derived.mosb") <
        std::filesystem::file_size(dir / "kept.mosb"));
  unpack_file(dir / "derived.mosb", dir / "a.mosb");
  unpack_file(dir / "kept.mosb", dir / "b.mosb");
  CHECK(bytes_of(dir / "a.mosb") == bytes_of(dir / "plain.mosb"));
  CHECK(bytes_of(dir / "b.mosb") == bytes_of(dir / "plain.mosb"));
  CHECK(mosb::load(dir / "derived.mosb").digest() ==
        GraphReader::open(dir / "plain.mosb").digest());
}

TEST_CASE("pack and unpack refuse a damaged input and write nothing") {
  // Structurally invalid (verify --level structure refuses it) but checksummed: packing it once
  // kept the damage (storing the reverse section, not deriving it); now it writes nothing.
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "plain.mosb");
  auto b = testing::read_bytes(dir / "plain.mosb");
  const auto i = testing::find_entry(b, "reverse_sources");
  const auto e = testing::entry_of(b, i);
  std::uint32_t first;
  std::memcpy(&first, b.data() + e.offset, 4);
  first ^= 1;
  std::memcpy(b.data() + e.offset, &first, 4);
  testing::reseal_section(b, i);
  testing::write_bytes(dir / "odd.mosb", b);
  const auto odd = dir / "odd.mosb";
  for (const auto& out : {dir / "packed.mosb", odd}) {
    CHECK_THROWS_WITH_AS(pack_file(odd, out, {}),
                         doctest::Contains((odd.string() + ": file is damaged: section ").c_str()),
                         Error);
    CHECK_THROWS_WITH_AS(unpack_file(odd, out), doctest::Contains("nothing written"), Error);
  }
  CHECK_FALSE(std::filesystem::exists(dir / "packed.mosb"));
  CHECK(testing::read_bytes(odd) == b);
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator()) == 2);  // plain, odd: no temporary
}

TEST_CASE("every padding byte of a packed file is checked, and pack does not repair it") {
  testing::TempDir dir;
  const auto golden = kPackedGolden / "valid" / "small.packed.mosb";
  const auto original = testing::read_bytes(golden);
  const auto reader = GraphReader::open(golden);
  std::vector<bool> padding(reader.header().table_offset, true);
  for (std::size_t i = 0; i < format::kHeaderSize; ++i) padding[i] = false;
  for (const auto& s : reader.sections())
    for (std::uint64_t i = 0; i < s.entry.stored_length; ++i) padding[s.entry.offset + i] = false;
  const auto bad = dir / "bad.mosb";
  std::size_t flipped = 0;
  for (std::size_t i = 0; i < padding.size(); ++i) {
    if (!padding[i]) continue;
    auto b = original;
    b[i] ^= std::byte{0x01};
    testing::write_bytes(bad, b);
    CAPTURE(i);
    const auto full = verify_file(bad, VerifyLevel::full);
    REQUIRE(full.problem.has_value());
    CHECK(full.problem->starts_with("[padding] byte " + std::to_string(i) + " "));
    CHECK(verify_file(bad, VerifyLevel::structure).problem == full.problem);
    CHECK_FALSE(verify_file(bad, VerifyLevel::checksums).problem.has_value());
    CHECK_FALSE(verify_file(bad, VerifyLevel::header).problem.has_value());
    ++flipped;
  }
  CHECK(flipped > 64);
  CHECK_FALSE(verify_file(golden, VerifyLevel::full).problem.has_value());
  CHECK_THROWS_WITH_AS(pack_file(bad, dir / "out.mosb", keeping_reverse()),
                       doctest::Contains("[padding]"), Error);
  CHECK_THROWS_WITH_AS(unpack_file(bad, dir / "out.mosb"), doctest::Contains("[padding]"), Error);
  CHECK_FALSE(std::filesystem::exists(dir / "out.mosb"));
}

TEST_CASE("decoding stays within the memory cap, refusing before it allocates") {
  const auto golden = kPackedGolden / "valid" / "grid.packed.mosb";
  const auto file = map_file(golden);
  const auto needed = unpack_bytes(file.bytes, "grid").bytes.size();
  CHECK_THROWS_WITH_AS(unpack_bytes(file.bytes, "grid", 1024),
                       doctest::Contains("grid: decoding needs "), Error);
  CHECK_THROWS_WITH_AS(
      unpack_bytes(file.bytes, "grid", needed),
      doctest::Contains(("more than the cap of " + std::to_string(needed)).c_str()), Error);
  CHECK(unpack_bytes(file.bytes, "grid", 2 * needed + 64).bytes.size() == needed);
  CHECK_THROWS_WITH_AS(mosb::load(golden, 4096), doctest::Contains("more than the cap"), Error);
  CHECK(available_memory() > 0);
}

TEST_CASE("a derived reverse CSR needs a forward CSR that is one") {
  // The 1.2 golden Grid with its forward targets stored raw, one of them out of range and the
  // checksums sealed: only the derivation can find it, and it must refuse, not write past the end.
  testing::TempDir dir;
  const auto golden = kGolden / "1.2" / "packed" / "valid" / "grid.packed.mosb";
  const auto source = GraphReader::open(golden);
  const auto n = source.header().vertex_count;
  const auto loaded = mosb::load(golden);
  const auto targets = loaded.forward_targets();
  std::vector<std::uint32_t> broken(targets.begin(), targets.end());
  broken.back() = static_cast<std::uint32_t>(n);
  {
    FileWriter writer(dir / "broken.mosb", AtomicFile::Existing::replace);
    for (const auto& s : source.sections()) {
      if (s.kind != format::SectionKind::forward_targets) {
        writer.add_encoded_section(s.entry, s.stored);
        continue;
      }
      auto entry = s.entry;
      entry.encoding = static_cast<std::uint8_t>(format::Encoding::raw);
      const auto raw = std::as_bytes(std::span(broken));
      entry.checksum = XXH3_64bits(raw.data(), raw.size());
      writer.add_encoded_section(entry, raw);
    }
    writer.commit(n, source.header().arc_count);
  }
  CHECK_THROWS_WITH_AS(mosb::load(dir / "broken.mosb"),
                       doctest::Contains("the forward CSR is not one"), Error);
  CHECK_THROWS_AS(unpack_file(dir / "broken.mosb", dir / "out.mosb"), Error);
  CHECK_FALSE(std::filesystem::exists(dir / "out.mosb"));
}

namespace {

// "ok", or what refused the file: a problem or an Error (its message).
std::string outcome_of(const std::function<FileVerification()>& check) {
  try {
    const auto found = check();
    return found.problem ? "problem: " + *found.problem : "ok " + found.digest;
  } catch (const Error& error) {
    return std::string("error: ") + error.what();
  }
}

// verify_file_streaming agrees with verify_file at level full: both pass (with one digest) or both
// refuse. `budget` small enough spills every large frame and sorts the transpose in many runs.
void check_streaming_agrees(const std::filesystem::path& file, std::uint64_t budget,
                            const std::filesystem::path& scratch) {
  CAPTURE(file);
  CAPTURE(budget);
  const auto expected = outcome_of([&] { return verify_file(file, VerifyLevel::full); });
  const auto streamed = outcome_of([&] {
    return verify_file_streaming(file, StreamingVerifyOptions{budget, scratch});
  });
  CAPTURE(expected);
  CAPTURE(streamed);
  CHECK(expected.starts_with("ok") == streamed.starts_with("ok"));
  if (expected.starts_with("ok")) CHECK(expected == streamed);
  // A refusal names the file, or (a problem, which callers prefix with it) the section or padding.
  const bool named = streamed.find(file.string()) != std::string::npos ||
                     streamed.starts_with("problem: section '") ||
                     streamed.starts_with("problem: [padding]");
  if (!streamed.starts_with("ok")) CHECK(named);
}

// A random graph of `n` vertices and `m` arcs with an integer, a float and a fractional cost.
GraphInput random_graph(std::uint32_t n, std::uint32_t m, std::uint64_t seed) {
  GraphInput g;
  g.vertex_count = n;
  std::uint64_t state = seed;
  auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<std::uint32_t>(state >> 33);
  };
  std::vector<std::uint64_t> distance;
  std::vector<double> time;
  for (std::uint32_t a = 0; a < m; ++a) {
    g.tails.push_back(next() % n);
    // A few heads take many arcs, as hubs do.
    g.heads.push_back(a % 7 == 0 ? next() % 5 : next() % n);
    distance.push_back(next() % 100000);
    time.push_back((next() % 1000) / 8.0);
  }
  g.costs.push_back({"distance", "m", distance, {}});
  g.costs.push_back({"time", "s", time, {}});
  g.queries.push_back({"default", {{0, n - 1}, {1, 2}}});
  return g;
}

}  // namespace

TEST_CASE("verify_file_streaming finds what verify_file finds, in any memory budget") {
  testing::TempDir dir;
  std::vector<std::filesystem::path> files;
  for (const auto& folder :
       {kGolden / "1.0" / "valid", kGolden / "1.0" / "invalid", kPackedGolden / "valid",
        kPackedGolden / "invalid", kGolden / "1.2" / "packed" / "valid",
        kGolden / "1.2" / "packed" / "invalid"})
    for (const auto& entry : std::filesystem::directory_iterator(folder))
      if (entry.path().extension() == ".mosb") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  CHECK(files.size() >= 30);
  // Large enough that frames stream and spill and the transpose merges many runs at 4 KiB.
  write_graph(random_graph(30000, 120000, 7), dir / "random.mosb");
  pack_file(dir / "random.mosb", dir / "random.packed.mosb", PackOptions{3, 1});
  pack_file(dir / "random.mosb", dir / "random.keep.mosb", [] {
    auto options = keeping_reverse();
    options.level = 3;
    return options;
  }());
  for (const auto* name : {"random.mosb", "random.packed.mosb", "random.keep.mosb"})
    files.push_back(dir / name);
  for (const auto& file : files)
    for (const std::uint64_t budget : {std::uint64_t{4096}, std::uint64_t{32} << 20})
      check_streaming_agrees(file, budget, dir.path());
  // The budget bounds the work, not the outcome: the same digest at every size.
  const auto digest = GraphReader::open(dir / "random.mosb").digest();
  for (const auto* name : {"random.mosb", "random.packed.mosb", "random.keep.mosb"})
    CHECK(verify_file_streaming(dir / name, {65536, dir.path()}).digest == digest);
}

TEST_CASE("verify_file_streaming finds a reverse CSR that is not the transpose in every budget") {
  testing::TempDir dir;
  write_graph(random_graph(3000, 20000, 11), dir / "plain.mosb");
  // Two entries of one in-list swapped, every checksum resealed: only the transpose rule fails.
  auto bytes = testing::read_bytes(dir / "plain.mosb");
  const auto reader = GraphReader::open(dir / "plain.mosb");
  const auto roff = reader.reverse_offsets();
  std::uint64_t v = 0;
  while (roff[v + 1] - roff[v] < 2) ++v;
  const auto arcs = testing::find_entry(bytes, "reverse_arcs");
  const auto sources = testing::find_entry(bytes, "reverse_sources");
  const auto j = roff[v];
  const auto ra = reader.reverse_arcs();
  const auto rs = reader.reverse_sources();
  testing::poke<std::uint32_t>(bytes, arcs, j, ra[j + 1]);
  testing::poke<std::uint32_t>(bytes, arcs, j + 1, ra[j]);
  testing::poke<std::uint32_t>(bytes, sources, j, rs[j + 1]);
  testing::poke<std::uint32_t>(bytes, sources, j + 1, rs[j]);
  testing::reseal_section(bytes, arcs);
  testing::reseal_section(bytes, sources);
  testing::write_bytes(dir / "swapped.mosb", bytes);
  const auto found = verify_file(dir / "swapped.mosb", VerifyLevel::full);
  REQUIRE(found.problem);
  CHECK(found.problem->find("reverse-transpose") != std::string::npos);
  pack_file(dir / "plain.mosb", dir / "keep.mosb", keeping_reverse());
  for (const std::uint64_t budget :
       {std::uint64_t{4096}, std::uint64_t{65536}, std::uint64_t{32} << 20}) {
    CAPTURE(budget);
    const auto streamed = verify_file_streaming(dir / "swapped.mosb", {budget, dir.path()});
    REQUIRE(streamed.problem);
    CHECK(streamed.problem->find("[reverse-transpose] entry " + std::to_string(j)) !=
          std::string::npos);
    CHECK_FALSE(verify_file_streaming(dir / "keep.mosb", {budget, dir.path()}).problem);
  }
}

TEST_CASE(
    "verify_file_streaming refuses, before it spills, a check that needs more disk than allowed") {
  // Issue 36 item 12: a few KiB of packed arcs that all go 0 -> 1, with one cost, decode to
  // megabytes of arcs: the check in buckets spills 12 bytes per arc, far beyond the download.
  testing::TempDir dir;
  GraphInput g;
  g.vertex_count = 2;
  const std::uint32_t m = 300000;
  g.tails.assign(m, 0);
  g.heads.assign(m, 1);
  g.costs.push_back({"c", "", std::vector<std::uint64_t>(m, 1), {}});
  write_graph(g, dir / "plain.mosb");
  pack_file(dir / "plain.mosb", dir / "packed.mosb", PackOptions{19, 1});
  const auto size = std::filesystem::file_size(dir / "packed.mosb");
  CHECK(size < 8192);
  const auto reader = GraphReader::open(dir / "packed.mosb");
  const std::uint64_t bound = streaming_spill_bound(reader, 4096);
  CHECK(bound >= 12 * std::uint64_t{m});
  CHECK(bound > default_check_disk(size, 4096));
  // The default: 64 times the file or 8 times the memory, whichever is more.
  CHECK(default_check_disk(size, 4096) == std::max<std::uint64_t>(64 * size, 32768));
  CHECK(default_check_disk(5632, std::uint64_t{32} << 20) == std::uint64_t{256} << 20);
  CHECK(default_check_disk(std::uint64_t{1} << 30, 4096) == std::uint64_t{64} << 30);
  CHECK(default_check_disk(UINT64_MAX / 2, 4096) == UINT64_MAX);
  // In 32 MiB the transpose fits: nothing spills, nothing is refused.
  CHECK(streaming_spill_bound(reader, std::uint64_t{32} << 20) == 0);
  const auto fine =
      verify_file_streaming(dir / "packed.mosb", {std::uint64_t{32} << 20, dir.path()});
  CHECK_FALSE(fine.problem);
  CHECK(fine.spilled == 0);
  // In 4 KiB it would spill: refused at the default limit, saying what it needs and the limit.
  const std::string said =
      (dir / "packed.mosb").string() + ": checking it in 4096 bytes of memory needs up to " +
      std::to_string(bound) + " bytes of disk for its spill file, more than the limit of " +
      std::to_string(default_check_disk(size, 4096)) + " bytes (the default: 64 times its " +
      std::to_string(size) +
      " bytes or 8 times the memory, whichever is more; streaming_verify.disk SIZE, "
      "or more streaming_verify.memory, allows it)";
  CHECK_THROWS_WITH_AS(verify_file_streaming(dir / "packed.mosb", {4096, dir.path()}),
                       doctest::Contains(said.c_str()), Error);
  CHECK_THROWS_AS(
      verify_file_streaming(dir / "packed.mosb", {4096, dir.path(), nullptr, bound - 1}), Error);
  // Allowed the disk, it passes, and the spill file never grew past the bound.
  const auto allowed =
      verify_file_streaming(dir / "packed.mosb", {4096, dir.path(), nullptr, bound});
  CHECK_FALSE(allowed.problem);
  CHECK(allowed.spilled == bound);
  // The unpacked file holds more than it spills: the default limit never refuses one.
  const auto plain = verify_file_streaming(dir / "plain.mosb", {4096, dir.path()});
  CHECK_FALSE(plain.problem);
  CHECK(plain.spilled <= std::filesystem::file_size(dir / "plain.mosb"));
}

TEST_CASE("the spill bound is what the check spills, in every budget") {
  testing::TempDir dir;
  write_graph(random_graph(30000, 120000, 5), dir / "random.mosb");
  pack_file(dir / "random.mosb", dir / "packed.mosb", PackOptions{3, 1});
  pack_file(dir / "random.mosb", dir / "keep.mosb", keeping_reverse());
  for (const auto* name : {"random.mosb", "packed.mosb", "keep.mosb"})
    for (const std::uint64_t budget :
         {std::uint64_t{4096}, std::uint64_t{1} << 20, std::uint64_t{32} << 20}) {
      CAPTURE(name);
      CAPTURE(budget);
      const auto bound = streaming_spill_bound(GraphReader::open(dir / name), budget);
      const auto found =
          verify_file_streaming(dir / name, {budget, dir.path(), nullptr, UINT64_MAX});
      CHECK_FALSE(found.problem);
      // Every region the check spills is in the bound, and nothing else: the spill file of a
      // valid file grows to the bound exactly.
      CHECK(found.spilled == bound);
    }
}
