#include "mosb/verify.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct VerifyArgs {
  std::vector<std::string> files;
  std::string level = "full";
  bool json = false;
};

struct Outcome {
  std::string file;
  std::optional<std::string> problem;
  std::string digest;
};

int run_verify(const VerifyArgs& a) {
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
      const auto reader = GraphReader::open(file);
      outcome.problem = verify(reader, verify_level, one_file ? progress : Progress{});
      if (outcome.problem) outcome.problem = file + ": " + *outcome.problem;
      outcome.digest = reader.digest();
    } catch (const Error& e) {
      outcome.problem = e.what();
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
        std::cout << "FAIL " << *o.problem << '\n';
      else
        std::cout << "OK   " << o.file << " (" << a.level << ", digest " << o.digest << ")\n";
    }
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace

Command add_verify(CLI::App& app) {
  auto* sub = app.add_subcommand("verify", "Check files: header, checksums, structure, or all");
  auto args = std::make_shared<VerifyArgs>();
  sub->add_option("INSTANCE", args->files, "the .mosb instances to verify")->required();
  sub->add_option("--level", args->level, "how much to check")
      ->check(CLI::IsMember({"header", "checksums", "structure", "full"}))
      ->capture_default_str();
  add_json_flag(sub, args->json);
  return {sub, [args] { return run_verify(*args); }};
}

}  // namespace mosb::cli
