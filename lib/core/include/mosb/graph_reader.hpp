// Opens a mosb instance by memory-mapping it. Every accessor hands out a bounds-checked (per
// section), zero-copy view into the mapping.
//
// What plain open(path) checks (spec/FORMAT.md §9 steps 1-9, in time independent of the file size):
// the path is a regular file (a FIFO, directory or device is refused before anything can block);
// magic, byte order, version, header size and file kind; the file length; the section table's
// place and the header checksum (which covers every offset and length in the table); feature bits;
// each entry's name, type, width, size, alignment and extent inside the data area; no overlaps;
// exactly one of each structural kind with the right type, width and row count; the objective
// count; unique names within a kind (over every kind, known or not); the two ends of each offsets
// column (0 and m).
//
// What plain open does NOT check: the payload. No section checksum is computed, so a cost, target
// or offset may carry any value; offsets between the ends may decrease or exceed m; targets,
// reverse sources and query endpoints may be ≥ n; the reverse CSR may not be the transpose; float
// costs may be NaN or negative; alignment padding may be non-zero; the metadata text is not parsed
// (metadata() parses it on first use). Walking the CSR of a plainly opened file can therefore read
// out of bounds. open(path, level) runs the verify() checks of `level` before returning and throws
// "FILE: file is damaged: PROBLEM; run mosb verify" when they fail; code that walks payload should
// open with VerifyLevel::full (checksums and structure), which is what the library's own payload
// walkers (stats.hpp, dimacs_export) require (see verified_level()).
//
// Lifetime: every span, pointer and reference a GraphReader hands out (CSR arrays, cost columns,
// queries, sections, metadata) points into its mapping and stays valid as long as the reader or
// any copy of it lives (copies share the mapping); for from_memory, as long as the caller's bytes.
// Threads: after open() returns, every const member function may be called from any number of
// threads at once (metadata() parses once, under std::call_once). Assigning to or destroying a
// reader while another thread uses it is a race, as for any object.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/container.hpp"
#include "mosb/enum_names.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/metadata.hpp"
#include "mosb/query.hpp"

namespace mosb {

// How much of a file to check (spec/FORMAT.md §9 "Verification levels"). `structure` does not
// include `checksums`; `full` is both.
enum class VerifyLevel { header, checksums, structure, full };
inline constexpr auto kVerifyLevelNames = enum_names<VerifyLevel>({
    {VerifyLevel::header, "header"},
    {VerifyLevel::checksums, "checksums"},
    {VerifyLevel::structure, "structure"},
    {VerifyLevel::full, "full"},
});

// True when a file verified at `done` has passed every check of `wanted`.
constexpr bool covers(VerifyLevel done, VerifyLevel wanted) {
  return done == wanted || done == VerifyLevel::full || wanted == VerifyLevel::header;
}

// A benchmark view (§7 `view.<name>.objectives` and `view.<name>.queries`).
struct View {
  std::string name;
  std::vector<std::size_t> objectives;  // objective indices, in the view's order
  std::string query_set;                // empty when the view names none
};

template <class T>
class CostAs;

class GraphReader : public ContainerReader {
 public:
  static GraphReader open(const std::filesystem::path& path);
  // Opens, then runs verify(reader, level); throws "FILE: file is damaged: ...; run mosb verify".
  static GraphReader open(const std::filesystem::path& path, VerifyLevel level);
  // open() for callers that walk the sections in place (the C ABI's mosb_open, Python's
  // mosb.open): a packed file is refused at once (ErrorCode::packed, naming mosb::load), rather
  // than when a packed section is first read.
  static GraphReader open_unpacked(const std::filesystem::path& path);
  // Reads `file` (a mapping, or memory such as a decoded packed file) and keeps it alive as long as
  // the reader or a copy lives; `display_name` stands for the file in messages. mosb::load
  // (mosb/pack.hpp) uses it to hand out decoded packed files.
  static GraphReader adopt(MappedFile file, std::string display_name);
  static GraphReader adopt(MappedFile file, std::string display_name, VerifyLevel level);
  // Reads bytes the caller keeps alive; `display_name` stands for the file in messages.
  static GraphReader from_memory(std::span<const std::byte> bytes, std::string display_name);
  static GraphReader from_memory(std::span<const std::byte> bytes, std::string display_name,
                                 VerifyLevel level);

  // The level verified before the reader was handed out: `header` for plain open/from_memory.
  VerifyLevel verified_level() const { return verified_level_; }
  // Throws mosb::Error unless the reader was verified at a level covering `level`; for payload
  // walkers that must not run on unverified bytes. `user` names the caller in the message.
  void require_verified(VerifyLevel level, std::string_view user) const;

  std::uint64_t vertex_count() const { return header_.vertex_count; }
  std::uint64_t arc_count() const { return header_.arc_count; }

  std::span<const std::uint64_t> forward_offsets() const;
  std::span<const std::uint32_t> forward_targets() const;
  std::span<const std::uint64_t> reverse_offsets() const;
  std::span<const std::uint32_t> reverse_sources() const;
  std::span<const std::uint32_t> reverse_arcs() const;

  std::size_t objective_count() const { return cost_indices_.size(); }
  const Section& objective(std::size_t i) const;
  std::optional<std::size_t> find_objective(std::string_view name) const;
  std::size_t objective_index(std::string_view name) const;  // throws when absent

  // A cost column in its stored type; asking for another type is an error that names both.
  template <class T>
  std::span<const T> cost(std::size_t objective_index) const {
    return values<T>(objective(objective_index));
  }
  template <class T>
  std::span<const T> cost(std::string_view name) const {
    return cost<T>(objective_index(name));
  }
  // Calls f(std::span<const T>) with cost column i in its stored type T (std::uint8_t, uint16_t,
  // uint32_t, uint64_t, float or double) and returns what f returns, which must be one type for
  // every T: the way to read a column whatever type a file chose, with no copy.
  template <class F>
  decltype(auto) visit_cost(std::size_t i, F&& f) const;
  // Cost column i read as T whatever its stored type, element by element (no copy); refuses to
  // read float columns as integers.
  template <class T>
  CostAs<T> cost_as(std::size_t i) const;
  // Widens (or converts) a cost column into a caller-owned buffer of m values.
  void read_cost_as(std::size_t objective_index, std::span<double> out) const;
  void read_cost_as(std::size_t objective_index, std::span<std::uint64_t> out) const;

  const Section* find(format::SectionKind kind, std::string_view name) const;
  std::vector<const Section*> all(format::SectionKind kind) const;
  // A query set's pairs; throws ErrorCode::not_found naming the sets there are when absent.
  std::span<const Query> queries(std::string_view name) const;
  // The names of the query sets, in the file's order.
  std::vector<std::string> query_set_names() const;
  // The published per-query optimum of query set `name` (section kind 17, spec/SOLUTIONS.md §6),
  // one value per query; nullopt when the set carries none. Its shape (f64 x 1, one row per
  // query) is checked at open, its values (finite, >= 0) by verify at level structure.
  std::optional<std::span<const double>> query_reference(std::string_view name) const;

  // Parsed on first use: malformed metadata is an error of that call, not of open().
  const Metadata& metadata() const;

  // Views, from the metadata: names in sorted order; a view naming an objective the file lacks
  // is an Error (ErrorCode::damaged); view() throws ErrorCode::not_found when absent. views()
  // resolves all in one pass, O(V log V): for V views, use it rather than view() per name.
  std::vector<std::string> view_names() const;
  std::vector<View> views() const;
  std::optional<View> find_view(std::string_view name) const;
  View view(std::string_view name) const;

  std::span<const std::byte> raw_bytes(const Section& s) const;  // refuses packed sections

 private:
  GraphReader() = default;
  View resolve(ViewKeys keys) const;  // objective names to indices, checked
  void validate();
  void verify_at_open(VerifyLevel level);
  const Section& required(format::SectionKind kind) const;

  std::vector<std::size_t> cost_indices_;
  std::size_t structural_[7] = {};  // section index per structural kind 1..6
  struct MetadataCache {
    std::once_flag parsed;
    std::optional<Metadata> value;
  };
  // Shared by copies of the reader, like the mapping; filled once by metadata().
  std::shared_ptr<MetadataCache> metadata_ = std::make_shared<MetadataCache>();
  VerifyLevel verified_level_ = VerifyLevel::header;
};

template <class F>
decltype(auto) GraphReader::visit_cost(std::size_t i, F&& f) const {
  return visit_cost_values(objective(i), std::forward<F>(f));
}

// A cost column read as T by value, whatever its stored type (see GraphReader::cost_as).
template <class T>
class CostAs {
 public:
  T operator[](std::size_t arc) const {
    return format::visit_element_type(type_, [&](auto tag) -> T {
      using Stored = typename decltype(tag)::type;
      return static_cast<T>(static_cast<const Stored*>(data_)[arc]);
    });
  }
  std::size_t size() const { return size_; }
  format::ElementType stored_type() const { return type_; }

 private:
  friend class GraphReader;
  CostAs(const void* data, std::size_t size, format::ElementType type)
      : data_(data), size_(size), type_(type) {}
  const void* data_;
  std::size_t size_;
  format::ElementType type_;
};

template <class T>
CostAs<T> GraphReader::cost_as(std::size_t i) const {
  static_assert(format::is_cost_type_v<T>, "cost_as reads unsigned or floating-point values");
  const Section& s = objective(i);
  if constexpr (!std::is_floating_point_v<T>)
    if (format::is_float(s.type))
      throw Error(ErrorCode::invalid_argument,
                  display_name_ + ": objective '" + s.name + "' holds " +
                      std::string(format::to_string(s.type)) + " values, which do not convert to " +
                      "integers");
  const auto raw = raw_bytes(s);
  return CostAs<T>(raw.data(), s.element_count(), s.type);
}

}  // namespace mosb
