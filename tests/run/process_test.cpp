// ProcessRunner (lib/run/src/process.hpp), in process: each query's processes forked by the job's
// fork server, executed, limited, measured and reaped; what a program holds when it starts.
#include "process.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace mosb;
using namespace mosb::run_internal;
namespace fs = std::filesystem;

namespace {

std::string contents(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A directory of queries, one subdirectory per query (as lib/run's run makes them).
struct Queries {
  fs::path root = fs::temp_directory_path() / ("mosb-process-test-" + std::to_string(::getpid()));
  int next = 0;
  Queries() {
    fs::remove_all(root);
    fs::create_directories(root);
  }
  ~Queries() { fs::remove_all(root); }
  Queries(const Queries&) = delete;
  Queries& operator=(const Queries&) = delete;

  ProcessSpec spec(const std::vector<std::string>& argv, Seal seal = Seal::none) {
    const fs::path dir = root / ("q" + std::to_string(next++));
    fs::create_directories(dir);
    ProcessSpec s;
    s.executable = argv.front();
    s.argv = argv;
    s.stdout_path = (dir / "stdout").string();
    s.stderr_path = (dir / "stderr").string();
    s.watched_files = {s.stdout_path, s.stderr_path};
    s.group_name = "mosb-process-test-" + std::to_string(::getpid());
    s.isolation = detect_isolation();
    s.seal = seal;
    s.queries_directory = root.string();
    return s;
  }
};

ProcessLimits limits(double wall_seconds) {
  ProcessLimits l;
  l.wall_seconds = wall_seconds;
  l.grace_seconds = 0.1;
  return l;
}

}  // namespace

TEST_CASE("process runner: a program's output, exit status and times, query after query") {
  prepare_process_runner();
  std::atomic<bool> stop{false};
  ProcessRunner runner(stop);
  Queries queries;
  const Measurement m = detect_measurement();
  for (int i = 0; i < 20; ++i) {
    const auto spec = queries.spec(
        {"/bin/sh", "-c",
         "echo out " + std::to_string(i) + "; echo err >&2; exit " + std::to_string(i % 3)});
    const ProcessOutcome out = runner.run(spec, limits(10), m);
    CHECK(out.ending == Ending::exited);
    CHECK(out.exit_code == i % 3);
    CHECK(contents(spec.stdout_path) == "out " + std::to_string(i) + "\n");
    CHECK(contents(spec.stderr_path) == "err\n");
    CHECK(out.wall_seconds > 0);
    CHECK(out.wall_seconds < 10);
  }
}

TEST_CASE("process runner: the wall time covers the program, from the launcher's clock") {
  prepare_process_runner();
  std::atomic<bool> stop{false};
  ProcessRunner runner(stop);
  Queries queries;
  const auto before = std::chrono::steady_clock::now();
  const ProcessOutcome out =
      runner.run(queries.spec({"/bin/sleep", "0.3"}), limits(10), detect_measurement());
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
  CHECK(out.ending == Ending::exited);
  CHECK(out.wall_seconds >= 0.3);
  CHECK(out.wall_seconds <= elapsed);
}

TEST_CASE("process runner: a program holds its standard streams and no other descriptor") {
  // The fork server's socket, the command sockets and error pipes of the queries forked ahead and
  // the memory groups' files are all closed before a program executes, sealed or not. `ls` holds
  // 3 itself, the listing.
  prepare_process_runner();
  std::atomic<bool> stop{false};
  ProcessRunner runner(stop);
  Queries queries;
  std::vector<Seal> seals{Seal::none};
  if (seal_refusal().empty()) seals.push_back(Seal::sealed);
  for (const Seal seal : seals)
    for (int i = 0; i < 3; ++i) {
      const auto spec = queries.spec({"/bin/ls", "/proc/self/fd"}, seal);
      const ProcessOutcome out = runner.run(spec, limits(10), detect_measurement());
      CHECK(out.ending == Ending::exited);
      CHECK(contents(spec.stdout_path) == "0\n1\n2\n3\n");
    }
}

TEST_CASE("process runner: a program that cannot run, and one past its time limit") {
  prepare_process_runner();
  std::atomic<bool> stop{false};
  ProcessRunner runner(stop);
  Queries queries;
  const Measurement m = detect_measurement();
  const ProcessOutcome missing = runner.run(queries.spec({"/nonexistent/solver"}), limits(10), m);
  CHECK(missing.ending == Ending::not_started);
  CHECK(missing.error.find("/nonexistent/solver: cannot run") != std::string::npos);
  const ProcessOutcome slow = runner.run(queries.spec({"/bin/sleep", "30"}), limits(0.2), m);
  CHECK(slow.ending == Ending::timeout);
  CHECK(slow.wall_seconds < 5);
  // The runner goes on after both.
  const auto spec = queries.spec({"/bin/echo", "after"});
  CHECK(runner.run(spec, limits(10), m).ending == Ending::exited);
  CHECK(contents(spec.stdout_path) == "after\n");
}
