#include "mosb/hex.hpp"
#include "mosb/verify.hpp"

#include "xxh3.hpp"

#include <cmath>

namespace mosb {

using format::ElementType;
using format::SectionKind;

std::optional<VerifyLevel> parse_verify_level(std::string_view text) {
  if (text == "header") return VerifyLevel::header;
  if (text == "checksums") return VerifyLevel::checksums;
  if (text == "structure") return VerifyLevel::structure;
  if (text == "full") return VerifyLevel::full;
  return std::nullopt;
}

namespace {

using Problem = std::optional<std::string>;


std::string in_section(const Section& s, std::string_view rule, const std::string& detail) {
  return "section '" + s.name + "': [" + std::string(rule) + "] " + detail;
}

Problem check_checksums(const GraphReader& reader) {
  for (const auto& s : reader.sections()) {
    if (s.is_packed())
      return in_section(s, "checksum", "zstd-packed sections are verified after unpacking");
    const std::uint64_t computed = XXH3_64bits(s.stored.data(), s.stored.size());
    if (computed != s.entry.checksum)
      return in_section(s, "checksum", "mismatch (stored " + hex64(s.entry.checksum) +
                                           ", computed " + hex64(computed) + ")");
  }
  return std::nullopt;
}

Problem check_offsets(const Section& s, std::span<const std::uint64_t> offsets) {
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v)
    if (offsets[v] > offsets[v + 1])
      return in_section(s, "offsets-monotonic",
                        "offsets decrease at vertex " + std::to_string(v) + " (" +
                            std::to_string(offsets[v]) + " > " + std::to_string(offsets[v + 1]) + ")");
  return std::nullopt;
}

Problem check_ids(const Section& s, std::span<const std::uint32_t> ids, std::uint64_t n,
                  std::string_view rule, std::string_view what) {
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] >= n)
      return in_section(s, rule, std::string(what) + " " + std::to_string(i) + " is vertex " +
                                     std::to_string(ids[i]) + ", not below n = " + std::to_string(n));
  return std::nullopt;
}

Problem check_csr(const GraphReader& reader) {
  const std::uint64_t n = reader.vertex_count();
  const auto& sections = reader.sections();
  auto section = [&](SectionKind kind) -> const Section& {
    for (const auto& s : sections)
      if (s.kind == kind) return s;
    return sections.front();  // unreachable: open() requires every structural section
  };
  const auto offsets = reader.forward_offsets();
  const auto targets = reader.forward_targets();
  const auto roffsets = reader.reverse_offsets();
  const auto rsources = reader.reverse_sources();
  const auto rarcs = reader.reverse_arcs();
  if (auto p = check_offsets(section(SectionKind::forward_offsets), offsets)) return p;
  if (auto p = check_offsets(section(SectionKind::reverse_offsets), roffsets)) return p;
  if (auto p = check_ids(section(SectionKind::forward_targets), targets, n, "target-range", "arc"))
    return p;
  if (auto p = check_ids(section(SectionKind::reverse_sources), rsources, n, "source-range", "entry"))
    return p;
  // Transpose: each entry j of v's in-list is an arc a into v whose tail is rsources[j], and the
  // arc ids ascend strictly within a list. With m entries in all, that makes every arc appear once.
  const Section& rs = section(SectionKind::reverse_arcs);
  const std::uint64_t m = targets.size();
  auto broken = [&](std::uint64_t v, std::uint64_t j, const std::string& what) {
    return in_section(rs, "reverse-transpose", "entry " + std::to_string(j) + " (vertex " +
                                                   std::to_string(v) + ") " + what);
  };
  for (std::uint64_t v = 0; v < n; ++v) {
    // Branch-free over the whole in-list (targets[a] is read only for a < m); the slow loop below
    // runs only to name the first broken entry.
    bool broken_list = false;
    for (auto j = roffsets[v]; j < roffsets[v + 1]; ++j) {
      const std::uint32_t a = rarcs[j];
      const std::uint32_t u = rsources[j];
      const bool in_range = a < m;
      // Integer ORs, not ||, so every test is evaluated without branches.
      const unsigned bad = unsigned{!in_range} | unsigned{targets[in_range ? a : 0] != v} |
                           unsigned{offsets[u] > a} | unsigned{a >= offsets[u + 1]} |
                           unsigned{j > roffsets[v] && rarcs[j - 1] >= a};
      broken_list |= bad != 0;
    }
    if (!broken_list) continue;
    for (auto j = roffsets[v]; j < roffsets[v + 1]; ++j) {
      const std::uint32_t a = rarcs[j];
      const std::uint32_t u = rsources[j];
      if (a < m && targets[a] == v && offsets[u] <= a && a < offsets[u + 1] &&
          (j == roffsets[v] || rarcs[j - 1] < a))
        continue;
      if (a >= m) return broken(v, j, "names arc " + std::to_string(a) + ", not below m = " + std::to_string(m));
      if (targets[a] != v)
        return broken(v, j, "names arc " + std::to_string(a) + ", which enters vertex " +
                                std::to_string(targets[a]));
      if (!(offsets[u] <= a && a < offsets[u + 1]))
        return broken(v, j, "says arc " + std::to_string(a) + " leaves vertex " +
                                std::to_string(u) + ", the forward CSR disagrees");
      return broken(v, j, "breaks the ascending arc order (" + std::to_string(rarcs[j - 1]) +
                              " then " + std::to_string(a) + ")");
    }
  }
  return std::nullopt;
}

template <class T>
Problem check_float_costs(const Section& s, std::span<const T> costs) {
  for (std::size_t a = 0; a < costs.size(); ++a) {
    if (!std::isfinite(costs[a]))
      return in_section(s, "cost-finite", "arc " + std::to_string(a) + " costs " +
                                              std::to_string(costs[a]));
    if (costs[a] < 0)
      return in_section(s, "cost-nonnegative", "arc " + std::to_string(a) + " costs " +
                                                   std::to_string(costs[a]));
  }
  return std::nullopt;
}

Problem check_structure(const GraphReader& reader) {
  if (auto p = check_csr(reader)) return p;
  for (const auto* s : reader.all(SectionKind::cost)) {
    if (s->type == ElementType::f32) {
      if (auto p = check_float_costs(*s, reader.values<float>(*s))) return p;
    } else if (s->type == ElementType::f64) {
      if (auto p = check_float_costs(*s, reader.values<double>(*s))) return p;
    }
  }
  for (const auto* s : reader.all(SectionKind::queries))
    if (auto p = check_ids(*s, reader.values<std::uint32_t>(*s), reader.vertex_count(),
                           "query-range", "endpoint"))
      return p;
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
  std::vector<std::string> objectives, query_sets;
  for (const auto* s : reader.all(SectionKind::cost)) objectives.push_back(s->name);
  for (const auto* s : reader.all(SectionKind::queries)) query_sets.push_back(s->name);
  if (auto problem = find_view_problem(*metadata, objectives, query_sets))
    return in_section(metadata_section, "metadata-views", *problem);
  return std::nullopt;
}

}  // namespace

std::optional<std::string> verify(const GraphReader& reader, VerifyLevel level) {
  // Opening already performed the header level.
  if (level == VerifyLevel::checksums || level == VerifyLevel::full)
    if (auto p = check_checksums(reader)) return p;
  if (level == VerifyLevel::structure || level == VerifyLevel::full) {
    for (const auto& s : reader.sections())
      if (s.is_packed()) return in_section(s, "structure", "zstd-packed; unpack the file first");
    if (auto p = check_structure(reader)) return p;
  }
  return std::nullopt;
}

}  // namespace mosb
