// Streams sections into a new mosb file. The file appears under its final name only when commit()
// succeeds; until then it lives under a temporary name in the same directory, removed on failure
// (mosb::AtomicFile, whose header states the guarantees).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/atomic_file.hpp"
#include "mosb/format.hpp"

struct XXH3_state_s;

namespace mosb {

class FileWriter {
 public:
  explicit FileWriter(std::filesystem::path target,
                      AtomicFile::Existing existing = AtomicFile::Existing::replace);
  ~FileWriter();
  FileWriter(const FileWriter&) = delete;
  FileWriter& operator=(const FileWriter&) = delete;

  void begin_section(format::SectionKind kind, std::string_view name, format::ElementType type,
                     std::uint32_t row_width);
  void append(std::span<const std::byte> bytes);
  template <class T>
  void append_values(std::span<const T> values) {
    append(std::as_bytes(values));
  }
  void end_section();

  template <class T>
  void add_section(format::SectionKind kind, std::string_view name, std::uint32_t row_width,
                   std::span<const T> values) {
    begin_section(kind, name, format::element_type_of<T>(), row_width);
    append_values(values);
    end_section();
  }

  // The file kind written at commit (default: instance).
  void set_file_kind(format::FileKind kind) { file_kind_ = kind; }
  // Raises the header's version_minor to at least `minor` (default 0): a writer calls it for each
  // feature newer than 1.0 it uses, so the file states the lowest minor that can read it (§2).
  void require_minor(std::uint16_t minor) { version_minor_ = std::max(version_minor_, minor); }
  // Makes commit() refuse (throwing mosb::Error that shows both digests, writing nothing under the
  // target's name) a file whose content digest is not `digest`; empty: no expectation.
  void expect_digest(std::string_view digest) { expected_digest_ = digest; }
  // Makes commit() call `check` with the temporary file, complete (table and header written),
  // before renaming it into place; a check that throws leaves the target untouched and the
  // temporary removed. Empty: no check.
  void check_before_commit(std::function<void(const std::filesystem::path& temporary)> check) {
    check_ = std::move(check);
  }

  // Adds a section whose bytes are already stored as they go on disk (say, one zstd frame): `entry`
  // gives the name, kind, type, width, row count, encoding and the checksum of the decoded
  // elements; the offset and stored length are set here. The encoding's required
  // feature bit is set, and the version the file needs.
  void add_encoded_section(const format::SectionEntry& entry, std::span<const std::byte> stored);

  // Writes the table and header, then renames the file into place. objective_count counts the
  // `cost` sections (instance) or the `front_cost` sections (solution file).
  void commit(std::uint64_t vertex_count, std::uint64_t arc_count);

 private:
  void write_at_end(const void* data, std::size_t size);
  void flush_buffer();
  [[noreturn]] void fail(const std::string& what) const;

  AtomicFile file_;
  std::uint64_t position_ = 0;  // bytes written or buffered so far
  std::vector<std::byte> buffer_;
  std::vector<format::SectionEntry> table_;
  bool in_section_ = false;
  std::uint64_t section_bytes_ = 0;
  std::uint64_t required_features_ = 0;
  XXH3_state_s* hash_state_ = nullptr;
  format::FileKind file_kind_ = format::FileKind::instance;
  std::uint16_t version_minor_ = 0;
  std::string expected_digest_;
  std::function<void(const std::filesystem::path&)> check_;
};

}  // namespace mosb
