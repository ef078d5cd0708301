// Opens a mosb instance by memory-mapping it. Opening checks the header, the section table and
// every cross-section count (spec/FORMAT.md §9), in time independent of the file size; after that,
// every accessor hands out a bounds-checked, zero-copy view into the mapping.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/metadata.hpp"
#include "mosb/query.hpp"

namespace mosb {

struct Section {
  format::SectionEntry entry;
  std::string name;
  std::optional<format::SectionKind> kind;  // nullopt: a kind this reader does not know
  format::ElementType type;
  std::uint64_t decoded_length;  // row_count * row_width * element size
  std::span<const std::byte> stored;

  bool is_packed() const { return entry.encoding != static_cast<std::uint8_t>(format::Encoding::raw); }
  std::uint64_t element_count() const { return entry.row_count * entry.row_width; }
};

class GraphReader {
 public:
  static GraphReader open(const std::filesystem::path& path);
  // Reads bytes the caller keeps alive; `display_name` stands for the file in messages.
  static GraphReader from_memory(std::span<const std::byte> bytes, std::string display_name);

  const std::string& display_name() const { return display_name_; }
  const format::FileHeader& header() const { return header_; }
  std::span<const std::byte> bytes() const { return bytes_; }
  std::uint64_t vertex_count() const { return header_.vertex_count; }
  std::uint64_t arc_count() const { return header_.arc_count; }
  const std::vector<Section>& sections() const { return sections_; }
  std::string digest() const;  // §8 content digest, 32 hex digits

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
  // Widens (or converts) a cost column into a caller-owned buffer of m values.
  void read_cost_as(std::size_t objective_index, std::span<double> out) const;
  void read_cost_as(std::size_t objective_index, std::span<std::uint64_t> out) const;

  const Section* find(format::SectionKind kind, std::string_view name) const;
  std::vector<const Section*> all(format::SectionKind kind) const;
  std::span<const Query> queries(std::string_view name) const;

  // Parsed on first use: malformed metadata is an error of that call, not of open().
  const Metadata& metadata() const;

  // Zero-copy view of a section's elements, checked for type and encoding.
  template <class T>
  std::span<const T> values(const Section& s) const {
    check_access(s, format::element_type_of<T>());
    return {reinterpret_cast<const T*>(s.stored.data()), s.element_count()};
  }
  std::span<const std::byte> raw_bytes(const Section& s) const;  // refuses packed sections

 private:
  GraphReader() = default;
  void validate();
  void check_access(const Section& s, format::ElementType wanted) const;
  [[noreturn]] void fail(const std::string& what) const;
  const Section& required(format::SectionKind kind) const;

  std::shared_ptr<const void> mapping_;
  std::span<const std::byte> bytes_;
  std::string display_name_;
  format::FileHeader header_{};
  std::vector<Section> sections_;
  std::vector<std::size_t> cost_indices_;
  std::size_t structural_[7] = {};  // section index per structural kind 1..6
  mutable std::shared_ptr<Metadata> metadata_;
};

}  // namespace mosb
