// The container every mosb file kind shares (spec/FORMAT.md §1-§6): mapping a file, and the checks
// of §9 steps 1-7 that hold whatever the file kind. Readers of a kind (GraphReader, and the readers
// of later file kinds) add their own checks of the sections on top of this one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

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

// The §8 content digest (32 lowercase hex digits) of a section table: independent of layout and
// encoding, so a packed file and its unpacked form have the same digest.
std::string content_digest(std::span<const Section> sections);
// The same over the entries themselves (a writer's table, before any reader exists).
std::string content_digest(std::span<const format::SectionEntry> table);

}  // namespace mosb
