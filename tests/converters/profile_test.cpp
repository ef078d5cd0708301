// Solver profiles (converters/profiles, spec/RUN.md §10): every shipped profile parses; a
// malformed one is one line naming the file, line, column and key.
#include "mosb/converters/profile.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "mosb/error.hpp"

using namespace mosb;
using namespace mosb::converters;

namespace {

const char* kMinimal = R"(name = "x"
command = "{executable} {instance} {source} {target}"
)";

// The message of the error parsing `text` throws ("" when it parses).
std::string error_of(const std::string& text) {
  try {
    parse_profile(text, "p.toml");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find('\n') == std::string::npos);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("every shipped profile parses, with its declared input and output") {
  // Shipped: every file of profiles/, by its name.
  std::vector<std::string> files, shipped_names;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(MOSB_SOURCE_DIR) / "profiles"))
    if (entry.path().extension() == ".toml") files.push_back(entry.path().stem().string());
  for (const auto& shipped : shipped_profiles()) shipped_names.emplace_back(shipped.name);
  std::sort(files.begin(), files.end());
  std::sort(shipped_names.begin(), shipped_names.end());
  CHECK(shipped_names == files);
  REQUIRE(!files.empty());
  for (const auto& shipped : shipped_profiles()) {
    const auto p = load_profile(std::string(shipped.name));
    CHECK(p.name == shipped.name);
    CHECK(!p.description.empty());
  }
  const auto emoa = load_profile("emoa");
  CHECK(emoa.success_exit_codes == std::vector<int>{1});
  CHECK(emoa.input.parallel_arcs == ParallelArcs::collapse);
  CHECK(emoa.output.format == "vectors");
  CHECK(emoa.output.group == 1);
  CHECK(emoa.output.trailing_separator);
  REQUIRE(emoa.output.status_lines.size() == 1);
  CHECK(emoa.output.status_lines[0].status == QueryStatus::timeout);
  const auto apex = load_profile("apex");
  CHECK(apex.input.append_dummy_arc);
  CHECK(apex.input.integer_costs);
  CHECK(apex.time_limit.integer);
  REQUIRE(apex.options.size() == 2);
  CHECK(apex.options[0].max_objectives.at("BOA") == 2);
  const auto tmda = load_profile("tmda");
  CHECK(tmda.input.form == InputForm::dimacs_multi_column);
  CHECK(tmda.input.pad_columns == 3);
  REQUIRE(tmda.output.runtime);
  CHECK(tmda.output.runtime->field == 8);
  const auto mohs = load_profile("mohs");
  REQUIRE(mohs.output.finished.size() == 1);
  CHECK(mohs.output.finished[0].when_option == "algorithm");
  CHECK(mohs.output.unfinished == QueryStatus::timeout);
}

TEST_CASE("a minimal profile takes the defaults") {
  const auto p = parse_profile(kMinimal, "p.toml");
  CHECK(p.input.form == InputForm::mosb);
  CHECK(p.input.id_base == 0);
  CHECK(p.output.format == "protocol");
  CHECK(p.output.runtime_clock == RuntimeClock::wall);
  CHECK(p.success_exit_codes == std::vector<int>{0});
  // The digest of the text, which a finished experiment cell is bound to: another text, another.
  CHECK(p.text_digest.size() == 16);
  CHECK(parse_profile(std::string(kMinimal) + "# changed\n", "p.toml").text_digest !=
        p.text_digest);
  CHECK(parse_profile(std::string(kMinimal) + "[output]\nruntime_clock = \"cpu\"\n", "p.toml")
            .output.runtime_clock == RuntimeClock::cpu);
  CHECK_THROWS(
      parse_profile(std::string(kMinimal) + "[output]\nruntime_clock = \"sun\"\n", "p.toml"));
}

TEST_CASE("a malformed profile is one line with file, line, column and key") {
  // TOML syntax
  CHECK(error_of("name = \"x\nfoo").rfind("p.toml:1:", 0) == 0);
  // an unknown key, where it is
  CHECK(error_of(std::string(kMinimal) + "\n[input]\nform = \"dimacs\"\nid_bsae = 1\n") ==
        "p.toml:6:1: key 'input.id_bsae': unknown key");
  // a wrong type
  CHECK(error_of(std::string(kMinimal) + "[input]\nid_base = \"1\"\n") ==
        "p.toml:4:11: key 'input.id_base': expected an integer");
  // out of range
  CHECK(error_of(std::string(kMinimal) + "[input]\nid_base = 2\n") ==
        "p.toml:4:11: key 'input.id_base': 2 is not in [0, 1]");
  // a choice
  CHECK(error_of(std::string(kMinimal) + "[input]\nparallel_arcs = \"merge\"\n") ==
        "p.toml:4:17: key 'input.parallel_arcs': 'merge' is not one of keep, collapse");
  // missing keys
  CHECK(error_of("name = \"x\"\n") == "p.toml:1:1: key 'command': is missing");
  // an unknown placeholder, and one that needs another input form
  CHECK(error_of("name = \"x\"\ncommand = \"{executable} {sourc}\"\n") ==
        "p.toml:2:11: key 'command': unknown placeholder {sourc}");
  CHECK(error_of("name = \"x\"\ncommand = \"{executable} {gr}\"\n") ==
        "p.toml:2:11: key 'command': {gr} needs input.form = \"dimacs\"");
  CHECK(error_of("name = \"x\"\ncommand = \"{executable} -m{gr}\"\n[input]\nform = "
                 "\"dimacs\"\n")
            .find("{gr} is a word of its own") != std::string::npos);
  // a format of the registry (mosb run --output-format) or vectors
  CHECK(error_of(std::string(kMinimal) + "[output]\nformat = \"xml\"\n") ==
        "p.toml:4:10: key 'output.format': expected protocol, example-log, json-log, or vectors");
  // output keys of the vectors format only with it
  CHECK(error_of(std::string(kMinimal) + "[output]\nformat = \"json-log\"\ngroup = 2\n") ==
        "p.toml:5:9: key 'output.group': only with format = \"vectors\"");
  // a status line that says the solver finished
  CHECK(error_of(std::string(kMinimal) +
                 "[output]\nformat = \"vectors\"\nstatus = [{ line = \"ok\", status = \"solved\" "
                 "}]\n")
            .find("key 'output.status.status': a status line states") != std::string::npos);
  // an option's default outside its values
  CHECK(error_of("name = \"x\"\ncommand = \"{executable} {a}\"\n[options.a]\ndefault = "
                 "\"q\"\nvalues = [\"p\"]\n") ==
        "p.toml:4:11: key 'options.a.default': not one of the values");
}

TEST_CASE("a shipped name and a file are told apart") {
  CHECK_THROWS_WITH_AS(load_profile("nosuch"), doctest::Contains("no shipped profile of that name"),
                       Error);
  CHECK_THROWS_WITH_AS(load_profile("/nonexistent/p.toml"),
                       doctest::Contains("/nonexistent/p.toml: cannot read"), Error);
  // A device is never read to its end (nor a FIFO waited for): not a regular file.
  CHECK_THROWS_WITH_AS(load_profile("/dev/null"), "/dev/null: not a regular file", Error);
}
