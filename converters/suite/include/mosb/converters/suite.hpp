// Writes a whole benchmark suite (many independent instances) into one directory, in parallel,
// followed by a MANIFEST (spec/MANIFEST.md, one record per file, sorted by file name), written
// atomically last (spec/GENERATORS.md, Suites). The bytes never depend on the thread count.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "mosb/graph_builder.hpp"
#include "mosb/pack.hpp"
#include "mosb/progress.hpp"

namespace mosb::converters {

struct SuiteInstance {
  std::string name;  // the file is name + ".mosb"
  // Called on a worker thread; must not share mutable state.
  std::function<std::variant<GraphInput, StreamedGraph>()> build;
  // Optional, on the same thread: rewrites the written file before it is packed (a raw recipe's
  // query set, added exactly as `mosb queries import --in-place` adds it).
  std::function<void(const std::filesystem::path&)> finish = {};
};

// The instances whose name matches one of the shell patterns (fnmatch: *, ?, [...]), in their
// order; all of them for no pattern. Throws mosb::Error naming a pattern that matches none, so a
// typo never builds an empty suite silently: ErrorCode::not_found with what `unbuilt` says of the
// benchmarks it matches there (name, then why it cannot be built: its missing raw inputs and
// where they come from), else invalid_argument.
std::vector<SuiteInstance> select_suite_instances(
    std::vector<SuiteInstance> instances, const std::vector<std::string>& patterns,
    const std::vector<std::pair<std::string, std::string>>& unbuilt = {});

struct SuiteEntry {
  std::string name;
  std::string file;
  std::uint64_t size = 0;
  std::string digest;  // FORMAT.md §8 content digest
  // Listed by the directory's MANIFEST before and not rebuilt: checked and kept.
  bool kept = false;
};

struct SuiteOptions {
  unsigned threads = 0;  // 0: std::thread::hardware_concurrency()
  // Stage "suite": called with 0 first, then once per finished instance, serialized.
  Progress progress;
  // Pack each file right after writing it (mosb::pack_file, in place); the MANIFEST then lists
  // the packed files. PackOptions::threads is ignored: instances are packed in parallel instead.
  std::optional<PackOptions> pack;
  // False (the default): a directory that already has a MANIFEST is added to; its entries that
  // are not rebuilt are checked (Store-level: size, SHA-256, verify --level full, digest) before
  // anything is written and stay listed. True: the MANIFEST lists the built instances only.
  bool replace = false;
};

// Creates `directory` if needed, writes every instance and then MANIFEST (of the JSON Lines format
// whatever the earlier one's): the built instances and, unless `options.replace`, every entry the
// earlier MANIFEST listed that was not rebuilt. Returns one entry per listed file, sorted by name
// (kept ones marked). A kept entry that fails its check throws mosb::Error naming it before
// anything is built; on a build failure throws the error of the lowest-index failing instance (the
// MANIFEST is left as it was).
std::vector<SuiteEntry> run_suite(const std::filesystem::path& directory,
                                  const std::vector<SuiteInstance>& instances,
                                  const SuiteOptions& options);

// The seed of one suite instance: mix(suite_seed + 0x9E3779B97F4A7C15 * key), where the key encodes
// the instance's parameters, so a subset of a suite reproduces the full suite's files exactly.
std::uint64_t suite_instance_seed(std::uint64_t suite_seed, std::uint64_t key);

// The suite as data (spec/suite.json, compiled in): the generated benchmarks' parameters and one
// recipe per raw-source benchmark. The Python package installs the same file (mosb.suite()).
std::string_view suite_description_json();

// The paper's sizes, from the description: 300, 350, ..., 600 (7 x 7 = 49 graphs) and
// N = 10000, 20000, 30000.
std::vector<std::uint32_t> paper_grid_sizes();
std::vector<std::uint32_t> paper_netmaker_vertex_counts();

// Grid-KxM for every K, M in `sizes`, 3 objectives (views Grid_2 and Grid_3); key K * 2^20 + M.
std::vector<SuiteInstance> grid_suite(std::uint64_t suite_seed,
                                      const std::vector<std::uint32_t>& sizes);

// NetMaker-N<N>-I<I>-<r> for N in `vertex_counts`, I in {20, 50}, r in {1, 2}; A = 1, B = 10;
// key (N * 2^16 + I) * 4 + r.
std::vector<SuiteInstance> netmaker_suite(std::uint64_t suite_seed,
                                          const std::vector<std::uint32_t>& vertex_counts);

// The generated part of the published suite (`mosb suite build`): the description's seed (1), the
// paper's sizes, the 49 Grids then the 12 NetMakers; the same instances `generate grid|netmaker
// --suite` writes, so a single file can still be rebuilt from its own command.
std::vector<SuiteInstance> published_generated_suite();

}  // namespace mosb::converters
