#include "mosb/file_writer.hpp"

#include <algorithm>

#include "mosb/container.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/xxh3.hpp"
#include "mosb/metadata.hpp"

namespace mosb {

namespace {
constexpr std::size_t kBufferSize = 1 << 20;
}

FileWriter::FileWriter(std::filesystem::path target, AtomicFile::Existing existing)
    : file_(std::move(target), existing) {
  hash_state_ = XXH3_createState();
  buffer_.reserve(kBufferSize);
  // The header is written last, at commit; until then its bytes are zero, so a partial file never
  // carries a valid magic.
  std::byte zeros[format::kHeaderSize] = {};
  write_at_end(zeros, sizeof zeros);
}

FileWriter::~FileWriter() {
  XXH3_freeState(hash_state_);
}

void FileWriter::fail(const std::string& what) const {
  throw Error(file_.target().string() + ": " + what);
}

void FileWriter::flush_buffer() {
  file_.write(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void FileWriter::write_at_end(const void* data, std::size_t size) {
  const auto* bytes = static_cast<const std::byte*>(data);
  position_ += size;
  while (size > 0) {
    std::size_t chunk = std::min(size, kBufferSize - buffer_.size());
    buffer_.insert(buffer_.end(), bytes, bytes + chunk);
    bytes += chunk;
    size -= chunk;
    if (buffer_.size() == kBufferSize) flush_buffer();
  }
}

void FileWriter::begin_section(format::SectionKind kind, std::string_view name,
                               format::ElementType type, std::uint32_t row_width) {
  if (in_section_) fail("internal error: section '" + std::string(name) + "' begun inside another");
  if (!format::is_valid_section_name(name))
    fail("invalid section name '" + std::string(name) + "' (" +
         std::string(format::kSectionNameRule) + ")");
  if (row_width == 0) fail("section '" + std::string(name) + "' has row width 0");
  static constexpr std::byte zeros[format::kAlignment] = {};
  write_at_end(zeros, format::align_up(position_) - position_);

  format::SectionEntry entry{};
  std::copy(name.begin(), name.end(), entry.name.begin());
  entry.kind = static_cast<std::uint16_t>(kind);
  entry.element_type = static_cast<std::uint8_t>(type);
  entry.encoding = static_cast<std::uint8_t>(format::Encoding::raw);
  entry.row_width = row_width;
  entry.offset = position_;
  table_.push_back(entry);
  in_section_ = true;
  section_bytes_ = 0;
  XXH3_64bits_reset(hash_state_);
}

void FileWriter::append(std::span<const std::byte> bytes) {
  if (!in_section_) fail("internal error: data written outside a section");
  XXH3_64bits_update(hash_state_, bytes.data(), bytes.size());
  write_at_end(bytes.data(), bytes.size());
  section_bytes_ += bytes.size();
}

void FileWriter::end_section() {
  auto& entry = table_.back();
  const std::uint64_t row_bytes =
      entry.row_width * format::element_size(static_cast<format::ElementType>(entry.element_type));
  if (section_bytes_ % row_bytes != 0)
    fail("internal error: section '" + std::string(format::name_of(entry)) +
         "' is not a whole number of rows");
  entry.row_count = section_bytes_ / row_bytes;
  entry.stored_length = section_bytes_;
  entry.checksum = XXH3_64bits_digest(hash_state_);
  in_section_ = false;
}

void FileWriter::add_encoded_section(const format::SectionEntry& entry,
                                     std::span<const std::byte> stored) {
  if (in_section_)
    fail("internal error: section '" + std::string(format::name_of(entry)) +
         "' added inside another");
  static constexpr std::byte zeros[format::kAlignment] = {};
  write_at_end(zeros, format::align_up(position_) - position_);
  auto& added = table_.emplace_back(entry);
  added.offset = position_;
  added.stored_length = stored.size();
  required_features_ |= format::feature_of(static_cast<format::Encoding>(entry.encoding));
  write_at_end(stored.data(), stored.size());
}

void FileWriter::commit(std::uint64_t vertex_count, std::uint64_t arc_count) {
  if (in_section_) fail("internal error: commit inside a section");
  static constexpr std::byte zeros[format::kAlignment] = {};
  write_at_end(zeros, format::align_up(position_) - position_);

  format::FileHeader header{};
  std::copy(format::kMagic.begin(), format::kMagic.end(), header.magic.begin());
  header.byte_order_mark = format::kByteOrderMark;
  header.version_major = format::kVersionMajor;
  header.version_minor =
      std::max(version_minor_, format::minimum_version_minor(required_features_));
  header.header_size = format::kHeaderSize;
  header.file_kind = static_cast<std::uint32_t>(file_kind_);
  header.required_features = required_features_;
  header.table_offset = position_;
  header.section_count = static_cast<std::uint32_t>(table_.size());
  header.file_size = position_ + table_.size() * sizeof(format::SectionEntry);
  const auto objective_kind = file_kind_ == format::FileKind::solutions
                                  ? format::SectionKind::front_cost
                                  : format::SectionKind::cost;
  header.objective_count =
      static_cast<std::uint32_t>(std::count_if(table_.begin(), table_.end(), [&](const auto& e) {
        return e.kind == static_cast<std::uint16_t>(objective_kind);
      }));
  header.vertex_count = vertex_count;
  header.arc_count = arc_count;

  write_at_end(table_.data(), table_.size() * sizeof(format::SectionEntry));
  flush_buffer();

  XXH3_64bits_reset(hash_state_);
  XXH3_64bits_update(hash_state_, &header, format::kHeaderChecksumOffset);
  XXH3_64bits_update(hash_state_, table_.data(), table_.size() * sizeof(format::SectionEntry));
  header.header_checksum = XXH3_64bits_digest(hash_state_);

  if (!expected_digest_.empty()) {
    const auto digest = content_digest(table_);
    if (digest != expected_digest_)
      throw Error(ErrorCode::other, {file_.target().string() + ": content digest " + digest +
                                         ", but " + expected_digest_ + " was expected (",
                                     setting("expect_digest"), "); nothing written"});
  }
  file_.write_at(&header, sizeof header, 0);
  if (check_) check_(file_.temporary());
  file_.commit();
}

}  // namespace mosb
