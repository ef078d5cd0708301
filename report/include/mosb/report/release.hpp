// `mosb suite release`: an experiment's instances and references as the store a suite is published
// as (spec/MANIFEST.md, "Releasing an experiment"), with its summary and a README naming the
// protocol. The same inputs give the same bytes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "mosb/manifest.hpp"
#include "mosb/pack.hpp"
#include "mosb/progress.hpp"

namespace mosb::pages {

struct ReleaseOptions {
  PackOptions pack;  // how the files are packed (level 19: one level, reproducible bytes)
  // The references packed too (format 1.6): about six times fewer bytes to download (a real
  // front; spec/BENCHMARKS.md, issue 45), which every pull then decodes to check. Kept raw by
  // default: a checked pull of raw references is faster than curl and sha256sum of them.
  bool pack_references = false;
  Progress progress;  // Store::add's stages
};

struct Release {
  std::vector<ManifestEntry> entries;  // the store's MANIFEST
  // The instances the references leave without one (file names), said in README.md too.
  std::vector<std::string> without_reference;
};

// Writes into `store`, which must not exist or be an empty directory: every instance of the
// experiment `results` (result_instances), packed; every solution file of `references` (a file or
// a directory of them), each an exact reference (ε = 0) of one of those instances, checked as
// `store add` checks it; then SUMMARY.csv, the suite table (the paper's Table 1) of the
// experiment's views over those references, and README.md: the experiment, its limits and
// solvers (executable SHA-256), the reference's solvers and whose statistics it carries, the
// machine, the contents and how to pull and evaluate them. Throws mosb::Error naming the file
// when a reference is approximate or belongs to no instance of the experiment, before anything is
// written.
Release release_suite(const std::filesystem::path& results, const std::filesystem::path& references,
                      const std::filesystem::path& store, const ReleaseOptions& options);

}  // namespace mosb::pages
