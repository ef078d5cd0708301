// Whole-file text I/O for tests that write fixtures and read results back.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace mosb::testing {

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace mosb::testing
