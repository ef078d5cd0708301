#include "mosb/container.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <iterator>
#include <unordered_set>

#include "mosb/error.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/sections_by_kind.hpp"
#include "mosb/internal/xxh3.hpp"

namespace mosb {

namespace {

std::string version_text(std::uint16_t major, std::uint16_t minor) {
  return std::to_string(major) + "." + std::to_string(minor);
}

// §6: encoding k (k >= 1) comes with required bit k - 1.
constexpr const char* kFeatureNames[] = {"zstd-sections", "shuffle-sections", "delta-sections",
                                         "transpose-sections"};
static_assert(std::size(kFeatureNames) == format::kLastEncoding);

bool mul_overflows(std::uint64_t a, std::uint64_t b, std::uint64_t& out) {
  return __builtin_mul_overflow(a, b, &out);
}

const char* file_type_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Throws "NAME: what", as every check of the container does.
struct Failure {
  std::string_view name;
  [[noreturn]] void operator()(const std::string& what) const { (*this)(ErrorCode::damaged, what); }
  [[noreturn]] void operator()(ErrorCode code, const std::string& what) const {
    throw Error(code, std::string(name) + ": " + what);
  }
};

}  // namespace

MappedFile map_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer, before fstat could
  // tell what it is. Reads go through mmap, which the flag does not affect.
  int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw Error(ErrorCode::io, name + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    throw Error(ErrorCode::io, name + ": cannot stat: " + std::strerror(error));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    throw Error(ErrorCode::not_mosb,
                name + ": is " + std::string(file_type_name(st.st_mode)) +
                    ", not a regular file; a mosb file must be a regular file");
  }
  const auto size = static_cast<std::size_t>(st.st_size);
  if (size < format::kHeaderSize) {
    ::close(fd);
    throw Error(ErrorCode::not_mosb, name + ": not a mosb file: " + std::to_string(size) +
                                         " bytes is shorter than the 128-byte header");
  }
  void* address = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  if (address == MAP_FAILED)
    throw Error(ErrorCode::io, name + ": cannot map: " + std::strerror(errno));
  MappedFile file;
  file.owner = std::shared_ptr<const void>(
      address, [size](const void* p) { ::munmap(const_cast<void*>(p), size); });
  file.bytes = {static_cast<const std::byte*>(address), size};
  return file;
}

namespace {

// §9 step 1: the magic and byte-order mark, naming the usual ways a transfer damages them.
void check_identity(const format::FileHeader& header, const Failure& fail) {
  const auto& magic = header.magic;
  if (!std::equal(magic.begin(), magic.end(), format::kMagic.begin())) {
    if (std::equal(magic.begin(), magic.end(), format::kMagic.rbegin()))
      fail(
          "byte-swapped mosb file (its magic is reversed); it was written or copied with the wrong "
          "byte order");
    const bool mos = magic[1] == 'M' && magic[2] == 'O' && magic[3] == 'S';
    if (mos && magic[0] == format::kMagic[0])
      fail(
          "mosb file damaged by a text-mode transfer (line-end bytes in the magic were changed); "
          "copy it in binary mode");
    if (mos && magic[0] == (format::kMagic[0] & 0x7F))
      fail(
          "mosb file damaged by a 7-bit transfer (the high bit of its first byte was cleared); "
          "copy it in binary mode");
    fail(ErrorCode::not_mosb, "not a mosb file (wrong magic)");
  }
  if (header.byte_order_mark != format::kByteOrderMark)
    fail("byte-swapped mosb file (byte-order mark reads " + hex64(header.byte_order_mark) + ")");
}

// §9 step 2: a format this reader reads, a 128-byte header, the kind the caller asked for.
void check_version_and_kind(const format::FileHeader& header, format::FileKind kind,
                            const Failure& fail) {
  if (header.version_major != format::kVersionMajor)
    fail(ErrorCode::version,
         "prepared with format " + version_text(header.version_major, header.version_minor) +
             ", this reader reads format " + std::to_string(format::kVersionMajor) + ".x (up to " +
             version_text(format::kVersionMajor, format::kVersionMinor) + ")");
  if (header.header_size != format::kHeaderSize)
    fail("header size " + std::to_string(header.header_size) + " is not 128");
  if (header.file_kind != static_cast<std::uint32_t>(kind)) {
    // A known kind in the wrong place is a caller's mistake; an unknown kind, damage.
    const auto found = format::to_string(static_cast<format::FileKind>(header.file_kind));
    fail(found.empty() ? ErrorCode::damaged : ErrorCode::invalid_argument,
         "file kind " + std::to_string(header.file_kind) +
             (found.empty() ? "" : " (" + std::string(found) + ")") + " is not a " +
             std::string(format::to_string(kind)) + " (" +
             std::to_string(static_cast<std::uint32_t>(kind)) + ")");
  }
}

// §9 steps 3 and 4: the file is as long as it says, and the table ends it. Returns the table's
// size in bytes.
std::uint64_t check_extent(const format::FileHeader& header, std::uint64_t file_bytes,
                           const Failure& fail) {
  if (header.file_size != file_bytes)
    fail(header.file_size > file_bytes
             ? "truncated: header says " + std::to_string(header.file_size) + " bytes, file has " +
                   std::to_string(file_bytes)
             : "extended: header says " + std::to_string(header.file_size) + " bytes, file has " +
                   std::to_string(file_bytes));
  std::uint64_t table_bytes = 0;
  if (header.table_offset % format::kAlignment != 0 || header.table_offset < format::kHeaderSize)
    fail("section table offset " + std::to_string(header.table_offset) +
         " is not a 64-aligned offset after the header");
  if (mul_overflows(header.section_count, sizeof(format::SectionEntry), table_bytes) ||
      header.table_offset > file_bytes || table_bytes != file_bytes - header.table_offset)
    fail("section table (" + std::to_string(header.section_count) + " entries at offset " +
         std::to_string(header.table_offset) + ") does not end at the end of the file (" +
         std::to_string(file_bytes) + " bytes)");
  return table_bytes;
}

// §9 step 5: the checksum covers the header up to itself and the whole section table.
void check_header_checksum(std::span<const std::byte> bytes, const format::FileHeader& header,
                           const std::byte* table, std::uint64_t table_bytes, const Failure& fail) {
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  XXH3_64bits_update(state, bytes.data(), format::kHeaderChecksumOffset);
  XXH3_64bits_update(state, table, table_bytes);
  const std::uint64_t computed = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  if (computed != header.header_checksum)
    fail("header checksum mismatch (stored " + hex64(header.header_checksum) + ", computed " +
         hex64(computed) + "): header or section table is damaged");
}

// §9 step 6: a required feature this reader does not know is refused by its bit number.
void check_known_features(const format::FileHeader& header, const Failure& fail) {
  if (std::uint64_t unknown = header.required_features & ~format::kKnownRequiredFeatures) {
    const int bit = std::countr_zero(unknown);
    fail(ErrorCode::version, "requires feature bit " + std::to_string(bit) +
                                 ", unknown to this reader (format " +
                                 version_text(format::kVersionMajor, format::kVersionMinor) + ")");
  }
}

// §9 step 7, an entry's encoding: declared by its feature bit and consistent with its stored
// length. Returns the feature bit the entry uses (0 for raw).
std::uint64_t check_encoding(const Section& s, const format::FileHeader& header,
                             format::FileKind kind, const std::string& label, const Failure& fail) {
  const auto& e = s.entry;
  if (e.encoding == static_cast<std::uint8_t>(format::Encoding::raw)) {
    if (e.stored_length != s.decoded_length)
      fail(label + ": stored length " + std::to_string(e.stored_length) + " differs from " +
           std::to_string(s.decoded_length) + " bytes of elements");
    return 0;
  }
  if (e.encoding > format::kLastEncoding)
    fail(label + ": unknown encoding " + std::to_string(e.encoding));
  const auto encoding = static_cast<format::Encoding>(e.encoding);
  const std::uint64_t bit = format::feature_of(encoding);
  if (!(header.required_features & bit))
    fail(label + ": " + std::string(format::to_string(encoding)) + "-encoded (encoding " +
         std::to_string(e.encoding) + ") but the header lacks the " +
         kFeatureNames[std::countr_zero(bit)] + " feature (bit " +
         std::to_string(std::countr_zero(bit)) + ")");
  if (encoding == format::Encoding::transpose) {
    // Derived at decoding from the forward CSR (§6), so only the reverse CSR may be.
    const bool reverse = s.kind == format::SectionKind::reverse_offsets ||
                         s.kind == format::SectionKind::reverse_sources ||
                         s.kind == format::SectionKind::reverse_arcs;
    if (!reverse || kind != format::FileKind::instance)
      fail(label + ": transpose encoding of a section that is not part of the reverse CSR");
    if (e.stored_length != 0)
      fail(label + ": transpose-encoded with stored length " + std::to_string(e.stored_length) +
           ", not 0");
  } else if (e.stored_length == 0) {
    fail(label + ": zstd-encoded with stored length 0");
  }
  if (encoding == format::Encoding::delta_zstd && format::is_float(s.type))
    fail(label + ": delta encoding of a float column");
  return bit;
}

// §9 step 7: one table entry, checked and resolved into a Section. Adds the feature bit its
// encoding uses to used_features.
Section read_entry(std::span<const std::byte> bytes, const format::FileHeader& header,
                   const std::byte* table, std::uint32_t i, format::FileKind kind,
                   std::uint64_t& used_features, const Failure& fail) {
  Section s{};
  std::memcpy(&s.entry, table + i * sizeof(format::SectionEntry), sizeof s.entry);
  const auto& e = s.entry;
  const std::string where = "section #" + std::to_string(i);
  s.name = std::string(format::name_of(e));
  for (std::size_t k = s.name.size(); k < format::kNameSize; ++k)
    if (e.name[k] != '\0') fail(where + ": name has bytes after its NUL padding");
  if (!format::is_valid_section_name(s.name))
    fail(where + ": invalid name (" + std::string(format::kSectionNameRule) + ")");
  const std::string label = "section '" + s.name + "'";
  auto type = format::element_type_from(e.element_type);
  if (!type) fail(label + ": unknown element type " + std::to_string(e.element_type));
  s.type = *type;
  s.kind = format::section_kind_from(e.kind);
  if (e.row_width == 0) fail(label + ": row width 0");
  std::uint64_t elements = 0;
  if (mul_overflows(e.row_count, e.row_width, elements) ||
      mul_overflows(elements, format::element_size(s.type), s.decoded_length))
    fail(label + ": size overflows");
  used_features |= check_encoding(s, header, kind, label, fail);
  if (e.offset % format::kAlignment != 0)
    fail(label + ": offset " + std::to_string(e.offset) + " is not 64-byte aligned");
  if (e.offset < format::kHeaderSize || e.offset > header.table_offset ||
      e.stored_length > header.table_offset - e.offset)
    fail(label + ": bytes " + std::to_string(e.offset) + "+" + std::to_string(e.stored_length) +
         " lie outside the data area [128, " + std::to_string(header.table_offset) + ")");
  s.stored = bytes.subspan(e.offset, e.stored_length);
  return s;
}

// §9 step 6, the other direction: every declared feature is used by some section.
void check_features_used(const format::FileHeader& header, std::uint64_t used_features,
                         const Failure& fail) {
  if (std::uint64_t unused = header.required_features & ~used_features) {
    const int bit = std::countr_zero(unused);
    fail("header declares " + std::string(kFeatureNames[bit]) + " but no section is " +
         std::string(format::to_string(static_cast<format::Encoding>(bit + 1))) + "-encoded");
  }
}

// §9 step 7: no two payloads overlap; sorting by offset makes it one pass over neighbours.
void check_no_overlap(const std::vector<Section>& sections, const Failure& fail) {
  std::vector<const Section*> by_offset;
  for (const auto& s : sections)
    if (s.entry.stored_length > 0) by_offset.push_back(&s);
  std::sort(by_offset.begin(), by_offset.end(),
            [](auto* a, auto* b) { return a->entry.offset < b->entry.offset; });
  for (std::size_t i = 1; i < by_offset.size(); ++i) {
    const auto& prev = by_offset[i - 1]->entry;
    if (prev.offset + prev.stored_length > by_offset[i]->entry.offset)
      fail("sections '" + by_offset[i - 1]->name + "' and '" + by_offset[i]->name + "' overlap");
  }
}

// Names are unique within a kind (§4), known or not: one hash set keeps open O(section_count).
void check_unique_names(const std::vector<Section>& sections, const Failure& fail) {
  std::unordered_set<std::string> seen;
  seen.reserve(sections.size());
  for (const auto& s : sections) {
    std::string key(reinterpret_cast<const char*>(&s.entry.kind), sizeof s.entry.kind);
    key += s.name;
    if (!seen.insert(std::move(key)).second)
      fail("section '" + s.name + "': a second " +
           (s.kind ? std::string(format::to_string(*s.kind))
                   : "kind " + std::to_string(s.entry.kind)) +
           " section of that name");
  }
}

}  // namespace

std::optional<format::FileHeader> stated_header(std::span<const std::byte> bytes) {
  format::FileHeader header{};
  if (bytes.size() < sizeof header) return std::nullopt;
  std::memcpy(&header, bytes.data(), sizeof header);
  if (header.magic != format::kMagic) return std::nullopt;
  return header;
}

std::optional<format::FileKind> stated_file_kind(std::span<const std::byte> bytes) {
  const auto header = stated_header(bytes);
  if (!header) return std::nullopt;
  return static_cast<format::FileKind>(header->file_kind);
}

bool stated_packed(std::span<const std::byte> bytes) {
  const auto header = stated_header(bytes);
  return header && format::is_packed(*header);
}

// The open checks of spec/FORMAT.md §9, steps 1 to 7 and the name rule of step 8, in that order.
Container parse_container(std::span<const std::byte> bytes, std::string_view display_name,
                          format::FileKind kind) {
  const Failure fail{display_name};
  Container result;
  auto& header = result.header;
  auto& sections = result.sections;
  if (bytes.size() < format::kHeaderSize)
    fail(ErrorCode::not_mosb, "not a mosb file: " + std::to_string(bytes.size()) +
                                  " bytes is shorter than the 128-byte header");
  std::memcpy(&header, bytes.data(), sizeof header);

  check_identity(header, fail);
  check_version_and_kind(header, kind, fail);
  const std::uint64_t table_bytes = check_extent(header, bytes.size(), fail);
  const std::byte* table = bytes.data() + header.table_offset;
  check_header_checksum(bytes, header, table, table_bytes, fail);
  check_known_features(header, fail);

  sections.clear();
  sections.reserve(header.section_count);
  std::uint64_t used_features = 0;
  for (std::uint32_t i = 0; i < header.section_count; ++i)
    sections.push_back(read_entry(bytes, header, table, i, kind, used_features, fail));
  check_features_used(header, used_features, fail);
  check_no_overlap(sections, fail);
  check_unique_names(sections, fail);
  return result;
}

std::string content_digest(std::span<const format::SectionEntry> table) {
  std::vector<format::SectionEntry> normalized(table.begin(), table.end());
  for (auto& e : normalized) {
    e.encoding = 0;
    e.offset = 0;
    e.stored_length = 0;
  }
  const XXH128_hash_t hash =
      XXH3_128bits(normalized.data(), normalized.size() * sizeof(format::SectionEntry));
  return hex64(hash.high64) + hex64(hash.low64);
}

std::string content_digest(std::span<const Section> sections) {
  std::vector<format::SectionEntry> table;
  table.reserve(sections.size());
  for (const auto& s : sections) table.push_back(s.entry);
  return content_digest(table);
}

std::string ContainerReader::digest() const {
  return content_digest(sections_);
}

void ContainerReader::attach(MappedFile file, std::string display_name, format::FileKind kind) {
  mapping_ = std::move(file.owner);
  attach_borrowed(file.bytes, std::move(display_name), kind);
}

void ContainerReader::attach_borrowed(std::span<const std::byte> bytes, std::string display_name,
                                      format::FileKind kind) {
  if (reinterpret_cast<std::uintptr_t>(bytes.data()) % alignof(std::uint64_t) != 0)
    throw Error(display_name + ": internal error: buffer is not 8-byte aligned");
  bytes_ = bytes;
  display_name_ = std::move(display_name);
  auto container = parse_container(bytes_, display_name_, kind);
  header_ = container.header;
  sections_ = std::move(container.sections);
}

void ContainerReader::check_access(const Section& s, format::ElementType wanted) const {
  if (s.is_packed())
    fail(ErrorCode::packed, "section '" + s.name +
                                "' is zstd-packed and cannot be mapped zero-copy; unpack the "
                                "file first");
  if (s.type != wanted)
    fail(ErrorCode::invalid_argument, "section '" + s.name + "' holds " +
                                          std::string(format::to_string(s.type)) + " values, not " +
                                          std::string(format::to_string(wanted)));
}

void ContainerReader::fail(const std::string& what) const {
  fail(ErrorCode::damaged, what);
}
void ContainerReader::fail(ErrorCode code, const std::string& what) const {
  throw Error(code, display_name_ + ": " + what);
}

SectionsByKind::SectionsByKind(std::span<const Section> sections, std::string_view display_name)
    : sections_(sections), display_name_(display_name) {
  for (std::size_t i = 0; i < sections.size(); ++i)
    if (sections[i].kind) indices_[static_cast<std::size_t>(*sections[i].kind)].push_back(i);
}

std::size_t SectionsByKind::single(format::SectionKind kind) const {
  const auto found = all(kind);
  if (found.empty()) return SIZE_MAX;
  if (found.size() > 1)
    fail(sections_[found[1]], "a second " + std::string(format::to_string(kind)) + " section");
  return found[0];
}

std::size_t SectionsByKind::single(format::SectionKind kind, format::ElementType type) const {
  const auto found = all(kind);
  if (!found.empty()) expect_shape(sections_[found[0]], type);
  return single(kind);
}

void SectionsByKind::expect_shape(const Section& s, format::ElementType type) const {
  if (s.type != type || s.entry.row_width != 1)
    fail(s, "must be " + std::string(format::to_string(type)) + " x 1");
}

void SectionsByKind::expect_cost_column(const Section& s) const {
  if (!format::is_unsigned(s.type) && !format::is_float(s.type))
    fail(s, "cost type " + std::string(format::to_string(s.type)) + " is not unsigned or float");
  if (s.entry.row_width != 1) fail(s, "cost columns have width 1");
}

void SectionsByKind::fail(const Section& s, const std::string& what) const {
  throw Error(ErrorCode::damaged,
              std::string(display_name_) + ": section '" + s.name + "': " + what);
}

}  // namespace mosb
