#include "commands.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>
#include <utility>

#include "graph_output.hpp"
#include "json_writer.hpp"
#include "mosb/converters/movingai.hpp"
#include "mosb/converters/suite.hpp"
#include "mosb/eval.hpp"
#include "mosb/experiment.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pull.hpp"
#include "mosb/run.hpp"

namespace mosb::cli {

Command group(CLI::App* parent, std::vector<Command> children) {
  parent->require_subcommand(1);
  return {parent, [children = std::move(children)] {
            for (const auto& child : children)
              if (child.subcommand->parsed()) return child.run();
            return 1;
          }};
}

CLI::Validator unsigned_integer(std::uint64_t max) {
  return {[max](std::string& text) -> std::string {
            const bool digits =
                !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
            if (!digits) return "'" + text + "' is not an unsigned integer (decimal digits only)";
            std::uint64_t value = 0;
            const auto [end, error] =
                std::from_chars(text.data(), text.data() + text.size(), value);
            if (error != std::errc{} || end != text.data() + text.size() || value > max)
              return "'" + text + "' is above the largest allowed value " + std::to_string(max);
            return {};
          },
          "UINT", "unsigned integer"};
}

CLI::Validator duration() {
  return {[](std::string& text) -> std::string {
            return parse_duration(text) ? "" : "not a duration (60, 60s, 500ms, 2m, 1h)";
          },
          "DURATION", "duration"};
}

CLI::Validator reference_source() {
  return {[](std::string& text) -> std::string {
            if (is_store_url(text)) return {};
            return CLI::ExistingPath(text);
          },
          "PATH|URL", "path or URL"};
}

CLI::Validator memory_size() {
  return {[](std::string& text) -> std::string {
            const auto bytes = parse_memory_size(text);
            if (!bytes) return "'" + text + "' is not a size (bytes, or 512M, 4G: powers of 1024)";
            text = std::to_string(*bytes);
            return {};
          },
          "SIZE", "memory size"};
}

CLI::Option* add_isolation_option(CLI::App* subcommand, std::string& isolation) {
  const char* from_environment = std::getenv("MOSB_ISOLATION");
  isolation = from_environment != nullptr && *from_environment != '\0' ? from_environment : "seal";
  return subcommand
      ->add_option("--isolation", isolation,
                   "seal (default, or $MOSB_ISOLATION): each query sees the filesystem read-only "
                   "but its own directory, a private /dev/shm and loopback alone, without "
                   "capabilities (spec/RUN.md section 4.1); none: the whole filesystem and "
                   "network, recorded as run.seal = none")
      ->check(CLI::IsMember(kSealNames.names()));
}

Seal parse_isolation(const std::string& isolation) {
  const auto seal = kSealNames.parse(isolation);
  if (!seal)
    throw UsageError("MOSB_ISOLATION=" + isolation + ": give one of " + kSealNames.choices_text());
  return *seal;
}

CLI::Option* add_measurement_option(CLI::App* subcommand, std::string& measurement) {
  measurement = "auto";
  auto names = kMeasurementNames.names();
  names.insert(names.begin(), "auto");
  return subcommand
      ->add_option("--measurement", measurement,
                   "auto (default: the first that works), " + kMeasurementNames.choices_text() +
                       ": how memory is limited and measured")
      ->check(CLI::IsMember(names));
}

std::optional<Measurement> chosen_measurement(const std::string& measurement) {
  return measurement == "auto" ? std::nullopt : parse_measurement(measurement);
}

namespace {
std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void request_stop(int) {
  g_stop.store(true);
}
}  // namespace

const std::atomic<bool>& install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signal, &action, nullptr);
  ::signal(SIGPIPE, SIG_IGN);
  return g_stop;
}

CLI::Option* add_slurm_options(CLI::App* subcommand, SlurmArgs& slurm, const SlurmHelp& help) {
  subcommand->add_option("--slurm", slurm.directory, help.slurm)->option_text("DIR");
  auto* queries_per_task =
      subcommand->add_option("--queries-per-task", slurm.queries_per_task, help.queries_per_task)
          ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()));
  subcommand
      ->add_option("--throttle", slurm.throttle,
                   "with --slurm: at most K tasks at once (the array's %K; default no limit)")
      ->check(unsigned_integer(1000000));
  subcommand->add_option("--account", slurm.account, "with --slurm: sbatch --account")
      ->check(printable_text());
  subcommand->add_option("--partition", slurm.partition, "with --slurm: sbatch --partition")
      ->check(printable_text());
  subcommand->add_flag("--submit", slurm.submit,
                       "with --slurm: submit with sbatch (else the sbatch command is printed)");
  subcommand->add_flag("--status", slurm.status, help.status);
  return queries_per_task;
}

CLI::Validator non_negative_real() {
  return {[](std::string& text) -> std::string {
            double value = 0;
            const auto [end, error] =
                std::from_chars(text.data(), text.data() + text.size(), value);
            if (text.empty() || error == std::errc::invalid_argument ||
                end != text.data() + text.size())
              return "'" + text + "' is not a number";
            if (error != std::errc{} || !std::isfinite(value))
              return "'" + text + "' is not finite";
            if (value < 0 || text.front() == '-') return "'" + text + "' is negative";
            return {};
          },
          "REAL", "non-negative real"};
}

std::string flag_of_setting(std::string_view setting) {
  static constexpr std::pair<std::string_view, std::string_view> kFlags[] = {
      {"view", "--view"},
      {"objectives", "--objectives"},
      {"queries", "--queries"},
      {"solver_template", "--solver"},
      {"solver_name", "--solver-name"},
      {"solver_version", "--solver-version"},
      {"shard", "--shard"},
      {"resume", "--resume"},
      {"allow_new_executable", "--allow-new-executable"},
      {"shards", "--shards"},
      {"queries_per_task", "--queries-per-task"},
      {"slurm.directory", "--slurm"},
      {"slurm.account", "--account"},
      {"slurm.partition", "--partition"},
      {"by_kind", "--by-kind"},
      {"prefer", "--prefer"},
      {"expect_digest", "--expect-digest"},
      {"max_memory", "--max-memory"},
      {"streaming_verify.disk", "--check-disk"},
      {"streaming_verify.memory", "--check-memory"},
      {"objective", "--objective"},
      {"exposure_file", "--exposure"},
      {"guards_file", "--guards"},
      {"cost_count", "--costs"},
      {"extract_bfs.count", "--count"},
      {"ignore_extra_fields", "--ignore-extra-fields"},
      {"id_base", "--id-base"},
      {"scale", "--scale"},
      {"columns", "--columns"},
      {"dominated", "--nondominated"},
      {"suite.benchmarks", "--benchmark"},
      {"replace", "--replace"},
      {"vertices_from_ids", "--vertices-from-ids"},
      {"vertex_file", "--vertices"},
      {"gr_files", "--gr"},
      {"graphml_file", "--graphml"},
      {"clearance", "--clearance"},
      {"weight", "--weight"},
      {"delta", "--delta"},
      {"profile", "--profile"},
      {"export_cache", "--export-cache"},
      {"scenario", "--scen"},
      {"match", "--match"},
      {"allow_same", "--allow-same"},
  };
  for (const auto& [name, flag] : kFlags)
    if (name == setting) return std::string(flag);
  return std::string(setting);
}

std::string error_text(const Message& message) {
  return message_text(message, flag_of_setting);
}

std::string error_text(const Error& error) {
  return error_text(error.parts());
}

CLI::Validator epsilon_value() {
  return {[](std::string& text) -> std::string {
            try {
              parse_epsilon(text);
            } catch (const Error& e) {
              return e.what();
            }
            return {};
          },
          "EPS", "epsilon"};
}

CLI::Validator printable_text() {
  return {[](std::string& text) -> std::string {
            for (const char c : text)
              if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
                return "control character " +
                       std::to_string(static_cast<unsigned>(static_cast<unsigned char>(c))) +
                       " in the text (no newline, tab or escape)";
            return {};
          },
          "TEXT", "printable text"};
}

void add_json_flag(CLI::App* subcommand, bool& json) {
  subcommand->add_flag("--json", json, "print the report as one JSON object on stdout");
}

namespace {
constexpr std::string_view kSizeUnits = " (bytes, or 512M, 4G: powers of 1024)";

// A memory size in bytes, or with a suffix (512M, 4G: powers of 1024).
CLI::Option* add_memory_size_option(CLI::App* subcommand, const std::string& name,
                                    std::uint64_t& bytes, const std::string& what) {
  return subcommand->add_option(name, bytes, what + std::string(kSizeUnits))
      ->transform(memory_size())
      ->capture_default_str();
}
}  // namespace

CLI::Option* add_max_memory_option(CLI::App* subcommand, std::uint64_t& max_memory) {
  return add_memory_size_option(
      subcommand, "--max-memory", max_memory,
      "the most memory decoding a packed file may take; 0: the memory available");
}

CLI::Option* add_check_memory_option(CLI::App* subcommand, std::uint64_t& check_memory) {
  return add_memory_size_option(subcommand, "--check-memory", check_memory,
                                "the working memory of each file's check, whatever the file's "
                                "size: more spills to a temporary file in the store")
      ->check(CLI::Range(std::uint64_t{4096}, UINT64_MAX));
}

CLI::Option* add_check_disk_option(CLI::App* subcommand, std::optional<std::uint64_t>& check_disk) {
  return subcommand
      ->add_option_function<std::uint64_t>(
          "--check-disk", [&check_disk](const std::uint64_t& bytes) { check_disk = bytes; },
          "the most disk each file's check may spill to (a file whose check needs more is "
          "refused before it spills); default: " +
              std::to_string(kCheckDiskPerFileByte) + " times the file's size or " +
              std::to_string(kCheckDiskPerMemoryByte) + " times --check-memory, whichever is more" +
              std::string(kSizeUnits))
      ->transform(memory_size());
}

CLI::Option* add_id_base_option(CLI::App* subcommand, unsigned& id_base,
                                const std::string& default_text) {
  return subcommand
      ->add_option(
          "--id-base", id_base,
          "0 or 1: the id of the first vertex in the text files (default: " + default_text + ")")
      ->check(unsigned_integer(std::numeric_limits<unsigned>::max()))
      ->check(CLI::IsMember({0u, 1u}));
}

void add_instance_id_base_options(CLI::App* subcommand, InstanceIdBase& id_base,
                                  const std::string& default_text) {
  id_base.option = add_id_base_option(subcommand, id_base.value, default_text);
  subcommand
      ->add_flag("--force-id-base", id_base.force,
                 "use --id-base even where it contradicts the instance's metadata id_base")
      ->needs(id_base.option);
}

std::optional<unsigned> InstanceIdBase::checked(const GraphReader& instance) const {
  if (option == nullptr || option->count() == 0) return std::nullopt;
  const auto recorded = instance.metadata().get("id_base");
  if (recorded && *recorded != std::to_string(value) && !force)
    throw UsageError("--id-base " + std::to_string(value) + " contradicts " +
                     instance.display_name() + ", whose metadata records id_base " + *recorded +
                     " (every vertex id would be off by one); pass --force-id-base if meant");
  return value;
}

CLI::Option* add_seed_option(CLI::App* subcommand, std::uint64_t& seed, const std::string& what) {
  seed = 1;
  return subcommand->add_option("--seed", seed, what + " (default 1)")
      ->check(unsigned_integer(std::numeric_limits<std::uint64_t>::max()));
}

CLI::Option* add_output_option(CLI::App* subcommand, std::string& output, const std::string& what) {
  return subcommand->add_option("-o,--output", output, what);
}

CLI::Option* add_expect_digest_option(CLI::App* subcommand, std::string& digest) {
  return subcommand
      ->add_option("--expect-digest", digest,
                   "fail, writing nothing, unless the output's content digest is D")
      ->option_text("D")
      ->transform([](std::string value) {
        for (auto& c : value)
          if (c >= 'A' && c <= 'F') c = static_cast<char>(c - 'A' + 'a');
        const bool hex =
            value.size() == 32 && value.find_first_not_of("0123456789abcdef") == std::string::npos;
        if (!hex) throw CLI::ValidationError("a content digest is 32 hex digits");
        return value;
      });
}

CLI::Option* add_graph_output_options(CLI::App* subcommand, GraphOutput& output) {
  auto* file = add_output_option(subcommand, output.file, "the .mosb file to write");
  add_view_spec_option(subcommand, output.views);
  add_expect_digest_option(subcommand, output.expect_digest);
  add_json_flag(subcommand, output.json);
  return file;
}

int report_written(const std::string& path, bool json) {
  // Header and table only (counts, digest): no payload is read, so the plain open checks suffice.
  const auto reader = GraphReader::open(path);
  if (json) {
    JsonWriter out(std::cout);
    out.begin_object();
    out.key("file").value(path);
    out.key("vertices").value(reader.vertex_count());
    out.key("arcs").value(reader.arc_count());
    out.key("objectives").value(std::uint64_t{reader.objective_count()});
    out.key("digest").value(reader.digest());
    out.end_object();
    return 0;
  }
  std::cout << "wrote " << escape_for_terminal(path) << ": " << reader.vertex_count()
            << " vertices, " << reader.arc_count() << " arcs, " << reader.objective_count()
            << " objectives, digest " << reader.digest() << '\n';
  return 0;
}

std::optional<PackOptions> suite_pack(bool pack) {
  return pack ? std::optional<PackOptions>(PackOptions{}) : std::nullopt;
}

CLI::Option* add_suite_pack_flag(CLI::App* sub, bool& pack) {
  return sub->add_flag("--pack", pack,
                       "pack each suite file at zstd level " + std::to_string(PackOptions{}.level) +
                           " (as mosb pack does); the MANIFEST lists the packed files");
}

int report_suite(const std::string& directory, const std::string& family,
                 const std::vector<converters::SuiteEntry>& entries, bool json,
                 const std::function<void(JsonWriter&)>& more) {
  if (!json) {
    const auto kept = std::count_if(entries.begin(), entries.end(),
                                    [](const converters::SuiteEntry& e) { return e.kept; });
    std::cout << "wrote " << entries.size() - kept << ' ' << family << " instances"
              << (kept > 0 ? " (kept " + std::to_string(kept) + " listed before)" : std::string())
              << " and MANIFEST to " << escape_for_terminal(directory) << '\n';
    return 0;
  }
  JsonWriter out(std::cout);
  out.begin_object();
  out.key("directory").value(directory);
  out.key("instances").begin_array();
  for (const auto& e : entries) {
    out.begin_object();
    out.key("name").value(e.name);
    out.key("file").value(e.file);
    out.key("size").value(e.size);
    out.key("digest").value(e.digest);
    out.key("kept").value(e.kept);
    out.end_object();
  }
  out.end_array();
  if (more) more(out);
  out.end_object();
  return 0;
}

Command add_convert(CLI::App& app) {
  auto* convert = app.add_subcommand("convert", "Convert a benchmark from its source format");
#define MOSB_ADD_CONVERT(name) add_convert_##name(*convert),
  return group(convert, {MOSB_CONVERT_FAMILIES(MOSB_ADD_CONVERT)});
#undef MOSB_ADD_CONVERT
}

Command add_generate(CLI::App& app) {
  auto* generate = app.add_subcommand("generate", "Generate a synthetic benchmark instance");
  return group(generate, {add_generate_grid(*generate), add_generate_netmaker(*generate)});
}

CLI::Option* add_view_spec_option(CLI::App* subcommand, std::vector<std::string>& specs) {
  return subcommand
      ->add_option("--view", specs,
                   "NAME=OBJ1,OBJ2,...[@QUERYSET]: a benchmark over some columns, besides the "
                   "family's default views (repeatable; a default view's name replaces it)")
      // A malformed value is a usage error (exit 2), found before any input is read.
      ->check(CLI::Validator(
          [](const std::string& text) {
            try {
              parse_view_spec(text);
              return std::string();
            } catch (const Error& e) {
              return error_text(e);
            }
          },
          "NAME=OBJ1,OBJ2,...[@QUERYSET]"));
}

void add_view_choice_options(CLI::App* subcommand, ViewChoice& choice, const std::string& what) {
  auto* view = subcommand->add_option("--view", choice.view,
                                      what + ": those of this view (and its query set)");
  auto* objectives = subcommand
                         ->add_option_function<std::string>(
                             "--objectives",
                             [&choice](const std::string& text) {
                               try {
                                 choice.objectives = parse_objective_list(text);
                               } catch (const Error& e) {
                                 throw CLI::ValidationError(error_text(e));
                               }
                             },
                             "these objectives, in this order, instead of a view's")
                         ->option_text("A,B,...");
  view->excludes(objectives);
  subcommand->add_option("--queries", choice.queries,
                         "the query set (default: the view's); with --objectives, a view's "
                         "objective list and query set need no view in the instance");
}

converters::TerrainRules TerrainOptions::rules() const {
  return {.swamp_passable = swamp == "passable", .water_passable = water == "passable"};
}

void add_terrain_options(CLI::App* subcommand, TerrainOptions& terrain) {
  subcommand->add_option("--swamp", terrain.swamp, "terrain 'S'")
      ->check(CLI::IsMember({"passable", "blocked"}))
      ->capture_default_str();
  subcommand->add_option("--water", terrain.water, "terrain 'W'")
      ->check(CLI::IsMember({"passable", "blocked"}))
      ->capture_default_str();
}

std::string status_counts_text(const StatusCounts& counts, bool nonzero) {
  std::string text;
  for (const auto status : kQueryStatuses)
    if (!nonzero || counts[status] != 0)
      text += (text.empty() ? "" : ", ") + std::to_string(counts[status]) + " " +
              std::string(to_string(status));
  return text;
}

void json_status_counts(JsonWriter& json, const StatusCounts& counts) {
  json.begin_object();
  for (const auto status : kQueryStatuses) json.key(to_string(status)).value(counts[status]);
  json.end_object();
}

void json_distribution(JsonWriter& json, const std::optional<Distribution>& d, bool with_min,
                       bool runtime) {
  if (!d) {
    json.null();
    return;
  }
  json.begin_object().key("count").value(d->count);
  if (with_min) json.key("min").value(d->min);
  json.key("median").value(d->median).key("mean").value(d->mean).key("max").value(d->max);
  if (runtime) json.key("shifted_geometric_mean").value(d->shifted_geometric_mean);
  json.end_object();
}

std::string distribution_text(const std::optional<Distribution>& d, const char* unit,
                              bool with_min) {
  if (!d) return "none";
  std::ostringstream out;
  if (with_min) out << "min " << d->min << unit << ", ";
  out << "median " << d->median << unit << ", mean " << d->mean << unit << ", max " << d->max
      << unit;
  return out.str();
}

std::vector<Ratio> parse_epsilons(const std::string& list) {
  std::vector<Ratio> result;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      result.push_back(parse_epsilon(item));
    } catch (const Error& e) {
      throw UsageError("--eps: '" + item + "': " + e.what());
    }
  }
  if (result.empty()) throw UsageError("--eps: no ε given");
  return result;
}

std::vector<std::filesystem::path> experiment_result_files(const std::filesystem::path& path) {
  std::vector<std::string> left_out;
  auto files = result_files(path, &left_out);
  if (!left_out.empty()) {
    std::string ids;
    for (const auto& id : left_out) ids += (ids.empty() ? "" : ", ") + id;
    std::cerr << "mosb: warning: " << escape_for_terminal(path.string()) << ": " << left_out.size()
              << " finished cells no longer in the experiment, left out: "
              << escape_for_terminal(ids) << '\n';
  }
  return files;
}

std::vector<std::filesystem::path> reference_files_of(const std::string& source,
                                                      std::span<const GraphReader> instances) {
  std::set<std::string> digests;
  for (const auto& instance : instances) digests.insert(instance.digest());
  std::filesystem::path local = source;
  if (is_store_url(source)) {
    local = store_cache(source);
    PullOptions options;
    options.references_of = digests;
    const auto pulled = pull(local, source, options);
    std::size_t fetched = 0;
    for (const auto& e : pulled.entries) {
      if (e.status == PullStatus::refused)
        throw Error(ErrorCode::damaged,
                    source + ": refused " + e.entry.file + ": " + error_text(e.reason));
      fetched += e.status == PullStatus::fetched ? 1 : 0;
    }
    if (fetched > 0)
      std::cerr << "mosb: note: pulled " << fetched << " files (" << pulled.bytes << " bytes) of "
                << escape_for_terminal(source) << " into " << escape_for_terminal(local.string())
                << '\n';
  }
  auto found = reference_files_for(local, digests);
  for (const auto& digest : found.missing) {
    std::string name = digest;
    for (const auto& instance : instances)
      if (instance.digest() == digest) name = instance.display_name() + " (digest " + digest + ")";
    std::cerr << "mosb: note: " << escape_for_terminal(source) << " has no reference for "
              << escape_for_terminal(name) << '\n';
  }
  return std::move(found.files);
}

int no_query_completed(const StatusCounts& counts, const FailureReasons& failures) {
  const auto ran = counts.total() - counts[QueryStatus::not_run];
  if (ran == 0 || counts.completed() > 0) return 0;
  std::cerr << "mosb: no query completed (" << status_counts_text(counts, true) << ")";
  if (const auto most = most_common_failure(failures))
    std::cerr << "; most often, " << most->second << " of " << ran << ": "
              << escape_for_terminal(most->first);
  std::cerr << '\n';
  return 3;
}

}  // namespace mosb::cli
