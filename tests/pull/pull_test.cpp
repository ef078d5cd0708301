#include "mosb/pull.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "mosb/converters/grid_generator.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/store.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

// A published store of two small grids, g1.mosb and g2.mosb, in DIR/pub.
std::filesystem::path publish(const testing::TempDir& dir) {
  write_graph(converters::grid_graph({4, 3, 2, 1}), dir / "g1.mosb");
  write_graph(converters::grid_graph({5, 3, 2, 1}), dir / "g2.mosb");
  auto store = Store::init(dir / "pub");
  store.add({dir / "g1.mosb", dir / "g2.mosb"}, {});
  return dir / "pub";
}

std::map<std::string, PullStatus> statuses(const PullResult& r) {
  std::map<std::string, PullStatus> out;
  for (const auto& e : r.entries) out[e.entry.file] = e.status;
  return out;
}

}  // namespace

TEST_CASE("is_store_url: what pull fetches from a server, not a directory path") {
  CHECK(is_store_url("https://example.org/suite/"));
  CHECK(is_store_url("http://127.0.0.1:8080/s"));
  CHECK(is_store_url("file:///srv/suite"));
  CHECK_FALSE(is_store_url("/srv/suite"));
  CHECK_FALSE(is_store_url("suite"));
  CHECK_FALSE(is_store_url("ftp://example.org/suite"));
}

TEST_CASE("store_cache: one folder per URL, trailing slashes aside, under MOSB_STORE_CACHE") {
  testing::TempDir dir;
  ::setenv("MOSB_STORE_CACHE", (dir / "cache").c_str(), 1);
  const auto a = store_cache("https://example.org/suite");
  CHECK(a.parent_path() == dir / "cache");
  CHECK(a.filename().string().size() == 16);
  CHECK(store_cache("https://example.org/suite//") == a);
  CHECK(store_cache("https://example.org/other") != a);
  ::unsetenv("MOSB_STORE_CACHE");
}

TEST_CASE("pull fetches a published store's entries, then finds them present") {
  testing::TempDir dir;
  const auto published = publish(dir);
  const auto first = pull(dir / "local", published.string(), {});
  CHECK(first.ok());
  CHECK(statuses(first) == std::map<std::string, PullStatus>{{"g1.mosb", PullStatus::fetched},
                                                             {"g2.mosb", PullStatus::fetched}});
  CHECK(Store::open(dir / "local").manifest().entries.size() == 2);
  const auto again = pull(dir / "local", published.string(), {});
  CHECK(statuses(again) == std::map<std::string, PullStatus>{{"g1.mosb", PullStatus::present},
                                                             {"g2.mosb", PullStatus::present}});
  // A selection by file name; a dry run writes nothing.
  PullOptions only;
  only.files = {"g2*"};
  only.dry_run = true;
  const auto planned = pull(dir / "dry", published.string(), only);
  CHECK(statuses(planned) == std::map<std::string, PullStatus>{{"g2.mosb", PullStatus::planned}});
  CHECK_FALSE(std::filesystem::exists(dir / "dry"));
}

TEST_CASE("pull refuses an entry whose bytes are not the listed ones and places the others") {
  testing::TempDir dir;
  const auto published = publish(dir);
  {
    std::fstream f(published / "g2.mosb", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(-1, std::ios::end);
    f.put('\x55');
  }
  const auto r = pull(dir / "local", published.string(), {});
  CHECK_FALSE(r.ok());
  CHECK(statuses(r) == std::map<std::string, PullStatus>{{"g1.mosb", PullStatus::fetched},
                                                         {"g2.mosb", PullStatus::refused}});
  for (const auto& e : r.entries)
    if (e.status == PullStatus::refused)
      CHECK(message_text(e.reason).find("SHA-256") != std::string::npos);
  const auto local = Store::open(dir / "local").manifest();
  REQUIRE(local.entries.size() == 1);
  CHECK(local.entries.front().file == "g1.mosb");
  CHECK_FALSE(std::filesystem::exists(dir / "local" / "g2.mosb"));
}
