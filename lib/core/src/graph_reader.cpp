#include "mosb/graph_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mosb/internal/choices.hpp"
#include "mosb/internal/sections_by_kind.hpp"

namespace mosb {

using format::ElementType;
using format::SectionKind;

namespace {

// Expected element type, width and row count of each structural kind.
struct Shape {
  SectionKind kind;
  ElementType type;
  bool per_vertex_plus_one;
};
constexpr Shape kStructural[] = {
    {SectionKind::forward_offsets, ElementType::u64, true},
    {SectionKind::forward_targets, ElementType::u32, false},
    {SectionKind::reverse_offsets, ElementType::u64, true},
    {SectionKind::reverse_sources, ElementType::u32, false},
    {SectionKind::reverse_arcs, ElementType::u32, false},
};

}  // namespace

GraphReader GraphReader::open(const std::filesystem::path& path) {
  return adopt(map_file(path), path.string());
}

GraphReader GraphReader::open_unpacked(const std::filesystem::path& path) {
  auto reader = open(path);
  if (format::is_packed(reader.header()))
    reader.fail(ErrorCode::packed,
                "zstd-packed file (mosb pack): its sections cannot be mapped in place; load it "
                "(mosb::load, mosb_load, mosb.load) or unpack it (mosb unpack)");
  return reader;
}

GraphReader GraphReader::adopt(MappedFile file, std::string display_name) {
  GraphReader reader;
  reader.attach(std::move(file), std::move(display_name), format::FileKind::instance);
  reader.validate();
  return reader;
}

void GraphReader::require_verified(VerifyLevel level, std::string_view user) const {
  if (!covers(verified_level_, level))
    fail(ErrorCode::invalid_argument,
         std::string(user) +
             " walks the payload and needs a reader opened with GraphReader::open(path, level)");
}

GraphReader GraphReader::from_memory(std::span<const std::byte> bytes, std::string display_name) {
  GraphReader reader;
  reader.attach_borrowed(bytes, std::move(display_name), format::FileKind::instance);
  reader.validate();
  return reader;
}

// After attach: steps 1-7, the container, are done.
void GraphReader::validate() {
  // 8. Kinds and counts (names are unique within a kind: checked with the container).
  const std::uint64_t n = header_.vertex_count, m = header_.arc_count;
  if (n > format::kMaxCount || m > format::kMaxCount)
    fail("vertex count " + std::to_string(n) + " or arc count " + std::to_string(m) +
         " exceeds the format limit of 2^32-2");
  auto expect_rows = [&](const Section& s, std::uint64_t rows, const char* what) {
    if (s.entry.row_count != rows)
      fail("section '" + s.name + "': has " + std::to_string(s.entry.row_count) + " rows, but " +
           what + " is " + std::to_string(rows));
  };
  const SectionsByKind table(sections_, display_name_);
  const auto metadata_index = table.single(SectionKind::metadata);
  if (metadata_index != SIZE_MAX) {
    const auto& s = sections_[metadata_index];
    if (s.type != ElementType::u8 || s.entry.row_width != 1)
      fail("section '" + s.name + "': metadata must be u8 x 1");
  }
  for (const auto& shape : kStructural) {
    const auto i = table.single(shape.kind, shape.type);
    if (i != SIZE_MAX)
      expect_rows(sections_[i], shape.per_vertex_plus_one ? n + 1 : m,
                  shape.per_vertex_plus_one ? "the vertex count + 1" : "the arc count");
    structural_[static_cast<std::size_t>(shape.kind)] = i;
  }
  const auto costs = table.all(SectionKind::cost);
  for (auto i : costs) {
    table.expect_cost_column(sections_[i]);
    expect_rows(sections_[i], m, "the arc count");
  }
  cost_indices_.assign(costs.begin(), costs.end());
  for (auto i : table.all(SectionKind::vertex_data))
    expect_rows(sections_[i], n, "the vertex count");
  for (auto i : table.all(SectionKind::arc_data)) expect_rows(sections_[i], m, "the arc count");
  for (auto i : table.all(SectionKind::queries))
    if (sections_[i].type != ElementType::u32 || sections_[i].entry.row_width != 2)
      fail("section '" + sections_[i].name + "': queries must be u32 x 2");
  for (auto i : table.all(SectionKind::query_reference)) {
    const auto& s = sections_[i];
    if (s.type != ElementType::f64 || s.entry.row_width != 1)
      fail("section '" + s.name + "': query references must be f64 x 1");
  }
  if (metadata_index == SIZE_MAX) fail("no metadata section");
  for (const auto& shape : kStructural)
    if (structural_[static_cast<std::size_t>(shape.kind)] == SIZE_MAX)
      fail("no " + std::string(format::to_string(shape.kind)) + " section");
  // A reference belongs to the query set of its name, one value per query (names are unique within
  // a kind, so at most one of each).
  for (auto i : table.all(SectionKind::query_reference)) {
    const auto& s = sections_[i];
    const Section* set = find(SectionKind::queries, s.name);
    if (!set) fail("section '" + s.name + "': a query reference naming no query set");
    if (s.entry.row_count != set->entry.row_count)
      fail("section '" + s.name + "': the query reference has " +
           std::to_string(s.entry.row_count) + " rows, but the query set has " +
           std::to_string(set->entry.row_count));
  }
  if (header_.objective_count != cost_indices_.size())
    fail("header declares " + std::to_string(header_.objective_count) + " objectives, table has " +
         std::to_string(cost_indices_.size()) + " cost sections");

  // 9. CSR end points (cheap, and they make the offsets usable as loop bounds right away).
  for (auto kind : {SectionKind::forward_offsets, SectionKind::reverse_offsets}) {
    const auto& s = required(kind);
    if (s.is_packed()) continue;
    auto offsets = values<std::uint64_t>(s);
    if (offsets.front() != 0 || offsets.back() != m)
      fail("section '" + s.name + "': offsets run from " + std::to_string(offsets.front()) +
           " to " + std::to_string(offsets.back()) + ", not from 0 to the arc count " +
           std::to_string(m));
  }
}

const Section& GraphReader::required(SectionKind kind) const {
  return sections_[structural_[static_cast<std::size_t>(kind)]];
}

std::span<const std::byte> GraphReader::raw_bytes(const Section& s) const {
  check_access(s, s.type);
  return s.stored;
}

std::span<const std::uint64_t> GraphReader::forward_offsets() const {
  return values<std::uint64_t>(required(SectionKind::forward_offsets));
}
std::span<const std::uint32_t> GraphReader::forward_targets() const {
  return values<std::uint32_t>(required(SectionKind::forward_targets));
}
std::span<const std::uint64_t> GraphReader::reverse_offsets() const {
  return values<std::uint64_t>(required(SectionKind::reverse_offsets));
}
std::span<const std::uint32_t> GraphReader::reverse_sources() const {
  return values<std::uint32_t>(required(SectionKind::reverse_sources));
}
std::span<const std::uint32_t> GraphReader::reverse_arcs() const {
  return values<std::uint32_t>(required(SectionKind::reverse_arcs));
}

const Section& GraphReader::objective(std::size_t i) const {
  if (i >= cost_indices_.size())
    fail(ErrorCode::invalid_argument, "objective index " + std::to_string(i) +
                                          " out of range (the file has " +
                                          std::to_string(cost_indices_.size()) + " objectives)");
  return sections_[cost_indices_[i]];
}

std::optional<std::size_t> GraphReader::find_objective(std::string_view name) const {
  for (std::size_t i = 0; i < cost_indices_.size(); ++i)
    if (sections_[cost_indices_[i]].name == name) return i;
  return std::nullopt;
}

std::size_t GraphReader::objective_index(std::string_view name) const {
  if (auto i = find_objective(name)) return *i;
  fail(ErrorCode::not_found, "no objective named '" + std::string(name) + "'");
}

namespace {
template <class Out>
void convert_column(const GraphReader& reader, std::size_t i, std::span<Out> out) {
  const Section& s = reader.objective(i);
  if (out.size() != s.element_count())
    throw Error(ErrorCode::invalid_argument, reader.display_name() + ": section '" + s.name +
                                                 "' has " + std::to_string(s.element_count()) +
                                                 " values, the buffer " +
                                                 std::to_string(out.size()));
  reader.visit_cost(i, [&](auto in) { std::copy(in.begin(), in.end(), out.begin()); });
}
}  // namespace

void GraphReader::read_cost_as(std::size_t i, std::span<double> out) const {
  convert_column(*this, i, out);
}

void GraphReader::read_cost_as(std::size_t i, std::span<std::uint64_t> out) const {
  const auto& s = objective(i);
  if (format::is_float(s.type))
    fail(ErrorCode::invalid_argument, "objective '" + s.name + "' holds " +
                                          std::string(format::to_string(s.type)) +
                                          " values, which do not convert to integers");
  convert_column(*this, i, out);
}

const Section* GraphReader::find(SectionKind kind, std::string_view name) const {
  for (const auto& s : sections_)
    if (s.kind == kind && s.name == name) return &s;
  return nullptr;
}

std::vector<const Section*> GraphReader::all(SectionKind kind) const {
  std::vector<const Section*> found;
  for (const auto& s : sections_)
    if (s.kind == kind) found.push_back(&s);
  return found;
}

std::vector<std::string> GraphReader::query_set_names() const {
  std::vector<std::string> names;
  for (const auto* s : all(SectionKind::queries)) names.push_back(s->name);
  return names;
}

std::span<const Query> GraphReader::queries(std::string_view name) const {
  const Section* s = find(SectionKind::queries, name);
  if (!s)
    fail(ErrorCode::not_found, "no query set named '" + std::string(name) + "' " +
                                   choices_text(name, query_set_names(), "query sets"));
  auto raw = values<std::uint32_t>(*s);
  return {reinterpret_cast<const Query*>(raw.data()), raw.size() / 2};
}

std::optional<std::span<const double>> GraphReader::query_reference(std::string_view name) const {
  if (!find(SectionKind::queries, name))
    fail(ErrorCode::not_found, "no query set named '" + std::string(name) + "'");
  const Section* s = find(SectionKind::query_reference, name);
  if (!s) return std::nullopt;
  return values<double>(*s);
}

const Metadata& GraphReader::metadata() const {
  // A throw leaves the flag unset: every call on malformed metadata reports the same error.
  std::call_once(metadata_->parsed, [this] {
    const Section* s = nullptr;
    for (const auto& candidate : sections_)
      if (candidate.kind == SectionKind::metadata) s = &candidate;
    if (!s) fail("no metadata section");  // open() refuses such a file; kept for the analyzer
    auto raw = raw_bytes(*s);
    try {
      metadata_->value =
          Metadata::parse(std::string_view(reinterpret_cast<const char*>(raw.data()), raw.size()));
    } catch (const Error& e) {
      fail(std::string("section 'metadata': ") + e.what());
    }
  });
  return *metadata_->value;
}

}  // namespace mosb
