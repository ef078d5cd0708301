#include "mosb/verify.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pack.hpp"
#include "mosb/store.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct VerifyArgs {
  std::vector<std::string> files;
  std::string level = "full";
  std::string manifest;
  std::string sources;
  bool json = false;
  std::uint64_t max_memory = 0;
};

// `verify --manifest FILE [PATH...]`: downloaded files against a published manifest.
int run_verify_manifest(const VerifyArgs& a) {
  TerminalProgress display;
  std::vector<std::filesystem::path> paths(a.files.begin(), a.files.end());
  // A download unpacked (or packed) since passes as what it is: the listed content, other bytes.
  return report_checks(check_against_manifest(a.manifest, paths, {0, display.callback(), true}),
                       a.json);
}

// `verify --sources DIR FILE`: the raw files in DIR against FILE's source.input.* provenance.
int run_verify_sources(const VerifyArgs& a) {
  if (a.files.size() != 1) throw UsageError("--sources DIR takes exactly one instance FILE");
  auto checks = check_sources(GraphReader::open(a.files.front()), a.sources);
  // A FIFO, device or directory in place of a raw file: say so, not what reading it threw.
  for (auto& c : checks) {
    std::error_code error;
    const auto status = std::filesystem::status(c.path, error);
    if (!c.problem.empty() && !error && std::filesystem::exists(status) &&
        !std::filesystem::is_regular_file(status))
      c.problem = c.path.string() + ": not a regular file";
  }
  std::size_t failures = 0;
  for (const auto& c : checks) failures += c.problem.empty() ? 0 : 1;
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("file").value(a.files.front());
    json.key("ok").value(failures == 0);
    json.key("sources").begin_array();
    for (const auto& c : checks) {
      json.begin_object();
      json.key("name").value(c.expected.name);
      json.key("size").value(c.expected.size);
      json.key("xxh3").value(c.expected.xxh3);
      json.key("ok").value(c.problem.empty());
      if (!c.problem.empty()) json.key("problem").value(c.problem);
      json.end_object();
    }
    json.end_array();
    json.end_object();
  } else {
    for (const auto& c : checks) {
      if (c.problem.empty())
        std::cout << "OK   " << escape_for_terminal(c.path.string()) << " (" << c.expected.size
                  << " bytes, XXH3 " << c.expected.xxh3 << ")\n";
      else
        std::cout << "FAIL " << escape_for_terminal(c.problem) << '\n';
    }
  }
  return failures == 0 ? 0 : 1;
}

struct Outcome {
  std::string file;
  std::optional<std::string> problem;
  std::string digest;
};

int run_verify(const VerifyArgs& a) {
  if (!a.manifest.empty()) return run_verify_manifest(a);
  if (!a.sources.empty()) return run_verify_sources(a);
  if (a.files.empty()) throw UsageError("INSTANCE is required (or --manifest FILE)");
  const auto verify_level = *parse_verify_level(a.level);
  TerminalProgress display;
  // One file: its own checks are the progress; several: the files are.
  const bool one_file = a.files.size() == 1;
  const auto progress = display.callback();
  const auto per_file = one_file ? Progress{} : progress;
  std::vector<Outcome> outcomes;
  report(per_file, "verify", 0, a.files.size());
  for (const auto& file : a.files) {
    Outcome outcome{file, std::nullopt, ""};
    try {
      // A packed file is decoded first, unless only its header and table are checked.
      auto result = verify_file(file, verify_level, a.max_memory, one_file ? progress : Progress{});
      outcome.problem = std::move(result.problem);
      if (outcome.problem) outcome.problem = file + ": " + *outcome.problem;
      outcome.digest = std::move(result.digest);
    } catch (const Error& e) {
      outcome.problem = error_text(e);
    }
    outcomes.push_back(std::move(outcome));
    report(per_file, "verify", outcomes.size(), a.files.size());
  }
  int failures = 0;
  for (const auto& o : outcomes) failures += o.problem ? 1 : 0;
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("level").value(a.level);
    json.key("ok").value(failures == 0);
    json.key("files").begin_array();
    for (const auto& o : outcomes) {
      json.begin_object();
      json.key("file").value(o.file);
      json.key("ok").value(!o.problem);
      if (o.problem)
        json.key("problem").value(*o.problem);
      else
        json.key("digest").value(o.digest);
      json.end_object();
    }
    json.end_array();
    json.end_object();
  } else {
    for (const auto& o : outcomes) {
      if (o.problem)
        std::cout << "FAIL " << escape_for_terminal(*o.problem) << '\n';
      else
        std::cout << "OK   " << escape_for_terminal(o.file) << " (" << a.level << ", digest "
                  << o.digest << ")\n";
    }
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace

Command add_verify(CLI::App& app) {
  auto* sub = app.add_subcommand("verify", "Check files: header, checksums, structure, or all");
  auto args = std::make_shared<VerifyArgs>();
  sub->add_option("INSTANCE", args->files,
                  "the .mosb instances to verify (with --manifest: the files to check, default "
                  "every listed file beside the manifest)");
  auto* level = sub->add_option("--level", args->level, "how much to check")
                    ->check(CLI::IsMember(kVerifyLevelNames.names()))
                    ->capture_default_str();
  auto* manifest = sub->add_option(
      "--manifest", args->manifest,
      "check files against this published MANIFEST (size, SHA-256, digest, full verification)");
  auto* sources = sub->add_option(
      "--sources", args->sources,
      "check that the raw files in this directory are the instance's recorded inputs");
  add_max_memory_option(sub, args->max_memory);
  manifest->excludes(sources);
  level->excludes(manifest)->excludes(sources);
  add_json_flag(sub, args->json);
  return {sub, [args] { return run_verify(*args); }};
}

}  // namespace mosb::cli
