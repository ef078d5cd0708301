#include "mosb/metadata.hpp"

#include <doctest/doctest.h>

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
