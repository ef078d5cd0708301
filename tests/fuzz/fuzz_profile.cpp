// libFuzzer target: arbitrary bytes as a solver-profile file, read as `--profile FILE` reads one
// (load_profile: the bounded reader, then TOML and the profile's keys). tests/fuzz/run.sh lets
// inputs grow past the reader's 1 MiB cap, so the refusal of a larger file is fuzzed too. Any
// outcome but a profile or a clean one-line mosb::Error naming the file is a bug.
#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "mosb/converters/profile.hpp"
#include "mosb/error.hpp"

namespace {

// A directory of this process's own, removed at exit.
const std::string& profile_path() {
  static const std::string path = [] {
    std::string directory = "/tmp/mosb-fuzz-profile-XXXXXX";
    if (::mkdtemp(directory.data()) == nullptr) __builtin_trap();
    static const std::string removed = directory;
    std::atexit([] { std::filesystem::remove_all(removed); });
    return directory + "/fuzz.toml";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& path = profile_path();
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    const auto profile = mosb::converters::load_profile(path);
    if (size > (std::size_t{1} << 20)) __builtin_trap();  // past the cap: never parsed
    if (profile.name.empty() || profile.command.empty()) __builtin_trap();
  } catch (const mosb::Error& e) {
    const std::string_view what = e.what();
    if (!what.starts_with(path + ":") || what.find('\n') != std::string_view::npos)
      __builtin_trap();
  }
  return 0;
}
