#include "mosb/command_template.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "mosb/error.hpp"

using Words = std::vector<std::string>;

TEST_CASE("split_command splits like a shell without expanding") {
  CHECK(mosb::split_command("a b\tc\n d") == Words{"a", "b", "c", "d"});
  CHECK(mosb::split_command("  solver  ") == Words{"solver"});
  CHECK(mosb::split_command("'a b' \"c d\"") == Words{"a b", "c d"});
  CHECK(mosb::split_command("a\\ b") == Words{"a b"});
  CHECK(mosb::split_command("'x'\"y\"z") == Words{"xyz"});
  CHECK(mosb::split_command("'' b") == Words{"", "b"});
  CHECK(mosb::split_command("\"a\\\"b\\\\c\\d\"") == Words{"a\"b\\c\\d"});
  CHECK(mosb::split_command("'a\\b'") == Words{"a\\b"});
  CHECK(mosb::split_command("a;b $HOME * >x") == Words{"a;b", "$HOME", "*", ">x"});
  CHECK(mosb::split_command("a \\\nb") == Words{"a", "b"});
}

TEST_CASE("split_command refuses what a shell would not finish") {
  CHECK_THROWS_WITH_AS(mosb::split_command("a 'b"), doctest::Contains("unterminated single"),
                       mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::split_command("a \"b"), doctest::Contains("unterminated double"),
                       mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::split_command("a \\"), doctest::Contains("backslash ends"),
                       mosb::Error);
  CHECK_THROWS_WITH_AS(mosb::split_command(" \t"), doctest::Contains("empty"), mosb::Error);
}

TEST_CASE("placeholders are checked and filled word by word") {
  const Words words = mosb::split_command("s {instance} --q={source},{target} '{front}' {{x}}");
  CHECK(mosb::template_placeholders(words, mosb::run_placeholders()) ==
        Words{"instance", "source", "target", "front"});
  const auto argv = mosb::expand_command(
      words, {{"instance", "a b;c.mosb"}, {"source", "1"}, {"target", "2"}, {"front", "f"}});
  CHECK(argv == Words{"s", "a b;c.mosb", "--q=1,2", "f", "{x}"});
  CHECK_THROWS_WITH_AS(
      mosb::template_placeholders(mosb::split_command("s {nope}"), mosb::run_placeholders()),
      doctest::Contains("unknown placeholder {nope}"), mosb::Error);
  CHECK_THROWS_WITH_AS(
      mosb::template_placeholders(mosb::split_command("s {query"), mosb::run_placeholders()),
      doctest::Contains("without '}'"), mosb::Error);
  CHECK_THROWS_WITH_AS(
      mosb::template_placeholders(mosb::split_command("s query}"), mosb::run_placeholders()),
      doctest::Contains("without '{'"), mosb::Error);
}

TEST_CASE("shell_quote: as it is when safe, else quoted, and split_command reads it back") {
  CHECK(mosb::shell_quote("it's") == "'it'\\''s'");
  CHECK(mosb::shell_quote("") == "''");
  CHECK(mosb::shell_quote("a/b-c.d") == "a/b-c.d");
  CHECK(mosb::shell_quote("{instance}") == "'{instance}'");
  for (const std::string word :
       {"plain", "two words", "it's", "\"q\"", "$HOME", "a\\b", "tab\there", "new\nline", "*;|>",
        "--flag=1,2", "{front}", "''", "\\"})
    CHECK_MESSAGE(mosb::split_command(mosb::shell_quote(word)) == Words{word}, word);
}
