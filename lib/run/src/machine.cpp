#include <sys/utsname.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "mosb/run.hpp"

namespace mosb {

namespace {

// The value after "KEY:" on the first line of `path` that starts with `key`, trimmed.
std::string field(const char* path, std::string_view key) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with(key)) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const auto first = line.find_first_not_of(" \t", colon + 1);
    return first == std::string::npos ? std::string() : line.substr(first);
  }
  return {};
}

}  // namespace

std::string describe_machine() {
  std::string cpu = field("/proc/cpuinfo", "model name");
  if (cpu.empty()) cpu = "unknown CPU";
  const long cores = ::sysconf(_SC_NPROCESSORS_ONLN);
  std::string memory = field("/proc/meminfo", "MemTotal");
  utsname names{};
  std::string kernel = "unknown kernel";
  if (::uname(&names) == 0)
    kernel = std::string(names.sysname) + " " + names.release + " " + names.machine;
  return cpu + ", " + std::to_string(cores) + " cores, memory " +
         (memory.empty() ? "unknown" : memory) + ", " + kernel;
}

}  // namespace mosb
