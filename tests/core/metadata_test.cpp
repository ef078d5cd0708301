#include "mosb/metadata.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "mosb/error.hpp"

using mosb::Metadata;

TEST_CASE("metadata serializes sorted, escaped, and parses back") {
  Metadata m;
  m.set("zeta", "last");
  m.set("alpha", "back\\slash\nnew line = kept");
  m.set("empty", "");
  const auto text = m.serialize();
  CHECK(text == "alpha=back\\\\slash\\nnew line = kept\nempty=\nzeta=last\n");
  const auto back = Metadata::parse(text);
  CHECK(back.entries() == m.entries());
  CHECK(Metadata::parse("").entries().empty());
}

TEST_CASE("malformed metadata is rejected with its line") {
  CHECK_THROWS_WITH_AS(Metadata::parse("a=1"), "metadata line 1: missing final newline",
                       mosb::Error);
  CHECK_THROWS_WITH_AS(Metadata::parse("a=1\nnoequals\n"), "metadata line 2: no '=' in line",
                       mosb::Error);
  CHECK_THROWS_WITH_AS(Metadata::parse("b=1\na=2\n"),
                       doctest::Contains("line 2: key 'a' is not in sorted order"), mosb::Error);
  CHECK_THROWS_WITH_AS(Metadata::parse("a=1\na=2\n"), doctest::Contains("repeated"), mosb::Error);
  CHECK_THROWS_WITH_AS(Metadata::parse("a b=1\n"), doctest::Contains("invalid key 'a b'"),
                       mosb::Error);
  CHECK_THROWS_WITH_AS(Metadata::parse("a=x\\t\n"), doctest::Contains("unknown escape '\\t'"),
                       mosb::Error);
  CHECK_THROWS_WITH_AS(Metadata::parse("a=x\\\n"), doctest::Contains("dangling"), mosb::Error);
  CHECK_THROWS_AS(Metadata().set("bad key", "v"), mosb::Error);
}

TEST_CASE("views must name existing objectives and query sets") {
  Metadata m;
  m.set("view.V.objectives", "a,b");
  m.set("view.V.queries", "q");
  CHECK_FALSE(mosb::find_view_problem(m, {"a", "b"}, {"q"}).has_value());
  CHECK(mosb::find_view_problem(m, {"a"}, {"q"}).value().find("names objective 'b'") !=
        std::string::npos);
  CHECK(mosb::find_view_problem(m, {"a", "b"}, {}).value().find("names query set 'q'") !=
        std::string::npos);
}

TEST_CASE("a view needs a name and objectives") {
  Metadata queries_only;
  queries_only.set("view.V.queries", "q");
  CHECK(mosb::find_view_problem(queries_only, {"a"}, {"q"}).value() ==
        "metadata key 'view.V.queries' names a view without objectives (no "
        "'view.V.objectives')");
  Metadata unnamed;
  unnamed.set("view..objectives", "a");
  CHECK(mosb::find_view_problem(unnamed, {"a"}, {}).value() ==
        "metadata key 'view..objectives' names a view with an empty name");
}

TEST_CASE("20,000 views are listed in sorted order in one pass") {
  // view_keys was quadratic (a linear search per key), and the C ABI called it once per view.
  Metadata m;
  for (int i = 0; i < 20000; ++i) {
    const auto name = "view.V" + std::to_string(i);
    m.set(name + ".objectives", "a");
    m.set(name + ".queries", "q");
  }
  const auto views = mosb::view_keys(m);
  REQUIRE(views.size() == 20000);
  CHECK(std::is_sorted(views.begin(), views.end(),
                       [](const auto& x, const auto& y) { return x.name < y.name; }));
  CHECK(views.front().name == "V0");
  CHECK(views.front().query_set == "q");
  CHECK(views.back().objectives == std::vector<std::string>{"a"});
  CHECK_FALSE(mosb::find_view_problem(m, {"a"}, {"q"}).has_value());
}
