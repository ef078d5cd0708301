#include "mosb/solver_protocol.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "mosb/error.hpp"

TEST_CASE("a protocol front: one vector per line, blanks and tabs, CRLF, blank lines") {
  const auto f = mosb::parse_protocol_front("1 2\n\n 3\t4.5 \r\n6e1 7", 2, "out");
  CHECK(f.vectors == 3);
  CHECK(f.costs == std::vector<double>{1, 2, 3, 4.5, 60, 7});
  CHECK(mosb::parse_protocol_front("", 3, "out").vectors == 0);
  CHECK(mosb::parse_protocol_front("\n \n", 3, "out").vectors == 0);
}

TEST_CASE("a protocol front refuses anything else, naming line and column") {
  CHECK_THROWS_WITH_AS(mosb::parse_protocol_front("1 2\n3\n", 2, "out"),
                       "out:2:2: 1 values, the view has 2 objectives", mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::parse_protocol_front("1 2 3\n", 2, "out"),
                       "out:1:5: more than 2 values in a vector", mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::parse_protocol_front("1 x\n", 2, "out"),
                       "out:1:3: 'x' is not a number", mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::parse_protocol_front("1,2\n", 2, "out"),
                       "out:1:1: '1,2' is not a number", mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::parse_protocol_front("inf 2\n", 2, "out"),
                       "out:1:1: a cost is not finite", mosb::Error);
}

TEST_CASE("protocol statistics on stderr") {
  const auto s = mosb::parse_protocol_statistics(
      "starting\nmosb: expanded=12\r\nmosb: generated=30\nmosb: runtime_seconds=0.5\n"
      "mosb: colour=blue\nlog mosb: expanded=x\n",
      "err");
  CHECK(s.expanded == 12u);
  CHECK(s.generated == 30u);
  CHECK(s.runtime_seconds == 0.5);
  CHECK_FALSE(mosb::parse_protocol_statistics("nothing\n", "err").expanded.has_value());
  CHECK_THROWS_WITH_AS(mosb::parse_protocol_statistics("a\nmosb: expanded=-1\n", "err"),
                       "err:2: expanded is not an unsigned integer below 2^64 - 1", mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::parse_protocol_statistics("mosb: hello\n", "err"),
                       "err:1: a 'mosb: ' line without key=value", mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::parse_protocol_statistics("mosb: runtime_seconds=nan\n", "err"),
                       doctest::Contains("runtime_seconds is not"), mosb::Error);
}
