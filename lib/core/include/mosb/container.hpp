// The container every mosb file kind shares (spec/FORMAT.md §1-§6): mapping a file, and the checks
// of §9 steps 1-7 that hold whatever the file kind. Readers of a kind (GraphReader, and the readers
// of later file kinds) add their own checks of the sections on top of this one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/format.hpp"

namespace mosb {

struct Section {
  format::SectionEntry entry;
  std::string name;
  std::optional<format::SectionKind> kind;  // nullopt: a kind this reader does not know
  format::ElementType type;
  std::uint64_t decoded_length;  // row_count * row_width * element size
  std::span<const std::byte> stored;

  bool is_packed() const {
    return entry.encoding != static_cast<std::uint8_t>(format::Encoding::raw);
  }
  std::uint64_t element_count() const { return entry.row_count * entry.row_width; }
};

// A file mapped read-only; copies share the mapping, which lives as long as any copy.
struct MappedFile {
  std::shared_ptr<const void> owner;
  std::span<const std::byte> bytes;
};

// Maps `path`. Refuses anything but a regular file before it can block (a FIFO is opened
// non-blocking, then fstat), and a file shorter than the 128-byte header; errors name the path.
MappedFile map_file(const std::filesystem::path& path);

// The header and section entries of a container whose §9 steps 1-7 passed, and whose section names
// are unique within each kind.
struct Container {
  format::FileHeader header{};
  std::vector<Section> sections;
};

// Runs §9 steps 1-7 on `bytes` and requires file kind `kind`; throws mosb::Error
// "DISPLAY_NAME: problem" (ErrorCode::not_mosb, version or damaged). O(section_count).
Container parse_container(std::span<const std::byte> bytes, std::string_view display_name,
                          format::FileKind kind);

// The header a file's first 128 bytes state, without any check but the magic: nullopt for bytes
// that do not start as a mosb file. Which reader to open it with and whether to decode it first,
// not a check (the reader of that kind runs §9).
std::optional<format::FileHeader> stated_header(std::span<const std::byte> bytes);
// The file kind stated_header states, or nullopt.
std::optional<format::FileKind> stated_file_kind(std::span<const std::byte> bytes);
// True when stated_header states a packed file (format::is_packed), whatever its kind.
bool stated_packed(std::span<const std::byte> bytes);

// What a reader of any file kind holds and offers: the bytes it reads (a mapping, memory it owns,
// or memory the caller keeps alive), the name its messages carry, the header and the table, and
// checked zero-copy access to a section's elements. GraphReader and SolutionReader add the checks
// and accessors of their kind.
class ContainerReader {
 public:
  const std::string& display_name() const { return display_name_; }
  const format::FileHeader& header() const { return header_; }
  std::span<const std::byte> bytes() const { return bytes_; }
  const std::vector<Section>& sections() const { return sections_; }
  std::string digest() const;  // §8 content digest, 32 hex digits

  // Zero-copy view of a section's elements, checked for type and encoding.
  template <class T>
  std::span<const T> values(const Section& s) const {
    check_access(s, format::element_type_of<T>());
    return {reinterpret_cast<const T*>(s.stored.data()), s.element_count()};
  }

 protected:
  ContainerReader() = default;
  // Holds `file` (the mapping or owned memory it came with) and parses its container as `kind`
  // (§9 steps 1-7); throws "DISPLAY_NAME: problem".
  void attach(MappedFile file, std::string display_name, format::FileKind kind);
  // The same over bytes the caller keeps alive, which must be 8-byte aligned (typed views of the
  // file's 64-byte offsets must land on aligned addresses).
  void attach_borrowed(std::span<const std::byte> bytes, std::string display_name,
                       format::FileKind kind);
  // Refuses a packed section (ErrorCode::packed) and another element type (invalid_argument).
  void check_access(const Section& s, format::ElementType wanted) const;
  [[noreturn]] void fail(const std::string& what) const;  // ErrorCode::damaged
  [[noreturn]] void fail(ErrorCode code, const std::string& what) const;
  // Calls f(std::span<const T>) with the elements of a section of a cost type T (unsigned or
  // float) and returns what f returns, one type for every T; other element types are refused.
  template <class F>
  decltype(auto) visit_cost_values(const Section& s, F&& f) const {
    using Result = std::invoke_result_t<F, std::span<const std::uint8_t>>;
    return format::visit_element_type(s.type, [&](auto tag) -> Result {
      using T = typename decltype(tag)::type;
      if constexpr (format::is_cost_type_v<T>)
        return std::invoke(std::forward<F>(f), values<T>(s));
      else
        fail("section '" + s.name + "' holds " + std::string(format::to_string(s.type)) +
             " values, not a cost type");
    });
  }

  std::shared_ptr<const void> mapping_;
  std::span<const std::byte> bytes_;
  std::string display_name_;
  format::FileHeader header_{};
  std::vector<Section> sections_;
};

// The §8 content digest (32 lowercase hex digits) of a section table: independent of layout and
// encoding, so a packed file and its unpacked form have the same digest.
std::string content_digest(std::span<const Section> sections);
// The same over the entries themselves (a writer's table, before any reader exists).
std::string content_digest(std::span<const format::SectionEntry> table);

}  // namespace mosb
