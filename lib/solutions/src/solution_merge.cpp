#include "mosb/solution_merge.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "mosb/atomic_file.hpp"

namespace mosb {

namespace {

constexpr std::string_view kLenient[] = {
    "run.executable",         "run.jobs",         "run.measurement",
    "run.measurement.detail", "run.mosb_version", "run.pin",
};
constexpr std::string_view kShardKey = "run.shard";
constexpr std::string_view kShardsKey = "run.shards";

bool lenient(std::string_view key) {
  return std::find(std::begin(kLenient), std::end(kLenient), key) != std::end(kLenient);
}

std::string quoted(const std::optional<std::string>& value) {
  return value ? "'" + *value + "'" : "(none)";
}

std::string objectives_of(const SolutionReader& r) {
  std::string text;
  for (std::size_t i = 0; i < r.objective_count(); ++i)
    text += (i ? "," : "") + r.objective_name(i) + " (" +
            std::string(format::to_string(r.objective_type(i))) + ")";
  return text;
}

// The metadata's run.shard, nullopt without one; throws when it is malformed.
std::optional<Shard> shard_of(const SolutionReader& r, const std::string& name) {
  const auto text = r.metadata().get("solution.solver.param." + std::string(kShardKey));
  if (!text) return std::nullopt;
  const auto shard = parse_shard(*text);
  if (!shard)
    throw SolutionMergeConflict(name + ": solution.solver.param.run.shard '" + *text +
                                "' is not i/N with 1 <= i <= N");
  return shard;
}

// Every distinct value, sorted, joined by " | ".
std::string joined(const std::set<std::string>& values) {
  std::string text;
  for (const auto& v : values) text += (text.empty() ? "" : " | ") + v;
  return text;
}

}  // namespace

std::optional<Shard> parse_shard(std::string_view text) {
  const auto slash = text.find('/');
  if (slash == std::string_view::npos) return std::nullopt;
  const auto number = [](std::string_view digits) -> std::optional<std::uint64_t> {
    if (digits.empty() || digits.size() > 9) return std::nullopt;
    std::uint64_t value = 0;
    for (const char c : digits) {
      if (c < '0' || c > '9') return std::nullopt;
      value = value * 10 + static_cast<std::uint64_t>(c - '0');
    }
    return value;
  };
  const auto index = number(text.substr(0, slash)), count = number(text.substr(slash + 1));
  if (!index || !count || *index < 1 || *index > *count) return std::nullopt;
  return Shard{*index, *count};
}

std::span<const std::string_view> merge_lenient_parameters() {
  return kLenient;
}

struct SolutionMerge::State {
  std::vector<SolutionReader> readers;
  std::vector<MergedInput> inputs;
  std::optional<std::uint64_t> shards;
  std::vector<std::int64_t> owner;  // per query: the input that ran it, or -1
  std::vector<std::uint64_t> missing;
};

namespace {

// Why `r` (named `name`) cannot join `first` (named `first_name`): one line, or nullopt.
std::optional<std::string> binding_difference(const SolutionReader& first,
                                              const SolutionReader& r) {
  if (r.instance_digest() != first.instance_digest())
    return "another instance (digest " + r.instance_digest() + ", not " + first.instance_digest() +
           ")";
  if (r.header().vertex_count != first.header().vertex_count ||
      r.header().arc_count != first.header().arc_count)
    return "another instance size (n, m)";
  if (r.view_name() != first.view_name())
    return "view " + quoted(r.view_name().empty() ? std::nullopt : std::optional(r.view_name())) +
           ", not " +
           quoted(first.view_name().empty() ? std::nullopt : std::optional(first.view_name()));
  if (objectives_of(r) != objectives_of(first))
    return "objectives " + objectives_of(r) + ", not " + objectives_of(first);
  if (r.query_set() != first.query_set() || r.query_count() != first.query_count())
    return "query set '" + r.query_set() + "' of " + std::to_string(r.query_count()) +
           " queries, not '" + first.query_set() + "' of " + std::to_string(first.query_count());
  return std::nullopt;
}

// The first solver setting in which `r` differs from `first`, or nullopt.
std::optional<std::string> setting_difference(const SolutionReader& first,
                                              const SolutionReader& r) {
  std::set<std::string> keys;
  for (const auto* reader : {&first, &r})
    for (const auto& [key, value] : reader->metadata().entries())
      if (key.starts_with("solution.solver.") || key == "solution.epsilon") keys.insert(key);
  constexpr std::string_view kParam = "solution.solver.param.";
  for (const auto& key : keys) {
    if (key.starts_with(kParam)) {
      const auto parameter = std::string_view(key).substr(kParam.size());
      if (parameter == kShardKey || lenient(parameter)) continue;
    }
    auto a = first.metadata().get(key), b = r.metadata().get(key);
    if (key == "solution.epsilon") {  // absent means exact
      a = a.value_or("0");
      b = b.value_or("0");
    }
    if (a != b) return key + " " + quoted(b) + ", not " + quoted(a);
  }
  return std::nullopt;
}

}  // namespace

SolutionMerge::SolutionMerge(std::span<const std::filesystem::path> paths)
    : state_(std::make_unique<State>()) {
  auto& st = *state_;
  if (paths.empty()) throw Error(ErrorCode::invalid_argument, "no solution files to merge");
  std::map<std::uint64_t, std::size_t> shard_files;
  for (const auto& path : paths) {
    for (const auto& input : st.inputs)
      if (input.file == path) throw SolutionMergeConflict(path.string() + ": given twice");
    st.readers.push_back(SolutionReader::open_verified(path));
    const auto& r = st.readers.back();
    const std::size_t k = st.readers.size() - 1;
    const std::string name = path.string();
    const std::string first_name = st.inputs.empty() ? "" : st.inputs.front().file.string();
    MergedInput input{path, std::nullopt, 0};
    const auto shard = shard_of(r, name);
    if (k > 0) {
      const auto& first = st.readers.front();
      if (auto why = binding_difference(first, r))
        throw SolutionMergeConflict(name + ": " + *why + " than " + first_name);
      if (auto why = setting_difference(first, r))
        throw SolutionMergeConflict(name + ": differs from " + first_name + " in " + *why);
      if (shard.has_value() != st.shards.has_value())
        throw SolutionMergeConflict(
            shard ? name + ": is shard " + std::to_string(shard->index) + "/" +
                        std::to_string(shard->count) + ", but " + first_name + " is no shard"
                  : name + ": is no shard (no run.shard), but " + first_name + " is one of " +
                        std::to_string(*st.shards));
      if (shard && shard->count != *st.shards)
        throw SolutionMergeConflict(name + ": is shard " + std::to_string(shard->index) + "/" +
                                    std::to_string(shard->count) + ", but " + first_name +
                                    " is one of " + std::to_string(*st.shards) + " shards");
    } else {
      st.owner.assign(r.query_count(), -1);
      if (shard) st.shards = shard->count;
    }
    if (shard) {
      input.shard = shard->index;
      const auto [it, fresh] = shard_files.emplace(shard->index, k);
      if (!fresh)
        throw SolutionMergeConflict(name + ": is shard " + std::to_string(shard->index) + "/" +
                                    std::to_string(shard->count) + ", as " +
                                    st.inputs[it->second].file.string() + " is");
    }
    for (std::uint64_t q = 0; q < r.query_count(); ++q) {
      const auto status = r.status(q);
      if (status == QueryStatus::not_run) continue;
      if (st.owner[q] >= 0) {
        const auto other = static_cast<std::size_t>(st.owner[q]);
        throw SolutionMergeConflict(name + ": query " + std::to_string(q) + " is also in " +
                                    st.inputs[other].file.string() + " (" +
                                    std::string(to_string(st.readers[other].status(q))) +
                                    " there, " + std::string(to_string(status)) +
                                    " here): the inputs overlap");
      }
      st.owner[q] = static_cast<std::int64_t>(k);
      ++input.queries;
    }
    st.inputs.push_back(std::move(input));
  }
  for (std::uint64_t q = 0; q < st.owner.size(); ++q)
    if (st.owner[q] < 0) st.missing.push_back(q);
}

SolutionMerge::~SolutionMerge() = default;
SolutionMerge::SolutionMerge(SolutionMerge&&) noexcept = default;

std::uint64_t SolutionMerge::query_count() const {
  return state_->owner.size();
}
const std::string& SolutionMerge::query_set() const {
  return state_->readers.front().query_set();
}
const std::vector<MergedInput>& SolutionMerge::inputs() const {
  return state_->inputs;
}
std::optional<std::uint64_t> SolutionMerge::shard_count() const {
  return state_->shards;
}
std::vector<std::uint64_t> SolutionMerge::absent_shards() const {
  std::vector<std::uint64_t> absent;
  if (!state_->shards) return absent;
  std::set<std::uint64_t> present;
  for (const auto& input : state_->inputs) present.insert(*input.shard);
  for (std::uint64_t i = 1; i <= *state_->shards; ++i)
    if (!present.count(i)) absent.push_back(i);
  return absent;
}
const std::vector<std::uint64_t>& SolutionMerge::missing() const {
  return state_->missing;
}

StatusCounts SolutionMerge::status_counts() const {
  StatusCounts counts;
  const auto& st = *state_;
  for (std::uint64_t q = 0; q < st.owner.size(); ++q) {
    const auto status = st.owner[q] < 0
                            ? QueryStatus::not_run
                            : st.readers[static_cast<std::size_t>(st.owner[q])].status(q);
    ++counts[status];
  }
  return counts;
}

void SolutionMerge::write(const std::filesystem::path& output) const {
  const auto& st = *state_;
  std::vector<std::filesystem::path> inputs;
  for (const auto& input : st.inputs) inputs.push_back(input.file);
  check_output_is_not_input(output, inputs);
  const auto& first = st.readers.front();
  SolutionWriter writer(first);
  // The solver: what every input shares, and for what may differ, each distinct value.
  SolverInfo info = first.solver();
  info.parameters.erase(std::string(kShardKey));
  std::set<std::string> machines;
  std::map<std::string, std::set<std::string>> lenient_values;
  for (const auto& r : st.readers) {
    const auto solver = r.solver();
    if (!solver.machine.empty()) machines.insert(solver.machine);
    for (const auto& [key, value] : solver.parameters)
      if (lenient(key)) lenient_values[key].insert(value);
  }
  info.machine = joined(machines);
  for (const auto& [key, values] : lenient_values) info.parameters[key] = joined(values);
  if (st.shards) info.parameters[std::string(kShardsKey)] = std::to_string(*st.shards);
  writer.set_solver(std::move(info));
  // What imports dropped from the parts, added up.
  std::optional<DroppedVectors> dropped;
  for (const auto& r : st.readers)
    if (const auto part = r.dropped_vectors()) {
      if (!dropped) dropped.emplace();
      dropped->vectors += part->vectors;
      dropped->queries += part->queries;
    }
  writer.set_dropped_vectors(dropped);

  std::vector<double> costs;
  std::vector<std::vector<std::uint32_t>> paths;
  for (std::uint64_t q = 0; q < st.owner.size(); ++q) {
    if (st.owner[q] < 0) continue;
    const auto& r = st.readers[static_cast<std::size_t>(st.owner[q])];
    const auto begin = r.front_begin(q), size = r.front_size(q);
    costs.clear();
    paths.clear();
    for (std::uint64_t row = begin; row < begin + size; ++row) {
      for (std::size_t i = 0; i < r.objective_count(); ++i)
        costs.push_back(r.value_as_double(i, row));
      if (r.has_paths()) {
        const auto path = r.path(row);
        paths.emplace_back(path.begin(), path.end());
      }
    }
    writer.set_query(q, r.status(q), costs, r.statistics(q), paths);
  }
  writer.write(output);
}

}  // namespace mosb
