#include "mosb/slurm.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mosb/atomic_file.hpp"
#include "mosb/command_template.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/run.hpp"
#include "mosb/version.hpp"
#include "process.hpp"

namespace mosb {

namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
constexpr const char* kRunFile = "run.json";
constexpr const char* kScriptFile = "run.sbatch";
constexpr const char* kJobsFile = "jobs";

std::uint64_t ceil_div(std::uint64_t a, std::uint64_t b) {
  return a / b + (a % b != 0);
}

// A path SLURM's #SBATCH lines and file name patterns take as is.
bool plain_path(const std::string& path) {
  return path.find_first_of(" \t\n\r'\"\\%$`") == std::string::npos;
}

// The output of a program run without a shell; nullopt when it is not in PATH.
std::optional<run_internal::ProgramOutput> capture(const std::vector<std::string>& argv) {
  const std::string program = resolve_executable(argv.front());
  if (program.empty() || ::access(program.c_str(), X_OK) != 0) return std::nullopt;
  return run_internal::run_program(program, argv);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

// The last non-blank line of a program's error output, for a one-line message.
std::string last_line(const std::string& text) {
  const auto lines = lines_of(text);
  return lines.empty() ? std::string("no message") : lines.back();
}

bool all_digits(std::string_view text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::uint64_t slurm_shard_count(std::uint64_t queries, std::optional<std::uint64_t> shards,
                                std::optional<std::uint64_t> queries_per_task) {
  if (shards && queries_per_task)
    throw Error(ErrorCode::invalid_argument, {"give ", setting("shards"), " N or ",
                                              setting("queries_per_task"), " K, not both"});
  if (queries == 0) throw Error(ErrorCode::invalid_argument, "the query set is empty");
  std::uint64_t n = 1;
  if (shards) {
    if (*shards == 0)
      throw Error(ErrorCode::invalid_argument, {setting("shards"), " 0: give at least 1"});
    if (*shards > queries)
      throw Error(ErrorCode::invalid_argument,
                  {setting("shards"), " " + std::to_string(*shards) + ": the query set has only " +
                                          std::to_string(queries) + " queries"});
    n = *shards;
  } else if (queries_per_task) {
    if (*queries_per_task == 0)
      throw Error(ErrorCode::invalid_argument,
                  {setting("queries_per_task"), " 0: give at least 1"});
    n = ceil_div(queries, *queries_per_task);
  } else {
    throw Error(ErrorCode::invalid_argument,
                {"give ", setting("shards"), " N or ", setting("queries_per_task"), " K"});
  }
  if (n > 1000000)
    throw Error(ErrorCode::invalid_argument,
                std::to_string(n) + " shards: more array tasks than SLURM takes");
  return n;
}

std::optional<std::uint64_t> slurm_time_seconds(const SlurmRun& run) {
  if (run.time_limit_seconds <= 0) return std::nullopt;
  const std::uint64_t largest =
      run.largest_shard > 0 ? run.largest_shard : ceil_div(run.queries, run.shards);
  const std::uint64_t rounds = ceil_div(largest, std::max(1u, run.jobs));
  const double per_query = std::ceil(run.time_limit_seconds + run.grace_seconds) + 10;
  const auto seconds = static_cast<std::uint64_t>(static_cast<double>(rounds) * per_query) + 300;
  return ceil_div(seconds, 60) * 60;
}

std::string slurm_time_text(std::uint64_t seconds) {
  char text[64];
  std::snprintf(text, sizeof text, "%llu-%02llu:%02llu:%02llu",
                static_cast<unsigned long long>(seconds / 86400),
                static_cast<unsigned long long>(seconds / 3600 % 24),
                static_cast<unsigned long long>(seconds / 60 % 60),
                static_cast<unsigned long long>(seconds % 60));
  return text;
}

std::optional<std::uint64_t> slurm_memory_mib(const SlurmRun& run) {
  if (run.memory_limit_bytes == 0) return std::nullopt;
  return ceil_div(run.memory_limit_bytes, kMiB) * std::max(1u, run.jobs) + 512;
}

std::string slurm_array_list(const std::vector<std::uint64_t>& shards) {
  std::string text;
  for (std::size_t k = 0; k < shards.size();) {
    std::size_t end = k;
    while (end + 1 < shards.size() && shards[end + 1] == shards[end] + 1) ++end;
    text += (text.empty() ? "" : ",") + std::to_string(shards[k]);
    if (end > k) text += "-" + std::to_string(shards[end]);
    k = end + 1;
  }
  return text;
}

namespace {

// `word` quoted for the shell, "{task}" in it becoming the array task's index ("$shard").
std::string quote_task_word(const std::string& word) {
  static constexpr std::string_view kTask = "{task}";
  std::string text;
  std::size_t from = 0;
  for (std::size_t at = word.find(kTask); at != std::string::npos; at = word.find(kTask, from)) {
    if (at > from) text += shell_quote(word.substr(from, at - from));
    text += "\"$shard\"";
    from = at + kTask.size();
  }
  if (from < word.size() || text.empty()) text += shell_quote(word.substr(from));
  return text;
}

}  // namespace

void describe_run_tasks(SlurmRun& run) {
  run.kind = kRunKind;
  run.task_comment = "# mosb run --slurm (spec/RUN.md section 8): array task i runs shard i of " +
                     std::to_string(run.shards) + "\n# of the " + std::to_string(run.queries) +
                     " queries of query set " + run.query_set + " and writes shard-i.sol here.\n" +
                     "# Resubmit what is missing: mosb run --slurm " + run.directory +
                     " --resume --submit\n";
  run.task_command = {"run"};
  run.task_words = {"--shard", "{task}/" + std::to_string(run.shards), "--resume", "-o",
                    run.directory + "/shard-{task}.sol"};
}

std::string slurm_script(const SlurmRun& run) {
  if (run.task_command.empty())
    throw Error(ErrorCode::invalid_argument, run.directory + ": no command for the array's tasks");
  // The script is shell: a line break in a comment or a directive's value would start a command
  // (a query set or an experiment file named with one). The directives' values are checked where
  // the directory is created.
  for (std::size_t at = 0; at < run.task_comment.size();) {
    const auto end = run.task_comment.find('\n', at);
    if (run.task_comment[at] != '#' || end == std::string::npos ||
        std::any_of(run.task_comment.begin() + static_cast<std::ptrdiff_t>(at),
                    run.task_comment.begin() + static_cast<std::ptrdiff_t>(end),
                    [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
      throw Error(ErrorCode::invalid_argument,
                  run.directory + ": the array's comment is not comment lines: " +
                      shell_quote(run.task_comment.substr(at, end - at)));
    at = end + 1;
  }
  std::ostringstream s;
  const std::string dir = run.directory;
  s << "#!/bin/sh\n" << run.task_comment << "# Written by mosb " << kVersion << ".\n";
  s << "#SBATCH --job-name=mosb-" << run.kind << "\n";
  s << "#SBATCH --array=" << slurm_array_list([&] {
    std::vector<std::uint64_t> all(run.shards);
    for (std::uint64_t i = 0; i < run.shards; ++i) all[i] = i + 1;
    return all;
  }());
  if (run.throttle) s << "%" << run.throttle;
  s << "\n#SBATCH --nodes=1\n#SBATCH --ntasks=1\n";
  s << "#SBATCH --cpus-per-task=" << std::max(1u, run.jobs) * std::max(1u, run.threads) << "\n";
  if (const auto seconds = slurm_time_seconds(run))
    s << "#SBATCH --time=" << slurm_time_text(*seconds) << "\n";
  if (const auto mib = slurm_memory_mib(run)) s << "#SBATCH --mem=" << *mib << "M\n";
  if (!run.account.empty()) s << "#SBATCH --account=" << run.account << "\n";
  if (!run.partition.empty()) s << "#SBATCH --partition=" << run.partition << "\n";
  s << "#SBATCH --output=" << dir << "/shard-%a.log\n";
  s << "#SBATCH --open-mode=append\n";
  s << "set -eu\n";
  s << "cd " << shell_quote(run.working_directory) << "\n";
  s << "shard=\"$SLURM_ARRAY_TASK_ID\"\n";
  s << "exec " << shell_quote(run.mosb);
  for (const auto& a : run.task_command) s << " " << shell_quote(a);
  for (const auto& a : run.run_arguments) s << " " << shell_quote(a);
  for (const auto& a : run.task_words) s << " " << quote_task_word(a);
  s << "\n";
  return s.str();
}

namespace {

nlohmann::json to_json(const SlurmRun& r) {
  return {{"mosb_slurm_run", 1},
          {"kind", r.kind},
          {"largest_shard", r.largest_shard},
          {"mosb", r.mosb},
          {"working_directory", r.working_directory},
          {"run_arguments", r.run_arguments},
          {"instance", r.instance},
          {"instance_digest", r.instance_digest},
          {"view", r.view},
          {"query_set", r.query_set},
          {"objectives", r.objectives},
          {"queries", r.queries},
          {"shards", r.shards},
          {"time_limit_seconds", r.time_limit_seconds},
          {"grace_seconds", r.grace_seconds},
          {"memory_limit_bytes", r.memory_limit_bytes},
          {"jobs", r.jobs},
          {"threads", r.threads},
          {"throttle", r.throttle},
          {"account", r.account},
          {"partition", r.partition},
          {"command", r.task_command}};
}

}  // namespace

void create_slurm_directory(const SlurmRun& run) {
  const fs::path dir(run.directory);
  if (!dir.is_absolute())
    throw Error(ErrorCode::invalid_argument,
                {setting("slurm.directory"), ": not absolute: " + run.directory});
  if (!plain_path(run.directory))
    throw Error(ErrorCode::invalid_argument,
                {setting("slurm.directory"),
                 " " + run.directory +
                     ": SLURM takes no blanks, quotes, backslashes, '$' or '%' in this path; "
                     "choose another directory"});
  for (const auto& [name, value] :
       {std::pair{"slurm.account", &run.account}, {"slurm.partition", &run.partition}})
    if (!plain_path(*value))
      throw Error(ErrorCode::invalid_argument,
                  {setting(name), " " + shell_quote(*value) + ": no blanks, quotes, '$' or '%'"});
  if (fs::exists(dir / kRunFile))
    throw Error(ErrorCode::invalid_argument,
                {(dir / kRunFile).string() + ": the directory holds a run already; continue it (",
                 setting("resume"), ") or choose another directory"});
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(ErrorCode::io, run.directory + ": cannot create: " + ec.message());
  write_file_atomically(dir / kScriptFile, slurm_script(run));
  write_file_atomically(dir / kRunFile, to_json(run).dump(2) + "\n");
}

SlurmRun read_slurm_directory(const std::string& directory, std::string_view kind) {
  const fs::path file = fs::path(directory) / kRunFile;
  if (!fs::exists(file))
    throw Error(ErrorCode::invalid_argument, file.string() + ": no such file; is " + directory +
                                                 " the directory of a mosb job array?");
  try {
    const auto j = nlohmann::json::parse(read_whole_file(file));
    if (j.value("mosb_slurm_run", 0) != 1) throw Error("not the file of a mosb job array");
    SlurmRun r;
    r.directory = fs::absolute(directory).lexically_normal().string();
    while (r.directory.size() > 1 && r.directory.back() == '/') r.directory.pop_back();
    r.kind = j.value("kind", std::string(kRunKind));  // absent before experiments
    if (r.kind.empty()) throw Error("an empty kind");
    r.largest_shard = j.value("largest_shard", std::uint64_t{0});
    r.mosb = j.at("mosb").get<std::string>();
    r.working_directory = j.at("working_directory").get<std::string>();
    r.run_arguments = j.at("run_arguments").get<std::vector<std::string>>();
    r.instance = j.at("instance").get<std::string>();
    r.instance_digest = j.at("instance_digest").get<std::string>();
    r.view = j.at("view").get<std::string>();
    r.query_set = j.at("query_set").get<std::string>();
    r.objectives = j.at("objectives").get<std::vector<std::string>>();
    r.queries = j.at("queries").get<std::uint64_t>();
    r.shards = j.at("shards").get<std::uint64_t>();
    r.time_limit_seconds = j.at("time_limit_seconds").get<double>();
    r.grace_seconds = j.at("grace_seconds").get<double>();
    r.memory_limit_bytes = j.at("memory_limit_bytes").get<std::uint64_t>();
    r.jobs = j.at("jobs").get<unsigned>();
    r.threads = j.at("threads").get<unsigned>();
    r.throttle = j.at("throttle").get<unsigned>();
    r.account = j.at("account").get<std::string>();
    r.partition = j.at("partition").get<std::string>();
    if (r.shards == 0 || r.shards > r.queries) throw Error("shards out of range");
    // Absent from arrays made before it was recorded: a run's is known.
    r.task_command = j.value("command", r.kind == kRunKind ? std::vector<std::string>{"run"}
                                                           : std::vector<std::string>{});
    if (r.kind != kind) {
      std::string made_by;
      for (const auto& word : r.task_command) made_by += " " + word;
      throw Error("a job array of kind '" + r.kind + "'" +
                  (made_by.empty() ? "" : " (made by mosb" + made_by + ")") + ", not of kind '" +
                  std::string(kind) + "'; continue it with the command that made it");
    }
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw Error(ErrorCode::invalid_argument,
                file.string() + ": not the file of a mosb job array (" + e.what() + ")");
  } catch (const Error& e) {
    if (e.code() == ErrorCode::io) throw;
    throw Error(ErrorCode::invalid_argument, file.string() + ": " + e.what());
  }
}

std::string shard_output(const SlurmRun& run, std::uint64_t shard) {
  return run.directory + "/shard-" + std::to_string(shard) + ".sol";
}

std::string_view to_string(ShardFile state) {
  return kShardFileNames.name(state);
}

Resubmission shards_to_resubmit(const std::vector<ShardState>& shards) {
  Resubmission out;
  for (const auto& s : shards)
    if (s.file != ShardFile::done) (s.queued() ? out.queued : out.resubmit).push_back(s.index);
  return out;
}

bool ShardState::queued() const {
  static constexpr std::string_view kActive[] = {
      "PENDING",     "RUNNING",  "CONFIGURING", "COMPLETING", "REQUEUED",  "REQUEUE_HOLD",
      "REQUEUE_FED", "RESIZING", "SUSPENDED",   "STAGE_OUT",  "SIGNALING", "STOPPED"};
  return std::find(std::begin(kActive), std::end(kActive), state) != std::end(kActive);
}

namespace {

// The state of DIR/shard-i.sol (and its journal).
ShardState shard_file_state(const SlurmRun& run, std::uint64_t index) {
  ShardState s;
  s.index = index;
  const Shard shard{index, run.shards};
  s.queries = shard.size(run.queries);
  const std::string path = shard_output(run, index);
  if (!fs::exists(path)) {
    const std::string journal = journal_path(path);
    if (fs::exists(journal)) {
      s.file = ShardFile::partial;
      s.recorded = journaled_queries(journal);
    }
    return s;
  }
  s.file = ShardFile::damaged;
  try {
    const auto r = SolutionReader::open_verified(path);
    std::vector<std::string> objectives;
    for (std::size_t i = 0; i < r.objective_count(); ++i) objectives.push_back(r.objective_name(i));
    const auto recorded_shard = r.metadata().get("solution.solver.param.run.shard");
    if (r.instance_digest() != run.instance_digest || r.view_name() != run.view ||
        r.query_set() != run.query_set || r.query_count() != run.queries ||
        objectives != run.objectives) {
      s.problem = "bound to another instance, view or query set than run.json";
    } else if (recorded_shard != shard.text()) {
      s.problem = "is shard " + recorded_shard.value_or("(none)") + ", not " + shard.text();
    } else {
      for (std::uint64_t q = index - 1; q < run.queries; q += run.shards) ++s.counts[r.status(q)];
      s.recorded = s.queries - s.counts[QueryStatus::not_run];
      if (s.recorded == s.queries)
        s.file = ShardFile::done;
      else
        s.problem = std::to_string(s.queries - s.recorded) + " of its queries are not-run";
    }
  } catch (const Error& e) {
    s.problem = e.what();
  }
  return s;
}

// Array task "JOBID_i" → i, when JOBID is `job`.
std::optional<std::uint64_t> task_index(const std::string& id, const std::string& job) {
  if (id.size() <= job.size() + 1 || id.compare(0, job.size(), job) != 0 || id[job.size()] != '_')
    return std::nullopt;
  const auto index = id.substr(job.size() + 1);
  if (!all_digits(index) || index.size() > 9) return std::nullopt;
  return std::stoull(index);
}

}  // namespace

SlurmStatus slurm_status(const SlurmRun& run,
                         const std::function<ShardState(std::uint64_t)>& file_state) {
  SlurmStatus status;
  for (std::uint64_t i = 1; i <= run.shards; ++i)
    status.shards.push_back(file_state ? file_state(i) : shard_file_state(run, i));
  const fs::path jobs_file = fs::path(run.directory) / kJobsFile;
  if (fs::exists(jobs_file))
    for (const auto& line : lines_of(read_whole_file(jobs_file))) {
      const auto id = line.substr(0, line.find(';'));  // --parsable: JOBID[;CLUSTER]
      if (all_digits(id)) status.jobs.push_back(id);
    }
  if (status.jobs.empty()) return status;
  // Later submissions win; for one submission squeue (live) wins over sacct.
  auto set = [&](std::uint64_t index, const std::string& job, const std::string& state) {
    if (index < 1 || index > run.shards) return;
    auto& shard = status.shards[index - 1];
    shard.job = job + "_" + std::to_string(index);
    shard.state = state.substr(0, state.find(' '));  // "CANCELLED by 0"
  };
  std::string list;
  for (const auto& job : status.jobs) list += (list.empty() ? "" : ",") + job;
  std::map<std::string, std::vector<std::pair<std::uint64_t, std::string>>> from_sacct;
  if (const auto sacct = capture({"sacct", "-n", "-P", "-X", "-j", list, "-o", "JobID,State"});
      sacct && sacct->status == 0) {
    status.sources.emplace_back("sacct");
    for (const auto& line : lines_of(sacct->out)) {
      const auto bar = line.find('|');
      if (bar == std::string::npos) continue;
      const auto id = line.substr(0, bar);
      const auto job = id.substr(0, id.find('_'));
      if (const auto index = task_index(id, job))
        from_sacct[job].emplace_back(*index, line.substr(bar + 1));
    }
  }
  bool squeue_answered = false;
  for (const auto& job : status.jobs) {
    for (const auto& [index, state] : from_sacct[job]) set(index, job, state);
    // One call per job: squeue refuses the whole list once one job has left its memory.
    const auto squeue = capture({"squeue", "-h", "-r", "-t", "all", "-j", job, "-o", "%i|%T"});
    if (!squeue) break;
    if (squeue->status != 0) {
      if (squeue->err.find("Invalid job id") != std::string::npos) continue;  // forgotten job
      break;  // no controller: asking about the next job would wait as long again
    }
    squeue_answered = true;
    for (const auto& line : lines_of(squeue->out)) {
      const auto bar = line.find('|');
      if (bar == std::string::npos) continue;
      if (const auto index = task_index(line.substr(0, bar), job))
        set(*index, job, line.substr(bar + 1));
    }
  }
  if (squeue_answered) status.sources.emplace_back("squeue");
  return status;
}

std::vector<std::string> sbatch_arguments(const SlurmRun& run,
                                          const std::vector<std::uint64_t>& shards) {
  std::vector<std::string> argv = {"sbatch", "--parsable"};
  if (shards.size() != run.shards)
    argv.push_back("--array=" + slurm_array_list(shards) +
                   (run.throttle ? "%" + std::to_string(run.throttle) : ""));
  argv.push_back(run.directory + "/" + kScriptFile);
  return argv;
}

std::string sbatch_command_text(const SlurmRun& run, const std::vector<std::uint64_t>& shards) {
  std::string text;
  for (const auto& word : sbatch_arguments(run, shards))
    text += (text.empty() ? "" : " ") + shell_quote(word);
  return text + " >> " + shell_quote(run.directory + "/" + kJobsFile);
}

std::string submit_shards(const SlurmRun& run, const std::vector<std::uint64_t>& shards) {
  const auto done = capture(sbatch_arguments(run, shards));
  if (!done) throw Error(ErrorCode::io, "sbatch: no such program in PATH (is SLURM installed?)");
  if (done->status != 0) {
    std::string message = last_line(done->err);
    if (message.starts_with("sbatch: ")) message.erase(0, 8);  // sbatch names itself
    throw Error(ErrorCode::io, "sbatch: " + message);
  }
  const auto lines = lines_of(done->out);
  std::string id = lines.empty() ? "" : lines.back().substr(0, lines.back().find(';'));
  if (!all_digits(id))
    throw Error(ErrorCode::io, "sbatch: printed no job id (" + last_line(done->out) + ")");
  const fs::path jobs = fs::path(run.directory) / kJobsFile;
  std::ofstream out(jobs, std::ios::app);
  out << id << "\n";
  out.flush();
  if (!out) throw Error(ErrorCode::io, jobs.string() + ": cannot append the job id " + id);
  return id;
}

SlurmRun slurm_run_here(const std::string& directory) {
  SlurmRun run;
  run.directory = fs::absolute(directory).lexically_normal().string();
  while (run.directory.size() > 1 && run.directory.back() == '/') run.directory.pop_back();
  std::error_code ec;
  run.mosb = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) throw Error(ErrorCode::io, "/proc/self/exe: cannot read: " + ec.message());
  run.working_directory = fs::current_path().string();
  return run;
}

SlurmRun plan_slurm_run(const RunConfig& config, const SlurmRequest& request) {
  const auto& instance = *config.instance;
  const View selection = solution_selection(instance, config.choice);
  template_executable(config.solver_template);  // checked before DIR is written
  SlurmRun run = slurm_run_here(request.directory);
  run.instance = fs::absolute(config.instance_path).lexically_normal().string();
  run.instance_digest = instance.digest();
  run.view = selection.name;
  run.query_set = selection.query_set;
  for (const auto i : selection.objectives) run.objectives.push_back(instance.objective(i).name);
  run.queries = instance.queries(selection.query_set).size();
  run.shards = slurm_shard_count(run.queries, request.shards, request.queries_per_task);
  run.time_limit_seconds = config.limits.wall_seconds;
  run.grace_seconds = config.limits.grace_seconds;
  run.memory_limit_bytes = config.limits.memory_bytes;
  run.jobs = config.jobs;
  run.threads = config.threads;
  run.throttle = request.throttle;
  run.account = request.account;
  run.partition = request.partition;
  run.run_arguments.push_back(run.instance);
  run.run_arguments.insert(run.run_arguments.end(), request.run_options.begin(),
                           request.run_options.end());
  describe_run_tasks(run);
  return run;
}

}  // namespace mosb
