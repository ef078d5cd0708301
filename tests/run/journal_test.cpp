#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

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
