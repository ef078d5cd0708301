// The raw-source part of the paper's suite (`mosb suite build DIR --raw RAWDIR`, spec/MANIFEST.md
// "Raw-source benchmarks"): one recipe per published file, naming the raw inputs it needs under
// their download names and building the file through the same converter entry point, with the
// same options, as the `mosb convert ...` command line the recipe documents.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "mosb/converters/suite.hpp"

namespace mosb::converters {

struct RawInput {
  std::string name;  // the download name; the plain or otherwise compressed twin is accepted too
  bool optional = false;
};

struct RawRecipe {
  std::string name;    // the file is name + ".mosb"
  std::string source;  // where its inputs come from (spec/suite.json `source`)
  std::vector<RawInput> inputs;
  // Builds the instance from the path of every input, in `inputs` order (empty for an absent
  // optional input).
  std::function<SuiteInstance(const std::vector<std::filesystem::path>&)> instance;
};

// The names accepted for an input: the download name, then its plain form (without ".gz") or its
// compressed forms (".gz", ".bz2", ".xz", ".zst"); every converter detects compression itself.
std::vector<std::string> raw_input_candidates(const std::string& name);

// Every recipe: the fixed ones of the paper, then one GUARDS recipe per `NAME.guards` found in
// `raw_dir` (the paper does not list its 12 maps), sorted by file name.
std::vector<RawRecipe> raw_recipes(const std::filesystem::path& raw_dir);

struct RawStatus {
  std::string name;                  // the recipe's file name without ".mosb"
  std::vector<std::string> missing;  // required inputs absent from RAWDIR; empty: built
  std::string source;                // where the inputs come from (RawRecipe::source)
};

// "NAME: built", or "NAME: skipped: missing A, B (from: SOURCE)": how a recipe's status is said.
std::string raw_status_text(const RawStatus& status);

struct RawPlan {
  std::vector<SuiteInstance> instances;  // the recipes whose required inputs are all present
  std::vector<RawStatus> statuses;       // one per recipe, in recipe order
};

RawPlan plan_raw_suite(const std::filesystem::path& raw_dir);

}  // namespace mosb::converters
