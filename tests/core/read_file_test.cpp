#include "mosb/internal/read_file.hpp"

#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "mosb/error.hpp"
#include "temp_dir.hpp"

using namespace mosb;

// The reader of the files a user names (experiment files, solver profiles): a regular file up to
// its cap, nothing else, and a file past the cap refused before it is read.
TEST_CASE("read_regular_file: a regular file up to the cap, refused past it, never waited on") {
  testing::TempDir dir;
  const auto at_cap = dir / "at-cap.toml";
  std::ofstream(at_cap) << std::string(1000, '#');
  CHECK(read_regular_file(at_cap, 1000) == std::string(1000, '#'));
  CHECK_THROWS_WITH_AS(read_regular_file(at_cap, 999),
                       (at_cap.string() + ": more than 999 bytes").c_str(), Error);
  // A sparse file of 1 TiB: refused from its size, nothing read (it would take minutes).
  const auto huge = dir / "huge.toml";
  std::ofstream(huge).close();
  REQUIRE(::truncate(huge.c_str(), off_t{1} << 40) == 0);
  CHECK_THROWS_WITH_AS(read_regular_file(huge, std::uint64_t{16} << 20),
                       (huge.string() + ": more than 16777216 bytes").c_str(), Error);
  // Not regular files: a FIFO (a read would block for ever), a device (never ends), a directory.
  const auto fifo = dir / "fifo.toml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const std::filesystem::path& path : {fifo, std::filesystem::path("/dev/zero"), dir.path()})
    CHECK_THROWS_WITH_AS(read_regular_file(path, 1000),
                         (path.string() + ": not a regular file").c_str(), Error);
  // A link is followed to what it names: to a regular file it reads, to a device it refuses.
  std::filesystem::create_symlink(at_cap, dir / "link.toml");
  CHECK(read_regular_file(dir / "link.toml", 1000).size() == 1000);
  std::filesystem::create_symlink("/dev/zero", dir / "zero.toml");
  CHECK_THROWS_AS(read_regular_file(dir / "zero.toml", 1000), Error);
  CHECK_THROWS_WITH_AS(read_regular_file(dir / "missing.toml", 1000),
                       doctest::Contains("missing.toml: cannot read: No such file"), Error);
}
