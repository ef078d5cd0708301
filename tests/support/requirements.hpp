// What a unit test needs beyond the repository: the real data of ../shared/data, a program that
// tools/install-deps.sh installs. Without it the test program ends with exit status 77, which
// ctest (SKIP_RETURN_CODE, set for every unit test) reports as skipped, not passed, and on which
// .ci/run fails, since CI has all of it. Call these before the test makes anything.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace mosb::testing {

// ../shared/data beside the repository.
inline std::filesystem::path shared_data() {
  return std::filesystem::path(MOSB_SOURCE_DIR) / ".." / "shared" / "data";
}

// Skips the test (exit 77) unless `present`, saying it lacks `what`.
inline void require(bool present, const std::string& what) {
  if (present) return;
  std::fprintf(stderr, "SKIPPED for want of %s\n", what.c_str());
  std::exit(77);
}

inline void require_shared(const std::filesystem::path& path) {
  require(std::filesystem::exists(path), path.string() + " (../shared/data)");
}

}  // namespace mosb::testing
