// The C++ API a solver author writes against (issue 9): the typed cost visitor and the widening
// view, views, error codes, the version, and metadata() shared by threads.
#include <doctest/doctest.h>

#include <thread>
#include <typeinfo>

#include "file_patch.hpp"
#include "golden_input.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/version.hpp"
#include "temp_dir.hpp"

using namespace mosb;
using format::ElementType;

namespace {
const std::filesystem::path kGolden =
    std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "golden" / "1.0";

// Costs of objective `name` in input order {0..6} mapped to CSR order (stable by tail).
const std::vector<double> kDistance = {10, 20, 30, 300, 40, 5, 50};

template <class F>
ErrorCode code_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  FAIL("no mosb::Error thrown");
  return ErrorCode::other;
}
}  // namespace

TEST_CASE("visit_cost hands each column to the callable in its stored type, zero-copy") {
  const auto r = GraphReader::open(kGolden / "valid" / "small.mosb");
  for (std::size_t i = 0; i < r.objective_count(); ++i) {
    const ElementType seen = r.visit_cost(i, [&](auto column) {
      using T = typename decltype(column)::value_type;
      CHECK(static_cast<const void*>(column.data()) == r.objective(i).stored.data());
      CHECK(column.size() == r.arc_count());
      return format::element_type_of<std::remove_const_t<T>>();
    });
    CHECK(seen == r.objective(i).type);
  }
  // The writer stored distance narrower than u64, so the fixed-type accessor refuses u64 ...
  CHECK(code_of([&] { (void)r.cost<std::uint64_t>("distance"); }) == ErrorCode::invalid_argument);
  // ... while the visitor reads it whatever the type.
  const double total = r.visit_cost(0, [](auto column) {
    double sum = 0;
    for (auto c : column) sum += static_cast<double>(c);
    return sum;
  });
  CHECK(total == 455);
  // A callable returning nothing works too.
  std::size_t count = 0;
  r.visit_cost(3, [&](auto column) { count = column.size(); });
  CHECK(count == 7);
}

TEST_CASE("cost_as reads any stored type by value and refuses floats as integers") {
  const auto r = GraphReader::open(kGolden / "valid" / "small.mosb");
  const auto distance = r.cost_as<double>(0);
  REQUIRE(distance.size() == kDistance.size());
  CHECK(distance.stored_type() == r.objective(0).type);
  for (std::size_t a = 0; a < kDistance.size(); ++a) CHECK(distance[a] == kDistance[a]);
  const auto big = r.cost_as<std::uint64_t>(4);
  CHECK(big[3] == (1ULL << 33));  // input arc 6 is CSR arc 3
  CHECK(r.cost_as<float>(1)[3] == 8.0f);
  CHECK_THROWS_WITH_AS((void)r.cost_as<std::uint64_t>(1),
                       doctest::Contains("do not convert to integers"), Error);
}

TEST_CASE("views resolve to objective indices and a query set") {
  const auto r = GraphReader::open(kGolden / "valid" / "small.mosb");
  CHECK(r.view_names() == std::vector<std::string>{"Small_2", "Small_5"});
  const View two = r.view("Small_2");
  CHECK(two.name == "Small_2");
  CHECK(two.objectives == std::vector<std::size_t>{0, 1});
  CHECK(two.query_set == "default");
  CHECK(r.view("Small_5").objectives == std::vector<std::size_t>{0, 1, 2, 3, 4});
  CHECK_FALSE(r.find_view("Small_3").has_value());
  CHECK_THROWS_WITH_AS(
      (void)r.view("Small_3"),
      doctest::Contains("no view 'Small_3' (views: Small_2, Small_5; did you mean 'Small_2'?)"),
      Error);
  CHECK(code_of([&] { (void)r.view("Small_3"); }) == ErrorCode::not_found);
}

TEST_CASE("a view without a query set has an empty one, and order follows the key") {
  testing::TempDir dir;
  auto g = testing::golden_input();
  g.metadata.set("view.Reordered.objectives", "big,distance");
  write_graph(g, dir / "v.mosb");
  const auto r = GraphReader::open(dir / "v.mosb");
  const View v = r.view("Reordered");
  CHECK(v.objectives == std::vector<std::size_t>{4, 0});
  CHECK(v.query_set.empty());
  CHECK(r.view_names() == std::vector<std::string>{"Reordered", "Small_2", "Small_5"});
}

TEST_CASE("a view naming a missing objective or query set is damage, found by view()") {
  testing::TempDir dir;
  auto bytes = testing::read_bytes(kGolden / "valid" / "small.mosb");
  // Same-length edits inside the metadata section (open checks no section checksum).
  auto replace = [&](std::string_view from, std::string_view to) {
    const auto* begin = reinterpret_cast<const char*>(bytes.data());
    const auto at = std::string_view(begin, bytes.size()).find(from);
    REQUIRE(at != std::string_view::npos);
    std::memcpy(bytes.data() + at, to.data(), to.size());
  };
  replace("view.Small_2.objectives=distance,time", "view.Small_2.objectives=distance,tame");
  replace("view.Small_5.queries=reverse", "view.Small_5.queries=reverso");
  testing::write_bytes(dir / "bad-view.mosb", bytes);
  const auto r = GraphReader::open(dir / "bad-view.mosb");
  CHECK_THROWS_WITH_AS((void)r.view("Small_2"),
                       doctest::Contains("view 'Small_2' names objective 'tame'"), Error);
  CHECK(code_of([&] { (void)r.view("Small_2"); }) == ErrorCode::damaged);
  CHECK_THROWS_WITH_AS((void)r.find_view("Small_5"),
                       doctest::Contains("view 'Small_5' names query set 'reverso'"), Error);
  CHECK(r.view_names() == std::vector<std::string>{"Small_2", "Small_5"});
}

TEST_CASE("errors carry a code to branch on") {
  CHECK(code_of([] { (void)GraphReader::open(kGolden / "absent.mosb"); }) == ErrorCode::io);
  CHECK(code_of([] { (void)GraphReader::open(kGolden / "invalid" / "bad-magic.mosb"); }) ==
        ErrorCode::not_mosb);
  CHECK(code_of([] { (void)GraphReader::open(kGolden / "invalid" / "newer-major.mosb"); }) ==
        ErrorCode::version);
  CHECK(code_of([] { (void)GraphReader::open(kGolden / "invalid" / "unknown-feature.mosb"); }) ==
        ErrorCode::version);
  CHECK(code_of([] { (void)GraphReader::open(kGolden / "invalid" / "overlap.mosb"); }) ==
        ErrorCode::damaged);
  const auto r = GraphReader::open(kGolden / "valid" / "small.mosb");
  CHECK(code_of([&] { (void)r.objective_index("nope"); }) == ErrorCode::not_found);
  CHECK(code_of([&] { (void)r.queries("nope"); }) == ErrorCode::not_found);
  CHECK(code_of([&] { (void)r.objective(9); }) == ErrorCode::invalid_argument);
  // The one-argument constructor stays, for the converters' text errors.
  CHECK(Error("x").code() == ErrorCode::other);
  CHECK(std::string(Error(ErrorCode::io, "y").what()) == "y");
}

TEST_CASE("metadata() may be called by many threads on a fresh reader") {
  const auto r = GraphReader::open(kGolden / "valid" / "small.mosb");
  std::vector<const Metadata*> seen(8);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < seen.size(); ++t)
    threads.emplace_back([&, t] { seen[t] = &r.metadata(); });
  for (auto& t : threads) t.join();
  for (const auto* m : seen) CHECK(m == seen[0]);  // parsed once, one object
  CHECK(seen[0]->get("benchmark") == "golden-small");
  const GraphReader copy = r;
  CHECK(&copy.metadata() == seen[0]);
}

TEST_CASE("the library reports the version it was built as") {
  CHECK(std::string(mosb::version()) == MOSB_VERSION_STRING);
  CHECK(std::string(mosb::version()) == std::to_string(MOSB_VERSION_MAJOR) + "." +
                                            std::to_string(MOSB_VERSION_MINOR) + "." +
                                            std::to_string(MOSB_VERSION_PATCH));
}
