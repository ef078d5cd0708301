#include "mosb/converters/suite.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <fstream>
#include <mutex>

#include "mosb/atomic_file.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/converters/netmaker_generator.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/parallel.hpp"
#include "mosb/manifest.hpp"
#include "mosb/random.hpp"
#include "mosb/store.hpp"
#include "suite_description.hpp"

namespace mosb::converters {

namespace {

// A size listed twice would make two workers write the same file.
std::vector<std::uint32_t> sorted_unique(std::vector<std::uint32_t> values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

// The earlier MANIFEST's entries that this build does not rebuild, each checked as a store checks
// its entries; throws naming the first one with a problem, so a suite never lists a file that is
// not what its entry says. Entries of a legacy (TSV) MANIFEST are described again from their bytes.
std::vector<ManifestEntry> kept_entries(const std::filesystem::path& directory,
                                        const std::vector<SuiteInstance>& instances,
                                        const SuiteOptions& options) {
  const auto manifest_path = directory / kManifestName;
  std::error_code ec;
  if (options.replace || !std::filesystem::exists(manifest_path, ec)) return {};
  const auto manifest = read_manifest(manifest_path);
  std::vector<std::pair<ManifestEntry, std::filesystem::path>> kept;
  for (const auto& entry : manifest.entries)
    if (std::none_of(instances.begin(), instances.end(),
                     [&](const SuiteInstance& i) { return i.name + ".mosb" == entry.file; }))
      kept.emplace_back(entry, directory / entry.file);
  const auto checks =
      check_files(kept, {options.threads, {}, false}, instance_paths(manifest, directory));
  std::vector<ManifestEntry> out;
  for (std::size_t i = 0; i < checks.size(); ++i) {
    if (!checks[i].ok())
      throw Error(ErrorCode::invalid_argument,
                  {(directory / kManifestName).string() + " lists " + checks[i].file +
                       ", which this build keeps but which fails its check (" +
                       checks[i].problems.front().detail + "); rebuild it (",
                   setting("suite.benchmarks"), ") or start over (", setting("replace"), ")"});
    out.push_back(manifest.legacy ? describe_file(kept[i].second) : kept[i].first);
  }
  return out;
}

}  // namespace

std::vector<SuiteInstance> select_suite_instances(
    std::vector<SuiteInstance> instances, const std::vector<std::string>& patterns,
    const std::vector<std::pair<std::string, std::string>>& unbuilt) {
  if (patterns.empty()) return instances;
  const auto matches = [](const std::string& pattern, const SuiteInstance& i) {
    return ::fnmatch(pattern.c_str(), i.name.c_str(), 0) == 0;
  };
  for (const auto& pattern : patterns) {
    if (std::any_of(instances.begin(), instances.end(),
                    [&](const SuiteInstance& i) { return matches(pattern, i); }))
      continue;
    std::string why;
    for (const auto& [name, reason] : unbuilt)
      if (::fnmatch(pattern.c_str(), name.c_str(), 0) == 0)
        why += (why.empty() ? "" : "; ") + reason;
    if (!why.empty())
      throw Error(ErrorCode::not_found,
                  {setting("suite.benchmarks"),
                   " '" + pattern + "' matches no benchmark that can be built: " + why});
    throw Error(ErrorCode::invalid_argument,
                {setting("suite.benchmarks"),
                 " '" + pattern +
                     "' matches no benchmark to build (the generated ones, and the raw-source ones "
                     "whose inputs are present)"});
  }
  std::erase_if(instances, [&](const SuiteInstance& i) {
    return std::none_of(patterns.begin(), patterns.end(),
                        [&](const std::string& p) { return matches(p, i); });
  });
  return instances;
}

std::vector<SuiteEntry> run_suite(const std::filesystem::path& directory,
                                  const std::vector<SuiteInstance>& instances,
                                  const SuiteOptions& options) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error(directory.string() + ": cannot create the suite directory: " + ec.message());
  const auto kept = kept_entries(directory, instances, options);

  std::vector<SuiteEntry> entries(instances.size());
  Manifest manifest;
  manifest.entries.resize(instances.size());
  std::mutex progress_mutex;
  std::size_t done = 0;
  report(options.progress, "suite", 0, instances.size());

  // A failed build leaves the MANIFEST untouched and removes the files it added. A file whose name
  // was there before is replaced atomically (the same bytes, for the same options), except when
  // its own recipe fails after writing it: then it stays, and `verify --manifest` reports it.
  std::vector<char> added(instances.size(), 0);
  const auto build = [&](std::size_t i) {
    const auto file = instances[i].name + ".mosb";
    std::error_code absent;
    added[i] = !std::filesystem::exists(directory / file, absent);
    std::visit([&](const auto& graph) { write_graph(graph, directory / file); },
               instances[i].build());
    if (instances[i].finish) instances[i].finish(directory / file);
    if (options.pack) pack_file(directory / file, directory / file, {options.pack->level, 1});
    manifest.entries[i] = describe_file(directory / file);
    const auto& e = manifest.entries[i];
    entries[i] = {instances[i].name, file, e.size, e.digest};
    std::lock_guard lock(progress_mutex);
    ++done;
    report(options.progress, "suite", done, instances.size());
  };
  try {
    parallel_for(instances.size(), thread_count(options.threads), build);
  } catch (...) {
    for (std::size_t i = 0; i < instances.size(); ++i)
      if (added[i]) std::filesystem::remove(directory / (instances[i].name + ".mosb"), ec);
    throw;
  }

  for (const auto& entry : kept) {
    manifest.entries.push_back(entry);
    const auto stem =
        entry.file.ends_with(".mosb") ? entry.file.substr(0, entry.file.size() - 5) : entry.file;
    entries.push_back({stem, entry.file, entry.size, entry.digest, true});
  }
  std::sort(manifest.entries.begin(), manifest.entries.end(),
            [](const ManifestEntry& a, const ManifestEntry& b) { return a.file < b.file; });
  std::sort(entries.begin(), entries.end(),
            [](const SuiteEntry& a, const SuiteEntry& b) { return a.name < b.name; });
  write_manifest(directory / kManifestName, manifest);
  return entries;
}

std::uint64_t suite_instance_seed(std::uint64_t suite_seed, std::uint64_t key) {
  return SplitMix64::mix(suite_seed + 0x9E3779B97F4A7C15ULL * key);
}

std::vector<std::uint32_t> paper_grid_sizes() {
  return suite_description::counts(suite_description::generated("grid"), "sizes");
}
std::vector<std::uint32_t> paper_netmaker_vertex_counts() {
  return suite_description::counts(suite_description::generated("netmaker"), "vertices");
}

std::vector<SuiteInstance> grid_suite(std::uint64_t suite_seed,
                                      const std::vector<std::uint32_t>& sizes) {
  const auto& grid = suite_description::generated("grid");
  const auto name = suite_description::text(grid, "name");
  const auto objectives = suite_description::count(grid, "objectives");
  std::vector<SuiteInstance> out;
  const auto unique = sorted_unique(sizes);
  for (auto width : unique)
    for (auto height : unique) {
      if (width < 1 || height < 1 || width >= (1u << 20) || height >= (1u << 20))
        throw Error("grid suite: sizes must be 1 to 2^20 - 1");
      const GridParameters p{
          width, height, objectives,
          suite_instance_seed(suite_seed, (std::uint64_t{width} << 20) + height)};
      out.push_back({suite_description::expand(name, {{"width", std::to_string(width)},
                                                      {"height", std::to_string(height)}}),
                     [p] { return grid_graph(p); }});
    }
  return out;
}

std::vector<SuiteInstance> netmaker_suite(std::uint64_t suite_seed,
                                          const std::vector<std::uint32_t>& vertex_counts) {
  const auto& netmaker = suite_description::generated("netmaker");
  const auto name = suite_description::text(netmaker, "name");
  const auto localities = suite_description::counts(netmaker, "locality");
  const auto replicas = suite_description::count(netmaker, "replicas");
  std::vector<SuiteInstance> out;
  for (auto n : sorted_unique(vertex_counts))
    for (std::uint32_t locality : localities)
      for (std::uint32_t r = 1; r <= replicas; ++r) {
        NetMakerParameters p;
        p.vertices = n;
        p.amin = suite_description::count(netmaker, "amin");
        p.amax = suite_description::count(netmaker, "amax");
        p.locality = locality;
        p.seed = suite_instance_seed(suite_seed, ((std::uint64_t{n} << 16) + locality) * 4 + r);
        p.name = suite_description::expand(name, {{"vertices", std::to_string(n)},
                                                  {"locality", std::to_string(locality)},
                                                  {"replica", std::to_string(r)}});
        out.push_back({*p.name, [p] { return netmaker_graph(p); }});
      }
  return out;
}

std::vector<SuiteInstance> published_generated_suite() {
  const std::uint64_t seed = suite_description::count(suite_description::root(), "seed");
  auto instances = grid_suite(seed, paper_grid_sizes());
  for (auto& instance : netmaker_suite(seed, paper_netmaker_vertex_counts()))
    instances.push_back(std::move(instance));
  return instances;
}

}  // namespace mosb::converters
