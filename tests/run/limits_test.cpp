// The limits' text of `mosb run` and of an experiment file: parse_duration, parse_memory_size.
#include <doctest/doctest.h>

#include <cstdint>

#include "mosb/run.hpp"

using namespace mosb;

TEST_CASE("parse_memory_size: bytes, K M G T as powers of 1024, an optional B or iB") {
  CHECK(parse_memory_size("0") == 0U);
  CHECK(parse_memory_size("4294967296") == 4294967296U);
  CHECK(parse_memory_size("100B") == 100U);
  CHECK(parse_memory_size("1K") == 1024U);
  CHECK(parse_memory_size("1k") == 1024U);
  CHECK(parse_memory_size("2KB") == 2048U);
  CHECK(parse_memory_size("2KiB") == 2048U);
  CHECK(parse_memory_size("512M") == 512ULL << 20);
  CHECK(parse_memory_size("512MiB") == 512ULL << 20);
  CHECK(parse_memory_size("16G") == 16ULL << 30);
  CHECK(parse_memory_size("16GB") == 16ULL << 30);
  CHECK(parse_memory_size("1T") == 1ULL << 40);
  // Either case, as the command line's size options have always taken them (one grammar).
  CHECK(parse_memory_size("16g") == 16ULL << 30);
  CHECK(parse_memory_size("1m") == 1ULL << 20);
  CHECK(parse_memory_size("2kib") == 2048U);
  CHECK(parse_memory_size("100b") == 100U);
  CHECK(parse_memory_size("18446744073709551615") == UINT64_MAX);
  CHECK(parse_memory_size("16777215T") == 16777215ULL << 40);
}

TEST_CASE("parse_memory_size: malformed or out of range is nullopt, never a wrapped value") {
  for (const char* bad :
       {"", "G", "B", "iB", "-1", "+1", " 1", "1 ", "1.5G", "16Q", "16GiBB", "100iB", "1KBB", "1e9",
        "0x10", "18446744073709551616", "99999999999999999999", "16777216T", "17179869184G"})
    CHECK_MESSAGE(!parse_memory_size(bad), bad);
}

TEST_CASE("parse_duration: seconds, ms, m or min, h") {
  CHECK(parse_duration("60") == 60.0);
  CHECK(parse_duration("60s") == 60.0);
  CHECK(parse_duration("0") == 0.0);
  CHECK(parse_duration("1.5m") == 90.0);
  CHECK(parse_duration("2min") == 120.0);
  CHECK(parse_duration("500ms") == doctest::Approx(0.5));
  CHECK(parse_duration("2h") == 7200.0);
  CHECK(parse_duration(".5s") == 0.5);
  CHECK(parse_duration("1e3") == 1000.0);
  CHECK(parse_duration("1000000000") == 1e9);
}

TEST_CASE("parse_duration: malformed, negative, not finite or above 1e9 s is nullopt") {
  for (const char* bad : {"", "s", "-1", "-1s", "+1", " 1", "1 ", "1 s", "1d", "1hh", "nan", "inf",
                          "infinity", "0x10", "0x1p4", "1e10", "1000000001", "300000h", "1,5s"})
    CHECK_MESSAGE(!parse_duration(bad), bad);
}
