#include "journal.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/run.hpp"

TEST_CASE(
    "journaled_queries counts query records: not the binding, an executable's line or a tear") {
  const auto dir = std::filesystem::temp_directory_path() / "mosb-journaled-queries";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto journal = (dir / "out.sol.journal").string();
  CHECK(mosb::journaled_queries(journal) == 0);  // absent
  {
    std::ofstream out(journal, std::ios::binary);
    out << R"({"check":"0","executable_sha256":"aa","version":2})" << '\n'
        << R"({"check":"1","query":0,"status":"solved"})" << '\n'
        << R"({"check":"2","executable_sha256":"bb"})" << '\n'
        << R"({"check":"3","query":1,"status":"timeout"})" << '\n'
        << R"({"check":"4","query":2,"sta)";  // torn by a kill
  }
  CHECK(mosb::journaled_queries(journal) == 2);
  {
    std::ofstream out(journal, std::ios::binary);
    out << R"({"check":"0","executable_sha256":"aa","version":2})" << '\n';
  }
  CHECK(mosb::journaled_queries(journal) == 0);
  std::filesystem::remove_all(dir);
}

namespace {

using mosb::run_internal::Journal;
using mosb::run_internal::JournalBinding;

mosb::QueryRecord solved(std::uint64_t query, std::vector<double> costs) {
  mosb::QueryRecord r;
  r.query = query;
  r.status = mosb::QueryStatus::solved;
  r.costs = std::move(costs);
  r.wall_seconds = 0.25;
  return r;
}

JournalBinding binding(std::string executable = "aa") {
  return {{{"solver", "boa {instance}"}, {"view", "Grid_2"}}, std::move(executable), false};
}

const mosb::run_internal::RecordCheck kAnyRecord = [](const mosb::QueryRecord&) {
  return std::optional<std::string>{};
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const mosb::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a journal gives back its records on resume and refuses what it was not") {
  const auto dir = std::filesystem::temp_directory_path() / "mosb-journal-test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto path = (dir / "out.sol.journal").string();
  {
    Journal journal(path, binding(), false, kAnyRecord);
    journal.append(solved(0, {1, 2, 3, 4}));
    journal.append(solved(2, {5, 6}));
  }
  {
    std::ofstream torn(path, std::ios::app | std::ios::binary);
    torn << R"({"check":"1","query":1,"sta)";  // a kill in the middle of a write
  }
  {
    Journal journal(path, binding(), true, kAnyRecord);
    REQUIRE(journal.records().size() == 2);
    CHECK(journal.records().at(0).costs == std::vector<double>{1, 2, 3, 4});
    CHECK(journal.records().at(2).status == mosb::QueryStatus::solved);
    CHECK(journal.executables() == std::vector<std::string>{"aa"});
  }
  // Without resume, an existing journal is refused; so are other settings, another executable
  // (unless allowed) and a record the run cannot take.
  CHECK(message_of([&] { Journal(path, binding(), false, kAnyRecord); }).find(path) !=
        std::string::npos);
  auto other = binding();
  other.settings["view"] = "Grid_3";
  CHECK(message_of([&] { Journal(path, other, true, kAnyRecord); }).find("view") !=
        std::string::npos);
  CHECK(message_of([&] {
          Journal(path, binding("bb"), true, kAnyRecord);
        }).find("the solver's executable changed") != std::string::npos);
  const mosb::run_internal::RecordCheck no_query_2 = [](const mosb::QueryRecord& r) {
    return r.query == 2 ? std::optional<std::string>("not in this run") : std::nullopt;
  };
  CHECK(message_of([&] {
          Journal(path, binding(), true, no_query_2);
        }).find("query 2: not in this run") != std::string::npos);
  {
    auto allowed = binding("bb");
    allowed.allow_new_executable = true;
    Journal journal(path, allowed, true, kAnyRecord);
    CHECK(journal.executables() == std::vector<std::string>{"aa", "bb"});
  }
  // The new executable's line is no query.
  CHECK(mosb::journaled_queries(path) == 2);
  // A hand edit is caught by the line's checksum, named by its line.
  {
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find("[5.0,6.0]");
    REQUIRE(at != std::string::npos);
    text.replace(at, 9, "[5.0,7.0]");
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  }
  CHECK(message_of([&] {
          Journal(path, binding("bb"), true, kAnyRecord);
        }).find(":3: its checksum does not match") != std::string::npos);
  std::filesystem::remove_all(dir);
}
