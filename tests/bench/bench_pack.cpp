// mosb_bench_pack: packed size and decoding speed of instances (issue 10's targets: packed smaller
// than gzip -9 / xz -9 of the text, decoding at >= 1 GB/s of output on one core).
//
//   mosb_bench_pack [--repeat R] FILE.mosb...
//
// Each FILE is packed twice at level 19, as `mosb pack` does by default (the reverse CSR derived,
// format 1.2) and with --keep-reverse (1.1), into a temporary directory. Then unpack_bytes, the
// decoder behind `mosb unpack` and GraphReader::load, decodes each packed file from memory R times
// (default 5), and at least as often as it takes to decode 256 MB: a decoding of a small file
// takes about a millisecond, of which the VM's page-table work varies most. The best time is
// reported as GB/s of decoded output. Run it pinned to one core
// (`taskset -c 0`) on an idle machine. Exit 1 only when a decoded image differs from FILE.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "mosb/container.hpp"
#include "mosb/pack.hpp"

using namespace mosb;
using Clock = std::chrono::steady_clock;

namespace {

struct Decoding {
  std::uint64_t packed_size;
  double best_seconds;
};

Decoding measure(const std::filesystem::path& packed, const MappedFile& original, int repeat) {
  const auto file = map_file(packed);
  const auto runs =
      std::max<std::uint64_t>(repeat, (std::uint64_t{256} << 20) / original.bytes.size());
  double best = 1e300;
  for (std::uint64_t r = 0; r < runs; ++r) {
    const auto start = Clock::now();
    const auto image = unpack_bytes(file.bytes, packed.string());
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
    if (image.bytes.size() != original.bytes.size() ||
        std::memcmp(image.bytes.data(), original.bytes.data(), image.bytes.size()) != 0) {
      std::fprintf(stderr, "%s: decodes to other bytes than its input\n", packed.c_str());
      std::exit(1);
    }
  }
  return {file.bytes.size(), best};
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeat" && i + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++i]));
    else
      files.emplace_back(arg);
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: mosb_bench_pack [--repeat R] FILE.mosb...\n");
    return 2;
  }
  const auto dir = std::filesystem::temp_directory_path() / "mosb-bench-pack";
  std::filesystem::create_directories(dir);
  std::printf("%-28s %12s | %12s %8s %9s | %12s %8s %9s\n", "file", "bytes", "derived", "ratio",
              "GB/s", "kept", "ratio", "GB/s");
  for (const auto& file : files) {
    const auto original = map_file(file);
    const double size = static_cast<double>(original.bytes.size());
    PackOptions derived, kept;
    kept.derive_reverse = false;
    const auto derived_path = dir / "derived.mosb", kept_path = dir / "kept.mosb";
    pack_file(file, derived_path, derived);
    pack_file(file, kept_path, kept);
    const auto d = measure(derived_path, original, repeat);
    const auto k = measure(kept_path, original, repeat);
    std::printf("%-28s %12.0f | %12llu %8.3f %9.2f | %12llu %8.3f %9.2f\n", file.filename().c_str(),
                size, static_cast<unsigned long long>(d.packed_size), d.packed_size / size,
                size / d.best_seconds / 1e9, static_cast<unsigned long long>(k.packed_size),
                k.packed_size / size, size / k.best_seconds / 1e9);
  }
  std::filesystem::remove_all(dir);
  return 0;
}
