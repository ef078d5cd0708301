// converters/experiment: the experiment file (spec/EXPERIMENT.md §1) read into lib/experiment's
// Experiment, and each refusal as one line "FILE:LINE: KEY: problem".
#include "mosb/converters/experiment_file.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "mosb/error.hpp"
#include "temp_dir.hpp"

using namespace mosb;
using mosb::converters::parse_experiment;

namespace {

constexpr const char* kSolver = "[[solver]]\nname = \"a\"\ntemplate = \"a {instance}\"\n";

// The one error line parse_experiment throws for `text`, or "" when it reads.
std::string error_of(const std::string& text) {
  try {
    (void)parse_experiment(text, "exp.toml");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::invalid_argument);
    std::string message = e.what();
    CHECK(message.find('\n') == std::string::npos);
    return message;
  }
  return "";
}

}  // namespace

TEST_CASE("parse_experiment: every key of the specification read into the Experiment") {
  const auto e = parse_experiment(R"(name = "table5"
store = "store/"
benchmarks = ["Grid_2", "NetMaker*"]
limits = { time = "1h", memory = "16G", cpu = "90s", grace = "500ms", output = "512M" }

[[solver]]
name = "namoa"
template = "namoa {instance} --view {view}"
output_format = "protocol"
epsilon = "0.01"
benchmarks = ["*_2"]

[[solver]]
name = "apex"
profile = "apex"
executable = "/opt/A-pex/bin/multiobj"
options = { algorithm = "Apex", depth = 3, ratio = 0.5, merge = true }

[reference]
solvers = ["namoa", "apex"]
)",
                                  "exp.toml");
  CHECK(e.file == "exp.toml");
  CHECK(e.name == "table5");
  CHECK(e.store == "store/");
  CHECK(e.instances.empty());
  CHECK(e.benchmarks == std::vector<std::string>{"Grid_2", "NetMaker*"});
  REQUIRE(e.benchmark_sources.size() == 2);
  CHECK(e.benchmark_sources[1].line == 3);
  CHECK(e.benchmark_sources[1].key == "benchmarks");
  CHECK(e.store_source.line == 2);
  CHECK(e.limits.process.wall_seconds == 3600);
  CHECK(e.limits.process.memory_bytes == 16ULL << 30);
  CHECK(e.limits.process.cpu_seconds == 90);
  CHECK(e.limits.process.grace_seconds == doctest::Approx(0.5));
  CHECK(e.limits.process.output_bytes == 512ULL << 20);
  // Canonical: the same limits spelt otherwise compare equal on a rerun.
  CHECK(e.limits.text == "time=3600s memory=17179869184B cpu=90s grace=0.5s output=536870912B");
  REQUIRE(e.solvers.size() == 2);
  CHECK(e.solvers[0].name == "namoa");
  CHECK(e.solvers[0].spec.solver_template == "namoa {instance} --view {view}");
  CHECK(e.solvers[0].spec.profile.empty());
  CHECK(e.solvers[0].spec.output_format == "protocol");
  CHECK(e.solvers[0].spec.epsilon == "0.01");
  CHECK(e.solvers[0].spec.name == "namoa");  // recorded as the experiment names it
  CHECK(e.solvers[0].benchmarks == std::vector<std::string>{"*_2"});
  CHECK(e.solvers[0].source.line == 6);
  CHECK(e.solvers[0].source.key == "solver[1]");
  CHECK(e.solvers[1].spec.profile == "apex");
  CHECK(e.solvers[1].spec.executable == "/opt/A-pex/bin/multiobj");
  // Options in key order, as KEY=VALUE: numbers as written, booleans as words.
  CHECK(e.solvers[1].spec.options ==
        std::vector<std::string>{"algorithm=Apex", "depth=3", "merge=true", "ratio=0.5"});
  CHECK(e.solvers[1].spec.epsilon == "0");
  CHECK(e.reference_solvers == std::vector<std::string>{"namoa", "apex"});
  CHECK(e.reference_source.line == 20);
}

TEST_CASE("parse_experiment: numbers where the specification says numbers, and ε sweeps") {
  const auto e = parse_experiment(R"(name = "x"
store = "s"
limits = { time = 60, memory = 1073741824, grace = 0.5, output = "1m" }
[[solver]]
name = "namoa"
template = "namoa {instance}"
epsilon = 0
[[solver]]
name = "apex"
profile = "apex"
executable = "/bin/apex"
epsilon = [0.01, "0.05", 0.1]
)",
                                  "exp.toml");
  CHECK(e.limits.process.wall_seconds == 60);
  CHECK(e.limits.process.memory_bytes == 1ULL << 30);
  CHECK(e.limits.process.grace_seconds == 0.5);
  CHECK(e.limits.process.output_bytes == 1ULL << 20);  // the command line's grammar: 1m is 1 MiB
  CHECK(e.limits.text == "time=60s memory=1073741824B grace=0.5s output=1048576B");
  REQUIRE(e.solvers.size() == 4);
  CHECK(e.solvers[0].spec.epsilon == "0");
  const std::vector<std::string> names{e.solvers[1].name, e.solvers[2].name, e.solvers[3].name};
  CHECK(names == std::vector<std::string>{"apex-eps0.01", "apex-eps0.05", "apex-eps0.1"});
  CHECK(e.solvers[2].spec.epsilon == "0.05");
  CHECK(e.solvers[3].spec.name == "apex-eps0.1");
  CHECK(e.solvers[3].spec.profile == "apex");
}

TEST_CASE("parse_experiment: limits keep their full precision") {
  const auto a = parse_experiment(
      "name = \"x\"\nstore = \"s\"\nlimits = { time = 1000000.4 }\n" + std::string(kSolver),
      "exp.toml");
  const auto b = parse_experiment(
      "name = \"x\"\nstore = \"s\"\nlimits = { time = 1000000 }\n" + std::string(kSolver),
      "exp.toml");
  CHECK(a.limits.text != b.limits.text);
}

TEST_CASE("parse_experiment: instances instead of a store, no limits, no reference") {
  const auto e = parse_experiment(
      std::string("name = \"x\"\ninstances = [\"a.mosb\", \"b.mosb\"]\n") + kSolver, "exp.toml");
  CHECK(e.store.empty());
  CHECK(e.instances == std::vector<std::filesystem::path>{"a.mosb", "b.mosb"});
  CHECK(e.benchmarks.empty());
  CHECK(e.limits.text.empty());
  CHECK(e.limits.process.memory_bytes == ProcessLimits{}.memory_bytes);
  CHECK(e.reference_solvers.empty());
}

TEST_CASE("parse_experiment: each refusal names the file, the line and the key") {
  const std::string head = "name = \"x\"\nstore = \"s\"\n";  // lines 1-2
  // TOML syntax: FILE:LINE:COLUMN.
  CHECK(error_of("name = \"x\"\nstore = = 1\n").starts_with("exp.toml:2:9: "));
  CHECK(error_of("name = \"x\"\nname = \"y\"\n").starts_with("exp.toml:2:"));
  // toml++ describes this one over two lines (found by mosb_fuzz_experiment): one line still.
  CHECK(error_of("name = \"x\"\nlimits = { time = \"1h\", merge = tr\nb = 1 }\n")
            .starts_with("exp.toml:2:"));
  // The root table's keys.
  CHECK(error_of(head + "colour = 1\n" + kSolver) == "exp.toml:3:1: key 'colour': unknown key");
  CHECK(error_of("store = \"s\"\n" + std::string(kSolver)) ==
        "exp.toml:1:1: key 'name': is missing (a non-empty string)");
  CHECK(error_of("name = \"\"\nstore = \"s\"\n" + std::string(kSolver)) ==
        "exp.toml:1:8: key 'name': is empty");
  CHECK(error_of("name = 5\nstore = \"s\"\n" + std::string(kSolver)) ==
        "exp.toml:1:8: key 'name': expected a string");
  CHECK(error_of("name = \"x\"\nstore = [\"s\"]\n" + std::string(kSolver)) ==
        "exp.toml:2:9: key 'store': expected a string");
  CHECK(error_of(head + "instances = \"a.mosb\"\n" + kSolver) ==
        "exp.toml:3:13: key 'instances': expected an array of strings");
  CHECK(error_of(head + "benchmarks = [\"a\", 2]\n" + kSolver) ==
        "exp.toml:3:20: key 'benchmarks': expected an array of strings");
  CHECK(error_of(head + "instances = [\"a.mosb\"]\n" + kSolver)
            .ends_with(": key 'instances': give exactly one of store and instances"));
  CHECK(error_of("name = \"x\"\n" + std::string(kSolver))
            .ends_with(": key 'store': give exactly one of store and instances"));
  CHECK(error_of(head).ends_with(": key 'solver': no [[solver]]"));
  CHECK(error_of(head + "solver = 3\n") ==
        "exp.toml:3:10: key 'solver': expected an array of tables ([[solver]])");
  CHECK(error_of(head + "solver = [1, 2]\n") ==
        "exp.toml:3:10: key 'solver': expected an array of tables ([[solver]])");
  // Limits.
  CHECK(error_of(head + "limits = 5\n" + kSolver) ==
        "exp.toml:3:10: key 'limits': expected a table");
  CHECK(error_of(head + "limits = { time = \"1 hour\" }\n" + kSolver) ==
        "exp.toml:3:19: key 'limits.time': '1 hour' is not a duration (60, 60s, 500ms, 2m, 1h)");
  CHECK(error_of(head + "limits = { time = true }\n" + kSolver) ==
        "exp.toml:3:19: key 'limits.time': expected a number of seconds or a duration text");
  CHECK(error_of(head + "limits = { time = -5 }\n" + kSolver) ==
        "exp.toml:3:19: key 'limits.time': '-5' is not a duration (60, 60s, 500ms, 2m, 1h)");
  CHECK(error_of(head + "limits = { memory = -1 }\n" + kSolver) ==
        "exp.toml:3:21: key 'limits.memory': '-1' is not a size (4294967296, 512M, 16G)");
  // A value with a line break, quoted in the problem, stays one line (found by
  // mosb_fuzz_experiment: memory = "512Mt\nce}").
  CHECK(error_of(head + "limits = { memory = \"512Mt\\nce}\" }\n" + kSolver) ==
        "exp.toml:3:21: key 'limits.memory': a control character in the string");
  CHECK(error_of(head + "[limits]\ncpu = \"-1s\"\n" + kSolver) ==
        "exp.toml:4:7: key 'limits.cpu': '-1s' is not a duration (60, 60s, 500ms, 2m, 1h)");
  CHECK(error_of(head + "[limits]\ngrace = \"2d\"\n" + kSolver) ==
        "exp.toml:4:9: key 'limits.grace': '2d' is not a duration (60, 60s, 500ms, 2m, 1h)");
  CHECK(error_of(head + "[limits]\nmemory = \"16Q\"\n" + kSolver) ==
        "exp.toml:4:10: key 'limits.memory': '16Q' is not a size (4294967296, 512M, 16G)");
  CHECK(error_of(head + "[limits]\noutput = \"99999999999999999999\"\n" + kSolver) ==
        "exp.toml:4:10: key 'limits.output': '99999999999999999999' is not a size (4294967296, "
        "512M, 16G)");
  CHECK(error_of(head + "[limits]\nmemroy = \"1G\"\n" + kSolver) ==
        "exp.toml:4:1: key 'limits.memroy': unknown key");
  // Solvers.
  CHECK(error_of(head + "[[solver]]\ntemplate = \"a\"\n") ==
        "exp.toml:3:1: key 'solver[1].name': is missing (a non-empty string)");
  CHECK(error_of(head + kSolver + "[[solver]]\nname = \"b\"\ntemplate = \"b\"\ncolor = 1\n") ==
        "exp.toml:9:1: key 'solver[2].color': unknown key");
  CHECK(error_of(head + "[[solver]]\nname = \"a\"\n") ==
        "exp.toml:3:1: key 'solver[1].template': give exactly one of template and profile");
  CHECK(error_of(head + "[[solver]]\nname = \"a\"\ntemplate = \"a\"\nprofile = \"p\"\n") ==
        "exp.toml:3:1: key 'solver[1].template': give exactly one of template and profile");
  CHECK(error_of(head + "[[solver]]\nname = \"a\"\ntemplate = \"a\"\nexecutable = \"/bin/a\"\n") ==
        "exp.toml:3:1: key 'solver[1].executable': executable, options and scale go with a "
        "profile, not a template");
  CHECK(error_of(head + "[[solver]]\nname = \"a\"\nprofile = \"p\"\nscale = -1\n") ==
        "exp.toml:6:9: key 'solver[1].scale': expected a positive number (float costs × scale, "
        "rounded)");
  CHECK(error_of(head + "[[solver]]\nname = \"a\"\nprofile = \"p\"\noptions = { x = [1] }\n") ==
        "exp.toml:6:17: key 'solver[1].options.x': expected a string, number or boolean");
  CHECK(error_of(head + "[[solver]]\nname = \"a\"\nprofile = \"p\"\noptions = 3\n") ==
        "exp.toml:6:11: key 'solver[1].options': expected a table");
  CHECK(error_of(head + kSolver + "output_format = \"nonesuch\"\n") ==
        "exp.toml:6:17: key 'solver[1].output_format': 'nonesuch': no such output format");
  CHECK(error_of(head + kSolver + "epsilon = true\n") ==
        "exp.toml:6:11: key 'solver[1].epsilon': expected an ε (0.05 or \"0.05\") or an array of "
        "them");
  CHECK(error_of(head + kSolver + "epsilon = -0.1\n")
            .starts_with("exp.toml:6:11: key 'solver[1].epsilon': "));
  CHECK(error_of(head + kSolver + "epsilon = []\n") ==
        "exp.toml:6:11: key 'solver[1].epsilon': an empty array: give at least one ε");
  CHECK(error_of(head + "[[solver]]\nname = \"a\"\nprofile = \"apex\"\nexecutable = \"/x\"\n"
                        "output_format = \"json-log\"\n") ==
        "exp.toml:7:17: key 'solver[1].output_format': not with a profile (the profile says it)");
  CHECK(error_of(head + kSolver + "benchmarks = \"Grid_2\"\n") ==
        "exp.toml:6:14: key 'solver[1].benchmarks': expected an array of strings");
  // The reference.
  CHECK(error_of(head + kSolver + "[reference]\nsolvers = \"a\"\n") ==
        "exp.toml:7:11: key 'reference.solvers': expected an array of strings");
  CHECK(error_of(head + kSolver + "[reference]\nsolvers = [\"a\"]\nprefer = \"a\"\n") ==
        "exp.toml:8:1: key 'reference.prefer': unknown key");
  CHECK(error_of(head + kSolver + "reference = 1\n") ==
        "exp.toml:6:1: key 'solver[1].reference': unknown key");
}

TEST_CASE("read_experiment_file: the path names the file in errors, an absent file is refused") {
  testing::TempDir dir;
  const auto path = dir / "exp.toml";
  {
    std::ofstream out(path);
    out << "name = \"x\"\nstore = \"s\"\n" << kSolver << "bogus = true\n";
  }
  try {
    (void)converters::read_experiment_file(path);
    FAIL("read an unknown key");
  } catch (const Error& e) {
    CHECK(std::string(e.what()) == path.string() + ":6:1: key 'solver[1].bogus': unknown key");
  }
  CHECK_THROWS_AS((void)converters::read_experiment_file(dir / "absent.toml"), Error);
}
