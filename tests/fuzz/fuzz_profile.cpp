// libFuzzer target: arbitrary bytes through the solver-profile parser (TOML, then the profile's
// keys). Any outcome but a profile or a clean one-line mosb::Error naming the file is a bug.
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/converters/profile.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.toml";
  try {
    const auto profile = mosb::converters::parse_profile(text, name);
    if (profile.name.empty() || profile.command.empty()) __builtin_trap();
  } catch (const mosb::Error& e) {
    const std::string_view what = e.what();
    if (what.substr(0, name.size()) != name || what.find('\n') != std::string_view::npos)
      __builtin_trap();
  }
  return 0;
}
