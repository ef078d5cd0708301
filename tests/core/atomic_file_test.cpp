#include "mosb/atomic_file.hpp"

#include <doctest/doctest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "mosb/converters/grid_generator.hpp"
#include "mosb/converters/suite.hpp"
#include "mosb/error.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

std::vector<std::string> names_in(const std::filesystem::path& directory) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(directory))
    names.push_back(e.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

void touch(const std::filesystem::path& path, const std::string& text = "x") {
  std::ofstream(path) << text;
}

pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

}  // namespace

TEST_CASE(
    "atomic file: the temporary is named .NAME.tmp-PID-XXXXXX and removed when not committed") {
  testing::TempDir dir;
  {
    AtomicFile file(dir / "out.txt");
    file.write("hello");
    // .out.txt.tmp-PID- and six letters or digits (no std::regex: GCC 12 warns inside it under
    // the sanitizers).
    const std::string name = file.temporary().filename().string();
    const std::string prefix = ".out.txt.tmp-" + std::to_string(::getpid()) + "-";
    CHECK(name.size() == prefix.size() + 6);
    CHECK(name.rfind(prefix, 0) == 0);
    CHECK(std::all_of(name.begin() + static_cast<std::ptrdiff_t>(prefix.size()), name.end(),
                      [](unsigned char c) { return std::isalnum(c) != 0; }));
    CHECK(names_in(dir.path()) == std::vector<std::string>{file.temporary().filename()});
  }
  CHECK(std::filesystem::is_empty(dir.path()));
}

TEST_CASE("atomic file: commit renames into place and replaces a symlink at the target name") {
  testing::TempDir dir;
  touch(dir / "elsewhere", "keep");
  std::filesystem::create_symlink(dir / "elsewhere", dir / "out.txt");
  {
    AtomicFile file(dir / "out.txt");
    file.write("new");
    file.commit();
  }
  CHECK_FALSE(std::filesystem::is_symlink(dir / "out.txt"));
  CHECK(std::filesystem::file_size(dir / "out.txt") == 3);
  CHECK(std::filesystem::file_size(dir / "elsewhere") == 4);
  CHECK(names_in(dir.path()) == std::vector<std::string>{"elsewhere", "out.txt"});
}

TEST_CASE(
    "atomic file: stale temporaries of dead processes are removed and reported, others kept") {
  testing::TempDir dir;
  const auto dead = std::to_string(dead_pid());
  const auto live = std::to_string(::getppid());
  const std::string stale = ".out.txt.tmp-" + dead + "-Ab3xYz";
  const std::vector<std::string> kept = {
      ".other.txt.tmp-" + dead + "-Ab3xYz",  // another target
      ".out.txt.tmp-" + live + "-Ab3xYz",    // a live process
      ".out.txt.tmp-" + dead + "-Ab3",       // not our pattern
      ".out.txt.tmp-XXXXXX",                 // the old, PID-less names
  };
  touch(dir / stale);
  for (const auto& name : kept) touch(dir / name);
  std::vector<std::filesystem::path> reported;
  set_stale_temporary_handler([&](const std::filesystem::path& p) { reported.push_back(p); });
  {
    AtomicFile file(dir / "out.txt");
    file.commit();
  }
  set_stale_temporary_handler({});
  CHECK(reported == std::vector<std::filesystem::path>{dir / stale});
  auto expected = kept;
  expected.push_back("out.txt");
  std::sort(expected.begin(), expected.end());
  CHECK(names_in(dir.path()) == expected);
}

TEST_CASE(
    "atomic file: an in-place rewrite keeps the mode and refuses read-only and hard-linked files") {
  testing::TempDir dir;
  touch(dir / "f");
  ::chmod((dir / "f").c_str(), 0640);
  {
    AtomicFile file(dir / "f", AtomicFile::Existing::rewrite_in_place);
    file.write("rewritten");
    file.commit();
  }
  struct stat st {};
  ::stat((dir / "f").c_str(), &st);
  CHECK((st.st_mode & 07777) == 0640);
  CHECK(st.st_size == 9);

  ::chmod((dir / "f").c_str(), 0444);
  CHECK_THROWS_WITH_AS(AtomicFile(dir / "f", AtomicFile::Existing::rewrite_in_place),
                       doctest::Contains("read-only"), Error);
  ::chmod((dir / "f").c_str(), 0644);
  std::filesystem::create_hard_link(dir / "f", dir / "g");
  CHECK_THROWS_WITH_AS(AtomicFile(dir / "f", AtomicFile::Existing::rewrite_in_place),
                       doctest::Contains("2 hard links"), Error);
  CHECK(names_in(dir.path()) == std::vector<std::string>{"f", "g"});
}

TEST_CASE("atomic file: an output that is an input is refused by device and inode") {
  testing::TempDir dir;
  touch(dir / "in");
  std::filesystem::create_hard_link(dir / "in", dir / "hard");
  std::filesystem::create_symlink(dir / "in", dir / "soft");
  for (const char* output : {"in", "hard", "soft"})
    CHECK_THROWS_WITH_AS(check_output_is_not_input(dir / output, {dir / "other", dir / "in"}),
                         doctest::Contains("is the same file as the input"), Error);
  CHECK_THROWS_AS(check_output_is_not_input(dir / "in", {dir / "soft"}), Error);
  touch(dir / "copy");
  CHECK_NOTHROW(check_output_is_not_input(dir / "copy", {dir / "in"}));
  CHECK_NOTHROW(check_output_is_not_input(dir / "new", {dir / "in"}));
  CHECK_NOTHROW(check_output_is_not_input(dir / "in", {""}));
}

TEST_CASE("atomic file: a suite's files and MANIFEST get mode 0666 & ~umask") {
  testing::TempDir dir;
  converters::GridParameters grid;
  grid.width = grid.height = 2;
  const std::vector<converters::SuiteInstance> instances = {
      {"a", [grid] { return converters::generate_grid(grid); }}};
  converters::SuiteOptions options;
  options.threads = 1;
  const mode_t saved = ::umask(077);
  try {
    converters::run_suite(dir.path(), instances, options);
  } catch (...) {
    ::umask(saved);
    throw;
  }
  ::umask(saved);
  struct stat st {};
  REQUIRE(::stat((dir / "MANIFEST").c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0600);
  REQUIRE(::stat((dir / "a.mosb").c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0600);
  CHECK(names_in(dir.path()) == std::vector<std::string>{"MANIFEST", "a.mosb"});
}
