#include "mosb/verify.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>

#include "mosb/internal/hex.hpp"
#include "mosb/internal/parallel.hpp"
#include "mosb/internal/verify_rules.hpp"
#include "mosb/internal/xxh3.hpp"

namespace mosb {

using format::ElementType;
using format::SectionKind;

std::optional<VerifyLevel> parse_verify_level(std::string_view text) {
  return kVerifyLevelNames.parse(text);
}

namespace rules {

MOSB_SCAN_CLONES bool offsets_ascend(std::span<const std::uint64_t> offsets) {
  bool decreases = false;
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v) decreases |= offsets[v] > offsets[v + 1];
  return !decreases;
}

MOSB_SCAN_CLONES bool ids_below(std::span<const std::uint32_t> ids, std::uint64_t n) {
  if (n > UINT32_MAX) return true;
  const auto limit = static_cast<std::uint32_t>(n);
  unsigned out_of_range = 0;
  for (const std::uint32_t id : ids) out_of_range |= unsigned{id >= limit};
  return out_of_range == 0;
}

Problem check_offsets(const Section& s, std::span<const std::uint64_t> offsets,
                      std::uint64_t first) {
  if (offsets_ascend(offsets)) return std::nullopt;
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v)
    if (offsets[v] > offsets[v + 1])
      return in_section(s, "offsets-monotonic",
                        "offsets decrease at vertex " + std::to_string(first + v) + " (" +
                            std::to_string(offsets[v]) + " > " + std::to_string(offsets[v + 1]) +
                            ")");
  return std::nullopt;
}

Problem check_ids(const Section& s, std::span<const std::uint32_t> ids, std::uint64_t n,
                  std::string_view rule, std::string_view what, std::uint64_t first) {
  if (ids_below(ids, n)) return std::nullopt;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] >= n)
      return in_section(s, rule,
                        std::string(what) + " " + std::to_string(first + i) + " is vertex " +
                            std::to_string(ids[i]) + ", not below n = " + std::to_string(n));
  return std::nullopt;
}

}  // namespace rules

namespace {

using namespace rules;

Problem check_checksum(const Section& s) {
  return checksum_problem(s, XXH3_64bits(s.stored.data(), s.stored.size()));
}

// A section's checksum and a rule over its elements in one pass, 64 KiB at a time, so the rule
// scans from cache what the hash has just read from memory (as a pass of its own it cost about as
// much as the hash). `values` are the section's stored bytes as elements; `holds` sees each chunk
// and the element after it; `rule_holds` says whether it held throughout.
template <class T, class Holds>
Problem check_checksum_and_rule(const Section& s, std::span<const T> values, Holds holds,
                                bool& rule_holds) {
  Xxh3Stream hash;
  rule_holds = true;
  constexpr std::size_t kChunk = (std::size_t{64} << 10) / sizeof(T);
  for (std::size_t first = 0; first * sizeof(T) < s.stored.size(); first += kChunk) {
    const std::size_t bytes = std::min(kChunk * sizeof(T), s.stored.size() - first * sizeof(T));
    hash.update(s.stored.data() + first * sizeof(T), bytes);
    if (first < values.size())
      rule_holds &= holds(values.subspan(first, std::min(kChunk + 1, values.size() - first)));
  }
  return checksum_problem(s, hash.digest());
}

// The sections check_csr reads, found once.
struct Csr {
  const Section *forward_offsets, *forward_targets, *reverse_offsets, *reverse_sources,
      *reverse_arcs;
  std::span<const std::uint64_t> offsets, roffsets;
  std::span<const std::uint32_t> targets, rsources, rarcs;
};

Csr csr_of(const GraphReader& reader) {
  auto section = [&](SectionKind kind) { return reader.all(kind).front(); };
  return {section(SectionKind::forward_offsets),
          section(SectionKind::forward_targets),
          section(SectionKind::reverse_offsets),
          section(SectionKind::reverse_sources),
          section(SectionKind::reverse_arcs),
          reader.forward_offsets(),
          reader.reverse_offsets(),
          reader.forward_targets(),
          reader.reverse_sources(),
          reader.reverse_arcs()};
}

// Transpose (§4) over the in-lists of vertices [first, last): each entry j of v's in-list is an arc
// a into v whose tail is rsources[j], and the arc ids ascend strictly within a list. With m entries
// in all, that makes every arc appear exactly once. On the way it meets the reverse CSR's own rules
// (reverse_offsets non-decreasing, every reverse_sources id below n), so these need no pass of
// their own. Every index is range-checked, so it runs on any bytes, at the same time as the other
// checks; verify() reports its result only after the CSR rules §9 lists before it held, so a
// message of its own about those rules is never shown. The fast loop is branch-free, so the
// out-of-order core keeps the two random reads of many entries (targets[a], offsets[u]) in flight
// at once (explicit prefetching measured no faster); the slow loop runs only to name the first
// broken entry.
Problem check_transpose(const Csr& c, std::uint64_t first, std::uint64_t last) {
  const std::uint64_t n = c.offsets.size() - 1, m = c.targets.size();
  auto broken = [&](std::uint64_t v, std::uint64_t j, const std::string& what) {
    return in_section(*c.reverse_arcs, "reverse-transpose",
                      "entry " + std::to_string(j) + " (vertex " + std::to_string(v) + ") " + what);
  };
  for (std::uint64_t v = first; v < last; ++v) {
    const std::uint64_t list_first = c.roffsets[v], list_end = c.roffsets[v + 1];
    if (list_first > list_end || list_end > m)
      return in_section(*c.reverse_offsets, "offsets-monotonic",
                        "the in-list of vertex " + std::to_string(v) + " is out of range");
    // Integer ORs, not ||, so every test is evaluated without branches; `previous` starts below
    // every arc id, so the first entry passes the order test.
    unsigned bad = 0;
    std::int64_t previous = -1;
    for (auto j = list_first; j < list_end; ++j) {
      const std::uint32_t a = c.rarcs[j];
      const std::uint32_t u = c.rsources[j];
      const bool in_range = (a < m) & (u < n);
      const std::uint32_t arc = in_range ? a : 0, tail = in_range ? u : 0;
      const std::uint64_t out_first = c.offsets[tail];
      bad |= unsigned{!in_range} | unsigned{c.targets[arc] != v} |
             unsigned{a - out_first >= c.offsets[tail + 1] - out_first} |
             unsigned{std::int64_t{a} <= previous};
      previous = a;
    }
    if (bad == 0) continue;
    for (auto j = list_first; j < list_end; ++j) {
      const std::uint32_t a = c.rarcs[j];
      const std::uint32_t u = c.rsources[j];
      if (a >= m)
        return broken(v, j,
                      "names arc " + std::to_string(a) + ", not below m = " + std::to_string(m));
      if (u >= n)
        return in_section(*c.reverse_sources, "source-range",
                          "entry " + std::to_string(j) + " is vertex " + std::to_string(u) +
                              ", not below n = " + std::to_string(n));
      if (c.targets[a] != v)
        return broken(v, j,
                      "names arc " + std::to_string(a) + ", which enters vertex " +
                          std::to_string(c.targets[a]));
      if (!(c.offsets[u] <= a && a < c.offsets[u + 1]))
        return broken(v, j,
                      "says arc " + std::to_string(a) + " leaves vertex " + std::to_string(u) +
                          ", the forward CSR disagrees");
      if (j > list_first && c.rarcs[j - 1] >= a)
        return broken(v, j,
                      "breaks the ascending arc order (" + std::to_string(c.rarcs[j - 1]) +
                          " then " + std::to_string(a) + ")");
    }
  }
  return std::nullopt;
}

// Every query set carrying a reference names, in `queries.<set>.reference.objective`, the cost
// section its values refer to (spec/SOLUTIONS.md §6).
std::optional<std::string> find_reference_problem(const GraphReader& reader,
                                                  const Metadata& metadata) {
  for (const auto* s : reader.all(SectionKind::query_reference)) {
    const std::string key = "queries." + s->name + ".reference.objective";
    const auto objective = metadata.get(key);
    if (!objective)
      return "query set '" + s->name + "' carries a reference, but " + key + " is missing";
    if (!reader.find(SectionKind::cost, *objective))
      return key + " names objective '" + *objective + "', which is no cost section";
    const std::string units_key = "queries." + s->name + ".reference.units";
    const auto units = metadata.get(units_key);
    if (units && *units != "octile" && *units != "objective")
      return units_key + " is '" + *units + "', not octile or objective";
  }
  return std::nullopt;
}

Problem check_metadata(const GraphReader& reader) {
  const Section& metadata_section = *reader.all(SectionKind::metadata).front();
  const Metadata* metadata = nullptr;
  try {
    metadata = &reader.metadata();
  } catch (const Error& e) {
    std::string what = e.what();
    const std::string prefix = reader.display_name() + ": section 'metadata': ";
    if (what.starts_with(prefix)) what = what.substr(prefix.size());
    return in_section(metadata_section, "metadata", what);
  }
  return metadata_problem(reader, *metadata);
}

// Runs every task on up to `threads` threads; results stay in task order, so the first problem
// reported does not depend on the scheduling. Tasks run longest first (by their `cost`).
struct Task {
  std::uint64_t cost;
  std::function<Problem()> run;
};

// Reports stage "verify" as tasks finish, in units of their cost, from whichever thread finished.
class TaskProgress {
 public:
  TaskProgress(const Progress& progress, std::uint64_t total) : progress_(progress), total_(total) {
    report(progress_, "verify", 0, total_);
  }
  void done(std::uint64_t cost) {
    if (!progress_) return;
    const std::lock_guard lock(mutex_);
    done_ = std::min(total_, done_ + cost);
    progress_("verify", done_, total_);
  }

 private:
  const Progress& progress_;
  std::uint64_t total_;
  std::uint64_t done_ = 0;
  std::mutex mutex_;
};

// Runs every task, the costliest first, so that no large one starts last.
std::vector<Problem> run_all(std::vector<Task>& tasks, unsigned threads, TaskProgress& progress) {
  std::vector<Problem> results(tasks.size());
  std::vector<std::size_t> order(tasks.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return tasks[a].cost > tasks[b].cost; });
  parallel_for(order.size(), threads, [&](std::size_t k) {
    const std::size_t i = order[k];
    results[i] = tasks[i].run();
    progress.done(tasks[i].cost);
  });
  return results;
}

// Below this size threads cost more than they save.
constexpr std::uint64_t kParallelFrom = 1 << 20;

// Packed sections cannot be checked in place: the first one found ends verification.
Problem refuse_packed(const GraphReader& reader, bool checksums) {
  for (const auto& s : reader.sections()) {
    if (s.is_packed() && checksums)
      return in_section(s, "checksum", "zstd-packed sections are verified after unpacking");
    if (s.is_packed()) return in_section(s, "structure", "zstd-packed; unpack the file first");
  }
  return std::nullopt;
}

// One verification laid out as tasks. The tasks point into it (the CSR, the flags the forward
// scans set), so it stays where verify made it; the index ranges say which results are which.
struct Plan {
  Plan() = default;
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;

  std::vector<Task> tasks;
  std::optional<Csr> csr;
  bool forward_offsets_ascend = true, targets_below_n = true;
  std::size_t checksums_end = 0, transpose_first = 0, transpose_end = 0;
};

// Every section's checksum. Fused with structure, the forward CSR's two sections also run their
// rule's scan on the bytes the checksum reads, so neither costs a pass of its own.
void add_checksum_tasks(const GraphReader& reader, bool fused, std::uint64_t n, Plan& plan) {
  auto& tasks = plan.tasks;
  for (const auto& s : reader.sections()) {
    if (fused && &s == plan.csr->forward_offsets)
      tasks.push_back({s.stored.size(), [&s, &c = *plan.csr, &ok = plan.forward_offsets_ascend] {
                         return check_checksum_and_rule(
                             s, c.offsets, [](auto chunk) { return offsets_ascend(chunk); }, ok);
                       }});
    else if (fused && &s == plan.csr->forward_targets)
      tasks.push_back({s.stored.size(), [&s, &c = *plan.csr, n, &ok = plan.targets_below_n] {
                         return check_checksum_and_rule(
                             s, c.targets, [n](auto chunk) { return ids_below(chunk, n); }, ok);
                       }});
    else
      tasks.push_back({s.stored.size(), [&s] { return check_checksum(s); }});
  }
}

// The transpose check, in blocks of about equal entry counts (found by bisecting the reverse
// offsets, which need not be sorted yet: any answer gives valid blocks), several per thread so that
// uneven cache behaviour evens out.
void add_transpose_tasks(unsigned threads, std::uint64_t n, std::uint64_t m, Plan& plan) {
  const Csr& c = *plan.csr;
  const std::uint64_t blocks = threads == 1 ? 1 : 8 * threads;
  auto first_vertex_past = [&c, n](std::uint64_t entries) {
    std::uint64_t low = 0, high = n;
    while (low < high) {
      const std::uint64_t middle = low + (high - low) / 2;
      if (c.roffsets[middle] <= entries)
        low = middle + 1;
      else
        high = middle;
    }
    return low;
  };
  plan.transpose_first = plan.tasks.size();
  std::uint64_t first = 0;
  for (std::uint64_t b = 1; b <= blocks && first < n; ++b) {
    std::uint64_t last = b == blocks ? n : first_vertex_past(m / blocks * b) - 1;
    last = std::clamp(last, first + 1, n);
    plan.tasks.push_back(
        {m / blocks, [&c, first, last] { return check_transpose(c, first, last); }});
    first = last;
  }
  plan.transpose_end = plan.tasks.size();
}

// The structural rules: the forward CSR's scans when no checksum carries them, the transpose,
// then the value ranges, the metadata and the padding.
void add_structure_tasks(const GraphReader& reader, bool fused, unsigned threads, Plan& plan) {
  const std::uint64_t n = reader.vertex_count(), m = reader.arc_count();
  auto& tasks = plan.tasks;
  const Csr& c = *plan.csr;
  if (!fused) {
    tasks.push_back({8 * n, [&c, &ok = plan.forward_offsets_ascend] {
                       ok = offsets_ascend(c.offsets);
                       return Problem{};
                     }});
    tasks.push_back({4 * m, [&c, n, &ok = plan.targets_below_n] {
                       ok = ids_below(c.targets, n);
                       return Problem{};
                     }});
  }
  add_transpose_tasks(threads, n, m, plan);
  for (const auto* s : reader.all(SectionKind::cost)) {
    if (s->type == ElementType::f32)
      tasks.push_back({s->stored.size(), [&reader, s] {
                         return check_float_values(*s, reader.values<float>(*s), "cost", "arc",
                                                   "costs");
                       }});
    else if (s->type == ElementType::f64)
      tasks.push_back({s->stored.size(), [&reader, s] {
                         return check_float_values(*s, reader.values<double>(*s), "cost", "arc",
                                                   "costs");
                       }});
  }
  for (const auto* s : reader.all(SectionKind::queries))
    tasks.push_back({s->stored.size(), [&reader, s, n] {
                       return check_ids(*s, reader.values<std::uint32_t>(*s), n, "query-range",
                                        "endpoint");
                     }});
  for (const auto* s : reader.all(SectionKind::query_reference))
    tasks.push_back({s->stored.size(), [&reader, s] {
                       return check_float_values(*s, reader.values<double>(*s), "reference",
                                                 "query", "has");
                     }});
  tasks.push_back({0, [&reader] { return check_metadata(reader); }});
  tasks.push_back({0, [&reader] { return find_padding_problem(reader); }});
}

// The first problem in the fixed order: every checksum; the CSR rules of §9 (forward offsets,
// reverse offsets, targets, reverse sources), whose message-naming scans run only now and only
// for a rule found broken; the transpose; then the other structural rules.
Problem first_problem(const Plan& plan, const std::vector<Problem>& results, std::uint64_t n) {
  for (std::size_t i = 0; i < plan.checksums_end; ++i)
    if (results[i]) return results[i];
  if (plan.csr) {
    const Csr& c = *plan.csr;
    const bool transpose_broken =
        std::any_of(results.begin() + plan.transpose_first, results.begin() + plan.transpose_end,
                    [](const Problem& p) { return p.has_value(); });
    if (!plan.forward_offsets_ascend)
      if (auto p = check_offsets(*c.forward_offsets, c.offsets)) return p;
    if (transpose_broken)
      if (auto p = check_offsets(*c.reverse_offsets, c.roffsets)) return p;
    if (!plan.targets_below_n)
      if (auto p = check_ids(*c.forward_targets, c.targets, n, "target-range", "arc")) return p;
    if (transpose_broken) {
      if (auto p = check_ids(*c.reverse_sources, c.rsources, n, "source-range", "entry")) return p;
      for (std::size_t i = plan.transpose_first; i < plan.transpose_end; ++i)
        if (results[i]) return results[i];
    }
  }
  for (std::size_t i = plan.transpose_end; i < results.size(); ++i)
    if (results[i]) return results[i];
  return std::nullopt;
}

}  // namespace

Problem rules::metadata_problem(const GraphReader& reader, const Metadata& metadata) {
  const Section& metadata_section = *reader.all(SectionKind::metadata).front();
  std::vector<std::string> objectives, query_sets;
  for (const auto* s : reader.all(SectionKind::cost)) objectives.push_back(s->name);
  for (const auto* s : reader.all(SectionKind::queries)) query_sets.push_back(s->name);
  if (auto problem = find_view_problem(metadata, objectives, query_sets))
    return in_section(metadata_section, "metadata-views", *problem);
  if (auto problem = find_value_problem(metadata))
    return in_section(metadata_section, "metadata-values", *problem);
  if (auto problem = find_reference_problem(reader, metadata))
    return in_section(metadata_section, "metadata-reference", *problem);
  return std::nullopt;
}

std::optional<std::string> find_padding_problem(const ContainerReader& reader) {
  return find_padding_problem(reader.bytes(), Container{reader.header(), reader.sections()});
}

std::optional<std::string> find_padding_problem(std::span<const std::byte> bytes,
                                                const Container& container) {
  std::vector<const Section*> by_offset;
  for (const auto& s : container.sections)
    if (s.entry.stored_length > 0) by_offset.push_back(&s);
  std::sort(by_offset.begin(), by_offset.end(),
            [](auto* a, auto* b) { return a->entry.offset < b->entry.offset; });
  auto gap = [&](std::uint64_t from, std::uint64_t to,
                 const std::string& where) -> std::optional<std::string> {
    for (auto i = from; i < to; ++i)
      if (bytes[i] != std::byte{0})
        return "[padding] byte " + std::to_string(i) + " (" + where + ") is 0x" +
               hex64(std::to_integer<std::uint64_t>(bytes[i])).substr(14) +
               ", but bytes outside every section are zero";
    return std::nullopt;
  };
  std::uint64_t position = format::kHeaderSize;
  for (const auto* s : by_offset) {
    if (auto p = gap(position, s->entry.offset, "before section '" + s->name + "'")) return p;
    position = s->entry.offset + s->entry.stored_length;
  }
  return gap(position, container.header.table_offset, "before the section table");
}

std::optional<std::string> verify(const GraphReader& reader, VerifyLevel level,
                                  const Progress& progress) {
  // Opening already performed the header level.
  const bool checksums = level == VerifyLevel::checksums || level == VerifyLevel::full;
  const bool structure = level == VerifyLevel::structure || level == VerifyLevel::full;
  if (!checksums && !structure) return std::nullopt;
  if (auto problem = refuse_packed(reader, checksums)) return problem;
  const unsigned threads = reader.bytes().size() < kParallelFrom ? 1 : thread_count(0);

  // Every check runs at once, on all threads; first_problem then reports in a fixed order. The CSR
  // rules cost no pass of their own: the forward ones are checked with the forward sections'
  // checksums (or alone, by a message-less scan, at level structure), the reverse ones by the
  // transpose's blocks (check_transpose).
  Plan plan;
  if (structure) plan.csr = csr_of(reader);
  const bool fused = checksums && structure;
  if (checksums) add_checksum_tasks(reader, fused, reader.vertex_count(), plan);
  plan.checksums_end = plan.transpose_first = plan.transpose_end = plan.tasks.size();
  if (structure) add_structure_tasks(reader, fused, threads, plan);

  std::uint64_t total = 0;
  for (const auto& t : plan.tasks) total += t.cost;
  TaskProgress tracker(progress, total);
  const auto results = run_all(plan.tasks, threads, tracker);
  return first_problem(plan, results, reader.vertex_count());
}

// The opens that verify live here, not in graph_reader.cpp: verify reads a GraphReader, and the
// reader's own source does not depend on verify.
GraphReader GraphReader::adopt(MappedFile file, std::string display_name, VerifyLevel level) {
  auto reader = adopt(std::move(file), std::move(display_name));
  reader.verify_at_open(level);
  return reader;
}

GraphReader GraphReader::open(const std::filesystem::path& path, VerifyLevel level) {
  auto reader = open(path);
  reader.verify_at_open(level);
  return reader;
}

GraphReader GraphReader::from_memory(std::span<const std::byte> bytes, std::string display_name,
                                     VerifyLevel level) {
  auto reader = from_memory(bytes, std::move(display_name));
  reader.verify_at_open(level);
  return reader;
}

void GraphReader::verify_at_open(VerifyLevel level) {
  if (level != VerifyLevel::header)
    for (const auto& s : sections_)
      if (s.is_packed())
        fail(ErrorCode::packed, "section '" + s.name +
                                    "' is zstd-packed; its payload cannot be verified or walked "
                                    "in place; unpack the file first");
  if (auto problem = verify(*this, level))
    fail("file is damaged: " + *problem + "; run mosb verify");
  verified_level_ = level;
}

}  // namespace mosb
