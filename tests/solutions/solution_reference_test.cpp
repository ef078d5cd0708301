// lib/solutions' reference fronts (spec/EVALUATION.md §6.1): cross_validate's kinds and statuses,
// its refusals, write_reference's file, reference_groups and query_ranges.
#include "mosb/solution_reference.hpp"

#include <doctest/doctest.h>

#include <deque>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "golden_input.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/solution_summary.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

struct Outcome {
  QueryStatus status;
  std::vector<double> costs;  // (c1 u32, c2 f32) pairs
};

constexpr auto kSolved = QueryStatus::solved;
constexpr auto kTimeout = QueryStatus::timeout;
constexpr auto kMemory = QueryStatus::memory_limit;
constexpr auto kNotRun = QueryStatus::not_run;
constexpr auto kFailed = QueryStatus::failed;
constexpr auto kDisconnected = QueryStatus::disconnected;

const std::vector<double> kFront0 = {10, 40, 20, 20, 40, 10};

// The golden instance (view Small_2: 3 queries) and solution files of it, one per solver.
class Files {
 public:
  Files() {
    write_graph(testing::golden_input(), dir_ / "g.mosb");
    instance_.emplace(GraphReader::open(dir_ / "g.mosb", VerifyLevel::full));
  }
  const SolutionReader& add(const std::string& solver, const std::vector<Outcome>& queries,
                            const std::string& file_name = "") {
    SolutionWriter w(*instance_, "Small_2");
    w.set_solver({solver, "1", {}, "0", ""});
    for (std::size_t q = 0; q < queries.size(); ++q)
      w.set_query(q, queries[q].status, queries[q].costs);
    const auto path = dir_ / (file_name.empty() ? solver + ".sol" : file_name);
    w.write(path);
    readers_.push_back(SolutionReader::open_verified(path));
    return readers_.back();
  }
  std::vector<const SolutionReader*> all() const {
    std::vector<const SolutionReader*> out;
    for (const auto& r : readers_) out.push_back(&r);
    return out;
  }
  const testing::TempDir& dir() const { return dir_; }

 private:
  testing::TempDir dir_;
  std::optional<GraphReader> instance_;
  std::deque<SolutionReader> readers_;
};

CrossValidation validate(const Files& files, std::vector<std::string> solvers,
                         std::optional<std::string> prefer = std::nullopt,
                         double tolerance = kDefaultTolerance) {
  ReferenceOptions options;
  options.solvers = std::move(solvers);
  options.prefer = std::move(prefer);
  options.tolerance = tolerance;
  return cross_validate(files.all(), options);
}

}  // namespace

TEST_CASE("cross_validate: agreed, single and unsolved queries, with who agreed") {
  Files files;
  files.add("a", {{kSolved, kFront0}, {kSolved, {30, 30}}, {kTimeout, {}}});
  files.add("b", {{kSolved, kFront0}, {kTimeout, {}}, {kTimeout, {}}});
  const auto v = validate(files, {"a", "b"});
  CHECK(v.solvers == std::vector<std::string>{"a", "b"});
  REQUIRE(v.queries.size() == 3);
  CHECK(v.queries[0].kind == ReferenceKind::agreed);
  CHECK(v.queries[0].status == kSolved);
  CHECK(v.queries[0].source == "a");
  CHECK(v.queries[0].agreed == std::vector<std::string>{"a", "b"});
  CHECK(v.queries[0].differing.empty());
  CHECK(v.queries[1].kind == ReferenceKind::single);
  CHECK(v.queries[1].source == "a");
  CHECK(v.queries[1].agreed == std::vector<std::string>{"a"});
  CHECK(v.queries[2].kind == ReferenceKind::unsolved);
  CHECK(v.queries[2].status == kTimeout);
  CHECK(v.queries[2].source.empty());
  CHECK(v.count(ReferenceKind::agreed) == 1);
  CHECK(v.count(ReferenceKind::single) == 1);
  CHECK(v.count(ReferenceKind::unsolved) == 1);
  CHECK(v.count(ReferenceKind::disagreement) == 0);
}

TEST_CASE("cross_validate: a disagreement names both solvers and the first differing vector") {
  Files files;
  files.add("a", {{kSolved, kFront0}, {kSolved, {30, 30}}, {kDisconnected, {}}});
  files.add("b", {{kSolved, kFront0}, {kSolved, {33, 30}}, {kSolved, {5, 5}}});
  files.add("c", {{kSolved, kFront0}, {kSolved, {30, 30}}, {kDisconnected, {}}});
  const auto v = validate(files, {"a", "b", "c"});
  CHECK(v.queries[0].kind == ReferenceKind::agreed);
  CHECK(v.queries[0].agreed == std::vector<std::string>{"a", "b", "c"});
  const auto& q1 = v.queries[1];
  CHECK(q1.kind == ReferenceKind::disagreement);
  CHECK(q1.status == kNotRun);  // left out of the reference
  CHECK(q1.source.empty());
  CHECK(q1.agreed.empty());
  CHECK(q1.first == "a");
  CHECK(q1.differing == "b");
  CHECK(q1.first_difference == std::vector<double>{30, 30});  // the smaller, in a's front
  CHECK(q1.difference_in_first);
  // Disconnected against solved: a disagreement with no differing vector.
  const auto& q2 = v.queries[2];
  CHECK(q2.kind == ReferenceKind::disagreement);
  CHECK(q2.differing == "b");
  CHECK(q2.first_difference.empty());
  CHECK(v.count(ReferenceKind::disagreement) == 2);
}

TEST_CASE("cross_validate: --prefer keeps the preferred solver's front where they disagree") {
  Files files;
  files.add("a", {{kSolved, kFront0}, {kSolved, {30, 30}}, {kTimeout, {}}});
  files.add("b", {{kSolved, kFront0}, {kSolved, {33, 30}}, {kTimeout, {}}});
  const auto v = validate(files, {"a", "b"}, "b");
  CHECK(v.queries[0].kind == ReferenceKind::agreed);  // agreement is not preference
  CHECK(v.queries[0].source == "a");
  CHECK(v.queries[1].kind == ReferenceKind::preferred);
  CHECK(v.queries[1].source == "b");
  CHECK(v.queries[1].agreed == std::vector<std::string>{"b"});
  CHECK(v.queries[1].status == kSolved);
  CHECK(v.queries[1].first == "a");
  CHECK(v.queries[1].differing == "b");
  // A preferred solver that did not complete the query settles nothing.
  Files other;
  other.add("a", {{kSolved, {30, 30}}, {kSolved, {30, 30}}, {kSolved, {30, 30}}});
  other.add("b", {{kSolved, {33, 30}}, {kSolved, {33, 30}}, {kSolved, {33, 30}}});
  other.add("c", {{kSolved, {34, 30}}, {kTimeout, {}}, {kSolved, {30, 30}}});
  const auto w = validate(other, {"a", "b", "c"}, "c");
  CHECK(w.queries[0].kind == ReferenceKind::preferred);
  CHECK(w.queries[0].source == "c");
  CHECK(w.queries[1].kind == ReferenceKind::disagreement);
  CHECK(w.queries[2].kind == ReferenceKind::preferred);
}

TEST_CASE("cross_validate: float objectives compared within the tolerance") {
  Files files;
  // c2 is f32: 30.000002 is stored as 30.0000019..., a relative difference of about 6e-8.
  files.add("a", {{kSolved, {30, 30}}, {kSolved, {30, 30}}, {kSolved, {30, 30}}});
  files.add("b", {{kSolved, {30, 30.000002}}, {kSolved, {30, 30}}, {kSolved, {31, 30}}});
  const auto strict = validate(files, {"a", "b"});
  CHECK(strict.queries[0].kind == ReferenceKind::disagreement);
  const auto tolerant = validate(files, {"a", "b"}, std::nullopt, 1e-6);
  CHECK(tolerant.queries[0].kind == ReferenceKind::agreed);
  CHECK(tolerant.queries[1].kind == ReferenceKind::agreed);
  CHECK(tolerant.queries[2].kind == ReferenceKind::disagreement);  // 31 vs 30 is beyond 1e-6
}

TEST_CASE("cross_validate: the status of a query no solver completed") {
  Files files;
  // q0: timeout and memory limit; q1: memory limits only; q2: a failure among timeouts.
  files.add("a", {{kTimeout, {}}, {kMemory, {}}, {kTimeout, {}}});
  files.add("b", {{kMemory, {}}, {kMemory, {}}, {kFailed, {}}});
  const auto v = validate(files, {"a", "b"});
  CHECK(v.queries[0].status == kTimeout);
  CHECK(v.queries[1].status == kMemory);
  CHECK(v.queries[2].status == kNotRun);
  for (const auto& q : v.queries) CHECK(q.kind == ReferenceKind::unsolved);
  // A solver that did not run a query (or has no file) does not hide the others' timeouts.
  Files partial;
  partial.add("a", {{kTimeout, {}}, {kNotRun, {}}, {kMemory, {}}});
  partial.add("b", {{kNotRun, {}}, {kNotRun, {}}, {kNotRun, {}}});
  const auto p = validate(partial, {"a", "b", "c"});  // c: no file
  CHECK(p.queries[0].status == kTimeout);
  CHECK(p.queries[1].status == kNotRun);
  CHECK(p.queries[2].status == kMemory);
}

TEST_CASE("cross_validate: refusals") {
  Files files;
  files.add("a", {{kSolved, {30, 30}}, {kSolved, {30, 30}}, {kSolved, {30, 30}}});
  files.add("b", {{kSolved, {30, 30}}, {kSolved, {30, 30}}, {kSolved, {30, 30}}});
  const auto message = [&](std::vector<std::string> solvers, std::optional<std::string> prefer,
                           std::vector<const SolutionReader*> given) -> std::string {
    ReferenceOptions options;
    options.solvers = std::move(solvers);
    options.prefer = std::move(prefer);
    try {
      (void)cross_validate(given, options);
    } catch (const Error& e) {
      CHECK(e.code() == ErrorCode::invalid_argument);
      return e.what();
    }
    return "";
  };
  const auto all = files.all();
  CHECK(message({}, {}, all) == "no solver named for the reference");
  CHECK(message({"a", "a"}, {}, all) == "solver 'a' is named twice");
  CHECK(message({"a,b"}, {}, all) == "solver name 'a,b' is empty or has a ','");
  CHECK(message({"a", ""}, {}, all) == "solver name '' is empty or has a ','");
  CHECK(message({"a", "b"}, "c", all) == "prefer 'c' is not one of the reference's solvers");
  CHECK(message({"a", "b"}, {}, {}) == "no solution file for the reference");
  CHECK(
      message({"a"}, {}, all).ends_with("b.sol: solver 'b' is not one of the reference's solvers"));
  CHECK(message({"a", "b"}, {}, {all[0], all[0]}).find("a second file of solver 'a'") !=
        std::string::npos);
  ReferenceOptions bad_tolerance;
  bad_tolerance.solvers = {"a", "b"};
  bad_tolerance.tolerance = 1.0;
  CHECK_THROWS_AS((void)cross_validate(all, bad_tolerance), Error);
}

TEST_CASE("write_reference: the agreed fronts, the statuses and who agreed in the metadata") {
  Files files;
  files.add("a", {{kSolved, kFront0}, {kSolved, {30, 30}}, {kTimeout, {}}});
  files.add("b", {{kSolved, kFront0}, {kSolved, {33, 30}}, {kTimeout, {}}});
  ReferenceOptions options;
  options.solvers = {"a", "b"};
  const auto all = files.all();
  const auto v = cross_validate(all, options);
  write_reference(all, v, options, files.dir() / "ref.sol");
  const auto ref = SolutionReader::open_verified(files.dir() / "ref.sol");
  CHECK(solver_name(ref) == "reference");
  CHECK(ref.status(0) == kSolved);
  CHECK(ref.front_size(0) == 3);
  CHECK(ref.value_as_double(0, ref.front_begin(0)) == 10);
  CHECK(ref.status(1) == kNotRun);  // the disagreement is left out
  CHECK(ref.front_size(1) == 0);
  CHECK(ref.status(2) == kTimeout);
  const auto parameters = ref.solver().parameters;
  CHECK(parameters.at("solvers") == "a,b");
  CHECK(parameters.at("agreed") == "0");
  CHECK(parameters.at("disagreement") == "1");
  CHECK(parameters.at("single").empty());
  CHECK(parameters.at("agreed.0") == "0");
  CHECK(parameters.at("agreed.1") == "0");
  CHECK(parameters.count("prefer") == 0);
}

TEST_CASE("reference_groups: one group per binding, the other solvers' files left out") {
  Files files;
  std::filesystem::create_directories(files.dir() / "x");
  std::filesystem::create_directories(files.dir() / "y");
  files.add("a", {{kSolved, {30, 30}}, {kSolved, {30, 30}}, {kSolved, {30, 30}}}, "x/a.sol");
  files.add("b", {{kSolved, {30, 30}}, {kSolved, {30, 30}}, {kSolved, {30, 30}}}, "y/a.sol");
  files.add("z", {{kSolved, {30, 30}}, {kSolved, {30, 30}}, {kSolved, {30, 30}}}, "z.sol");
  std::vector<SolutionReader> readers;
  for (const auto* r : files.all())
    readers.push_back(SolutionReader::open_verified(r->display_name()));
  ReferenceOptions options;
  options.solvers = {"a", "b"};
  const auto groups = reference_groups(readers, options);
  REQUIRE(groups.size() == 1);
  CHECK(groups[0].files == std::vector<std::size_t>{0, 1});
  CHECK(groups[0].name == "a.sol");
  // A named solver without a file (a typo) is refused, naming the solvers there are.
  options.solvers = {"a", "q"};
  CHECK_THROWS_WITH_AS((void)reference_groups(readers, options),
                       "solver 'q' has no file among the inputs (their solvers: a, b, z)", Error);
}

TEST_CASE("query_ranges: ascending numbers as ranges") {
  CHECK(query_ranges(std::vector<std::uint64_t>{}).empty());
  CHECK(query_ranges(std::vector<std::uint64_t>{7}) == "7");
  CHECK(query_ranges(std::vector<std::uint64_t>{0, 1, 2, 3, 4, 7, 9, 10, 11, 12}) == "0-4,7,9-12");
  CHECK(query_ranges(std::vector<std::uint64_t>{1, 3, 5}) == "1,3,5");
}
