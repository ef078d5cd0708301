#include "mosb/report/release.hpp"

#include <algorithm>
#include <set>
#include <sstream>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/experiment.hpp"
#include "mosb/report/report.hpp"
#include "mosb/report/tables.hpp"
#include "mosb/solution_summary.hpp"
#include "mosb/store.hpp"
#include "mosb/version.hpp"

namespace mosb::pages {

namespace {

namespace fs = std::filesystem;

// Refuses, before anything is written, a reference that is approximate or answers no instance
// of the experiment.
void check_references(const std::vector<SolutionReader>& references,
                      const std::vector<GraphReader>& instances) {
  for (const auto& r : references) {
    if (const auto epsilon = r.solver().epsilon; epsilon != "0")
      throw Error(ErrorCode::invalid_argument,
                  r.display_name() + ": claims epsilon " + epsilon +
                      "; a release holds exact references (epsilon 0) only");
    if (std::none_of(instances.begin(), instances.end(),
                     [&](const GraphReader& i) { return i.digest() == r.instance_digest(); }))
      throw Error(ErrorCode::invalid_argument, r.display_name() + ": fronts of instance " +
                                                   r.instance_digest() +
                                                   ", which the experiment did not run");
  }
}

// The reference's protocol as its files say it: the solvers that agreed, whose statistics it
// carries, and the machine (from the first file that names each).
struct ReferenceProtocol {
  std::string solvers, statistics_of, machine;
};

ReferenceProtocol reference_protocol(const std::vector<SolutionReader>& references) {
  ReferenceProtocol out;
  for (const auto& r : references) {
    const auto info = r.solver();
    const auto param = [&](const char* key) {
      const auto it = info.parameters.find(key);
      return it == info.parameters.end() ? std::string() : it->second;
    };
    if (out.solvers.empty())
      for (const auto& solver : front_solvers(r))
        out.solvers += (out.solvers.empty() ? "" : ", ") + solver;
    if (out.statistics_of.empty()) out.statistics_of = param("statistics");
    if (out.machine.empty()) out.machine = info.machine;
  }
  return out;
}

std::string readme(const RecordedRun& run, const ReferenceProtocol& reference,
                   const Release& release, std::size_t instance_count) {
  std::ostringstream out;
  const auto name = run.name.empty() ? std::string("experiment") : run.name;
  out << "# " << name << ": instances and reference fronts\n\n"
      << "Released with `mosb suite release` (mosb " << kVersion << ") from the results of the "
      << "experiment `" << name << "`"
      << (run.file.empty() ? "" : " (" + fs::path(run.file).filename().string() + ")") << ".\n\n"
      << "## Protocol\n\n";
  if (!run.limits.empty()) out << "- Limits per query: `" << run.limits << "`.\n";
  for (const auto& s : run.solvers)
    out << "- Solver `" << s.name << "`: `" << s.binding << "`"
        << (s.executable_sha256.empty() ? "" : ", executable SHA-256 " + s.executable_sha256)
        << ".\n";
  out << "- References: the fronts of the exact solvers "
      << (reference.solvers.empty() ? std::string("named in each file") : reference.solvers)
      << " where they agree (`mosb solutions reference`)";
  if (!reference.statistics_of.empty())
    out << ", with the per-query statistics of " << reference.statistics_of
        << " (runtime, expanded and generated nodes, peak memory) for every query it completed; "
           "a query that timed out is marked so, without counters";
  out << ".\n";
  if (!reference.machine.empty()) out << "- Machine: " << reference.machine << ".\n";
  std::size_t references = 0;
  bool references_packed = false;
  for (const auto& e : release.entries) {
    references += e.solutions ? 1 : 0;
    references_packed |= e.solutions && e.packed;
  }
  out << "\n## Contents\n\n"
      << "- " << instance_count << " instances (`.mosb`, packed) and " << references
      << " reference files (`.sol`" << (references_packed ? ", packed" : "")
      << "), listed with their sizes, SHA-256 and content digests in `MANIFEST`; each reference "
         "is bound to its instance by content digest. `mosb unpack` restores a packed file's "
         "exact bytes.\n"
      << "- `" << kStoreSummary
      << "`: per benchmark, the suite table (the paper's Table 1) over these references.\n";
  if (!release.without_reference.empty()) {
    out << "- Instances without a reference:";
    for (const auto& file : release.without_reference) out << " `" << file << "`";
    out << ".\n";
  }
  out << "\n## Use\n\n"
      << "    mosb store pull DIR URL          # every byte checked against MANIFEST\n"
      << "    mosb store verify DIR            # instances, references and their bindings\n"
      << "    mosb eval RESULTS --reference DIR   # a solver's experiment against the references\n";
  return out.str();
}

}  // namespace

Release release_suite(const fs::path& results, const fs::path& references, const fs::path& store,
                      const ReleaseOptions& options) {
  std::error_code ec;
  if (fs::exists(store, ec) && !fs::is_empty(store, ec))
    throw Error(ErrorCode::invalid_argument,
                store.string() +
                    ": exists and is not empty; a release is written into a new "
                    "directory, so that the same inputs give the same bytes");
  const auto instance_paths = result_instances(results);
  const auto reference_paths = reference_files(references);
  std::vector<GraphReader> instances;
  instances.reserve(instance_paths.size());
  for (const auto& path : instance_paths) instances.push_back(load(path, VerifyLevel::full));
  const auto readers = open_verified_all(reference_paths);
  check_references(readers, instances);

  // The summary first: make_report's checks (one reference per binding) refuse before the store
  // is made.
  ReportOptions report_options;
  report_options.views = result_views(results);
  const auto report = make_report(instances, {}, readers, report_options);
  std::ostringstream summary;
  tables::write_csv(summary, report.suite);

  auto made = Store::init(store);
  Store::AddOptions add;
  add.pack = options.pack;
  add.progress = options.progress;
  made.add(instance_paths, add);
  if (!options.pack_references) add.pack.reset();
  Release release;
  made.add(reference_paths, add);
  release.entries = Store::open(store).manifest().entries;
  std::set<std::string> bound;
  for (const auto& r : readers) bound.insert(r.instance_digest());
  for (std::size_t i = 0; i < instances.size(); ++i)
    if (!bound.contains(instances[i].digest()))
      release.without_reference.push_back(instance_paths[i].filename().string());
  write_file_atomically(store / kStoreSummary, summary.str());
  write_file_atomically(
      store / kStoreReadme,
      readme(recorded_run(results), reference_protocol(readers), release, instances.size()));
  return release;
}

}  // namespace mosb::pages
