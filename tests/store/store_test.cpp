#include "mosb/store.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "file_patch.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/converters/netmaker_generator.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/manifest.hpp"
#include "mosb/sha256.hpp"
#include "mosb/store_lock.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

std::span<const std::byte> bytes_of(std::string_view text) {
  return std::as_bytes(std::span<const char>(text.data(), text.size()));
}

}  // namespace

TEST_CASE("sha256 gives the FIPS 180-2 test vectors") {
  CHECK(sha256_hex(bytes_of("abc")) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex(bytes_of("")) ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  testing::TempDir dir;
  // More than one 1 MiB read: the streamed hash equals the one-shot hash.
  std::string big(3 * (1 << 20) + 17, 'x');
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 31);
  testing::Bytes bytes(big.size());
  std::memcpy(bytes.data(), big.data(), big.size());
  testing::write_bytes(dir / "big", bytes);
  CHECK(sha256_file(dir / "big") == sha256_hex(bytes_of(big)));
  CHECK_THROWS_AS(sha256_file(dir / "absent"), Error);
  // Fed in uneven pieces (as a download arrives), the same hash; hex() starts it again.
  Sha256 streamed;
  for (std::size_t at = 0, piece = 1; at < big.size(); at += piece, piece = piece * 3 + 1)
    streamed.update(big.data() + at, std::min(piece, big.size() - at));
  CHECK(streamed.hex() == sha256_hex(bytes_of(big)));
  streamed.update("abc", 3);
  CHECK(streamed.hex() == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST_CASE("a manifest serializes deterministically and parses back to the same entries") {
  Manifest m;
  ManifestEntry b{"b.mosb",
                  10,
                  std::string(64, 'a'),
                  std::string(32, 'b'),
                  "1.0",
                  true,
                  "B",
                  {"V_2"},
                  {"default"},
                  {{"b.gr", 5, std::string(16, 'c')}},
                  std::nullopt};
  ManifestEntry a = b;
  a.file = "a.mosb";
  a.packed = false;
  a.sources.clear();
  m.entries = {b, a};
  const auto text = serialize_manifest(m);
  CHECK(text.starts_with("{\"format\":\"mosb-manifest\",\"version\":1}\n"));
  CHECK(text.find("a.mosb") < text.find("b.mosb"));
  const auto back = parse_manifest(text, "M");
  REQUIRE(back.entries.size() == 2);
  CHECK(back.entries[0] == a);
  CHECK(back.entries[1] == b);
  CHECK_FALSE(back.legacy);
  CHECK(serialize_manifest(back) == text);
  m.entries.push_back(a);
  CHECK_THROWS_WITH_AS(serialize_manifest(m), doctest::Contains("listed twice"), Error);
  a.file = "../x";
  CHECK_THROWS_AS(serialize_manifest(Manifest{{a}, false}), Error);
}

TEST_CASE(
    "a solution file's entry round-trips in a version-2 manifest, and bad ones name the line") {
  ManifestEntry instance{
      "g.mosb",    10, std::string(64, 'a'), std::string(32, 'b'), "1.0", false, "G", {"G_2"},
      {"default"}, {}, std::nullopt};
  ManifestEntry reference = instance;
  reference.file = "g.ref.sol";
  reference.digest = std::string(32, 'c');
  reference.solutions = SolutionsEntry{instance.digest,
                                       "0",
                                       "reference",
                                       {"namoa", "ltmoa"},
                                       {{"solved", 9}, {"timeout", 1}},
                                       1234,
                                       {"expanded", "runtime_seconds"}};
  const auto text = serialize_manifest(Manifest{{instance, reference}, false});
  CHECK(text.starts_with("{\"format\":\"mosb-manifest\",\"version\":2}\n"));
  CHECK(text.find("\"kind\":\"solutions\"") != std::string::npos);
  const auto back = parse_manifest(text, "M");
  REQUIRE(back.entries.size() == 2);
  CHECK(back.entries[0] == instance);
  CHECK(back.entries[1] == reference);
  // Without a solution file the manifest stays version 1, byte for byte what mosb wrote before.
  CHECK(serialize_manifest(Manifest{{instance}, false})
            .starts_with("{\"format\":\"mosb-manifest\",\"version\":1}\n"));
  const auto line = text.substr(text.find('\n', text.find('\n') + 1) + 1);
  const auto header = text.substr(0, text.find('\n') + 1);
  auto edited = [&](const std::string& from, const std::string& to) {
    auto changed = line;
    REQUIRE(changed.find(from) != std::string::npos);
    changed.replace(changed.find(from), from.size(), to);
    return header + changed;
  };
  CHECK_THROWS_WITH_AS(
      parse_manifest(edited("\"kind\":\"solutions\"", "\"kind\":\"frontier\""), "M"),
      "M:2: kind 'frontier' is neither \"instance\" nor \"solutions\"", Error);
  CHECK_THROWS_WITH_AS(
      parse_manifest(edited("\"instance\":\"" + instance.digest, "\"instance\":\"xyz"), "M"),
      "M:2: instance is not 32 lowercase hex digits", Error);
  CHECK_THROWS_WITH_AS(parse_manifest(edited("\"epsilon\":\"0\"", "\"epsilon\":\"\""), "M"),
                       "M:2: epsilon '' is not a decimal number", Error);
  CHECK_THROWS_WITH_AS(parse_manifest(edited("\"timeout\"", "\"lost\""), "M"),
                       "M:2: statuses: 'lost' is no status", Error);
  CHECK_THROWS_WITH_AS(parse_manifest(edited("\"solved\":9", "\"solved\":-9"), "M"),
                       "M:2: key 'solved' is not an integer in range", Error);
  CHECK_THROWS_WITH_AS(parse_manifest(edited(",\"epsilon\":\"0\"", ""), "M"),
                       "M:2: missing key 'epsilon'", Error);
}

TEST_CASE("the older TSV MANIFEST is read and bad manifests name the line") {
  const auto legacy = parse_manifest("G-2\tg2.mosb\t20\t" + std::string(32, '1') +
                                         "\nG-1\tg1.mosb\t10\t" + std::string(32, '2') + "\n",
                                     "M");
  CHECK(legacy.legacy);
  REQUIRE(legacy.entries.size() == 2);
  CHECK(legacy.entries[0].file == "g1.mosb");
  CHECK(legacy.entries[0].benchmark == "G-1");
  CHECK(legacy.entries[0].size == 10);
  CHECK(legacy.entries[0].sha256.empty());
  CHECK(legacy.find("g2.mosb") != nullptr);
  CHECK(legacy.find("g3.mosb") == nullptr);
  CHECK_THROWS_WITH_AS(parse_manifest("G\tg.mosb\tten\t" + std::string(32, '1') + "\n", "M"),
                       "M:1: size 'ten' is not a number", Error);
  CHECK_THROWS_WITH_AS(parse_manifest("{\"format\":\"other\",\"version\":1}\n", "M"),
                       doctest::Contains("M:1:"), Error);
  CHECK_THROWS_WITH_AS(parse_manifest("{\"format\":\"mosb-manifest\",\"version\":3}\n", "M"),
                       "M:1: manifest version 3, this mosb reads 1 to 2", Error);
  CHECK_THROWS_WITH_AS(
      parse_manifest("{\"format\":\"mosb-manifest\",\"version\":1}\n{\"file\":\"a\",\"size\":1,"
                     "\"sha256\":\"zz\",\"digest\":\"" +
                         std::string(32, '0') + "\"}\n",
                     "M"),
      "M:2: sha256 is not 64 lowercase hex digits", Error);
}

TEST_CASE("the name rule refuses what a terminal would not show as itself") {
  // Issue 36 item 10: C1 controls and bidirectional formatting characters passed.
  for (const std::string& name : std::vector<std::string>{
           "g\xC2\x85.mosb", "g\xC2\x9B[2J.mosb", "\xE2\x80\xAEgsom.mosb", "g\xE2\x80\xAA",
           "g\xE2\x81\xA6.mosb", "g\xE2\x81\xA9.mosb", "g\xE2\x80\x8F.mosb", "g\xE2\x80\xA8.mosb",
           "g\x85.mosb", "g\xC0\xAF.mosb", "g\x1B[2J.mosb", "g\x7F.mosb", "a/b", "..", "MANIFEST",
           std::string("g\0.mosb", 7)}) {
    CAPTURE(name);
    CHECK_FALSE(is_valid_manifest_file_name(name));
  }
  for (const std::string name :
       {"g.mosb", "Grid-300x300.mosb", "Stra\xC3\x9F.mosb", "\xE6\x97\xA5.mosb", "g\\x1b.mosb",
        "g\xC2\xA0.mosb", "...", ".hidden"})
    CHECK(is_valid_manifest_file_name(name));
}

TEST_CASE("a refused name is in the message whole, a NUL included") {
  // Issue 36 item 11: what() ends at the NUL; message() holds the whole line for the printer,
  // which escapes it.
  const std::string name("g\0evil.mosb", 11);
  const std::string text = std::string(R"({"format":"mosb-manifest","version":1})") + '\n' +
                           R"({"file":"g\u0000evil.mosb","size":1,"sha256":")" +
                           std::string(64, '0') + R"(","digest":")" + std::string(32, '0') +
                           "\"}\n";
  try {
    (void)parse_manifest(text, "M");
    FAIL("a NUL in a name was accepted");
  } catch (const Error& e) {
    CHECK(e.message() ==
          "M:2: invalid file name '" + name + "' (" + std::string(kManifestFileNameRule) + ")");
  }
}

TEST_CASE("Store::instance resolves views and benchmarks and refuses ambiguous names") {
  testing::TempDir dir;
  write_graph(converters::grid_graph({4, 3, 3, 1}), dir / "g1.mosb");
  write_graph(converters::grid_graph({5, 3, 3, 1}), dir / "g2.mosb");
  converters::NetMakerParameters p;
  p.vertices = 100;
  p.name = "NM";
  write_graph(converters::generate_netmaker(p), dir / "nm.mosb");
  auto store = Store::init(dir / "store");
  CHECK_THROWS_AS(Store::init(dir / "store"), Error);
  store.add({dir / "g1.mosb", dir / "g2.mosb", dir / "nm.mosb"}, {});
  const auto reopened = Store::open(dir / "store");
  CHECK(reopened.manifest().entries.size() == 3);

  const auto nm = reopened.instance("NetMaker-100_3");  // a view served by one file
  CHECK(nm.entry.file == "nm.mosb");
  REQUIRE(nm.view);
  CHECK(nm.view->objectives.size() == 3);
  CHECK(nm.query_set == "default");
  CHECK(nm.reader.verified_level() == VerifyLevel::full);
  CHECK(reopened.instance("NM").entry.file == "nm.mosb");  // benchmark with one view

  const auto g = reopened.instance("Grid-5x3/Grid_2");
  CHECK(g.entry.file == "g2.mosb");
  CHECK(g.view->objectives.size() == 2);
  const auto whole = reopened.instance("Grid-4x3");  // two views: the whole file
  CHECK(whole.entry.file == "g1.mosb");
  CHECK_FALSE(whole.view);
  CHECK_THROWS_WITH_AS(reopened.instance("Grid_2"), doctest::Contains("ambiguous"), Error);
  CHECK_THROWS_WITH_AS(reopened.instance("nothing"), doctest::Contains("no entry"), Error);

  // A file changed after it was listed is not handed out.
  auto bytes = testing::read_bytes(dir / "store" / "g1.mosb");
  bytes[bytes.size() / 2] ^= std::byte{1};
  testing::write_bytes(dir / "store" / "g1.mosb", bytes);
  CHECK_THROWS_AS(reopened.instance("Grid-4x3/Grid_3"), Error);
}

TEST_CASE("a store refuses reserved names before placing anything") {
  CHECK(is_reserved_store_name("MANIFEST"));
  CHECK(is_reserved_store_name(".MANIFEST.tmp-123-abcdef"));
  CHECK(is_reserved_store_name(".cache"));
  CHECK(is_reserved_store_name(".staging"));
  CHECK(is_reserved_store_name(kStoreLockFile));
  CHECK(is_reserved_store_name(".x.mosb"));
  CHECK_FALSE(is_reserved_store_name("MANIFEST.mosb"));
  CHECK_FALSE(is_reserved_store_name("g.mosb"));

  testing::TempDir dir;
  std::filesystem::create_directories(dir / "in");
  write_graph(converters::grid_graph({4, 3, 3, 1}), dir / "in" / "MANIFEST");
  write_graph(converters::grid_graph({4, 3, 3, 1}), dir / "in" / ".cache");
  auto store = Store::init(dir / "store");
  const auto manifest = testing::read_bytes(store.manifest_path());
  CHECK_THROWS_WITH_AS(store.add({dir / "in" / "MANIFEST"}, {}),
                       doctest::Contains("cannot be added as 'MANIFEST'"), Error);
  CHECK_THROWS_WITH_AS(store.add({dir / "in" / ".cache"}, {}),
                       doctest::Contains("cannot be added as '.cache'"), Error);
  CHECK(testing::read_bytes(store.manifest_path()) == manifest);
  CHECK_FALSE(std::filesystem::exists(dir / "store" / ".cache"));
}

TEST_CASE("StoreLock excludes a second holder until released and refuses a symlink") {
  testing::TempDir dir;
  std::filesystem::create_directories(dir / "store");
  std::atomic<bool> second_holds{false};
  std::optional<StoreLock> first(std::in_place, dir / "store");
  std::jthread second([&] {
    const StoreLock lock(dir / "store");  // flock: a second open file excludes even this process
    second_holds = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  CHECK_FALSE(second_holds.load());
  first.reset();
  second.join();
  CHECK(second_holds.load());
  CHECK(std::filesystem::is_regular_file(dir / "store" / ".lock"));  // kept: see store_lock.hpp

  std::filesystem::remove(dir / "store" / ".lock");
  testing::write_bytes(dir / "outside", testing::Bytes(3));
  std::filesystem::create_symlink(dir / "outside", dir / "store" / ".lock");
  CHECK_THROWS_WITH_AS(StoreLock(dir / "store"), doctest::Contains("is a symbolic link"), Error);
  CHECK(testing::read_bytes(dir / "outside").size() == 3);
}

TEST_CASE("an add removes an empty .cache left by an earlier version, not a fresh or full one") {
  namespace fs = std::filesystem;
  testing::TempDir dir;
  write_graph(converters::grid_graph({4, 3, 3, 1}), dir / "a.mosb");
  write_graph(converters::grid_graph({5, 3, 3, 2}), dir / "b.mosb");
  auto store = Store::init(dir / "store");
  const auto cache = dir / "store" / ".cache";
  fs::create_directory(cache);
  store.add({dir / "a.mosb"}, {});
  CHECK(fs::is_directory(cache));  // just made: perhaps by a `store instance` about to fill it

  fs::last_write_time(cache, fs::file_time_type::clock::now() - std::chrono::minutes(2));
  store.add({dir / "b.mosb"}, {});
  CHECK_FALSE(fs::exists(cache));

  fs::create_directory(cache);
  testing::write_bytes(cache / "kept", testing::Bytes(1));
  fs::last_write_time(cache, fs::file_time_type::clock::now() - std::chrono::minutes(2));
  write_graph(converters::grid_graph({6, 3, 3, 3}), dir / "c.mosb");
  store.add({dir / "c.mosb"}, {});
  CHECK(fs::exists(cache / "kept"));
}

TEST_CASE("an add with expected entries places only files that are exactly those entries") {
  testing::TempDir dir;
  write_graph(converters::grid_graph({4, 3, 3, 1}), dir / "g.mosb");
  auto expected = describe_file(dir / "g.mosb");
  auto store = Store::init(dir / "store");
  Store::AddOptions options;
  for (const auto& [field, problem] : std::vector<std::pair<int, std::string>>{
           {0, "bytes, the manifest says"}, {1, "SHA-256 "}, {2, "content digest "}}) {
    auto wrong = expected;
    if (field == 0) wrong.size += 1;
    if (field == 1) wrong.sha256 = std::string(64, '0');
    if (field == 2) wrong.digest = std::string(32, '0');
    options.expect = {wrong};
    CHECK_THROWS_WITH_AS(store.add({dir / "g.mosb"}, options), doctest::Contains(problem.c_str()),
                         Error);
    CHECK(Store::open(dir / "store").manifest().entries.empty());
    CHECK_FALSE(std::filesystem::exists(dir / "store" / "g.mosb"));
  }
  options.expect = {expected, expected};
  CHECK_THROWS_AS(store.add({dir / "g.mosb"}, options), Error);  // one per file
  options.expect = {expected};
  store.add({dir / "g.mosb"}, options);
  CHECK(Store::open(dir / "store").manifest().entries.at(0) == expected);
}

TEST_CASE("Store::unpack makes the cache copy of a packed entry and refuses others") {
  testing::TempDir dir;
  write_graph(converters::grid_graph({4, 3, 3, 1}), dir / "g.mosb");
  write_graph(converters::grid_graph({5, 3, 3, 1}), dir / "p.mosb");
  auto store = Store::init(dir / "store");
  store.add({dir / "g.mosb"}, {});
  Store::AddOptions pack;
  pack.pack = PackOptions{};
  store.add({dir / "p.mosb"}, pack);
  const auto copy = store.unpack("p.mosb");
  CHECK(copy == dir / "store" / kCacheDirectory / "p.mosb");
  CHECK(testing::read_bytes(copy) == testing::read_bytes(dir / "p.mosb"));
  CHECK(store.instance("Grid-5x3/Grid_2").path == copy);
  CHECK_THROWS_WITH_AS(store.unpack("g.mosb"), doctest::Contains("not a packed entry"), Error);
  CHECK_THROWS_AS(store.unpack("absent.mosb"), Error);
}
