#include "mosb/graph_reader.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <unordered_set>

#include "mosb/hex.hpp"
#include "mosb/verify.hpp"
#include "xxh3.hpp"

namespace mosb {

using format::ElementType;
using format::SectionKind;

namespace {

std::string version_text(std::uint16_t major, std::uint16_t minor) {
  return std::to_string(major) + "." + std::to_string(minor);
}

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

bool mul_overflows(std::uint64_t a, std::uint64_t b, std::uint64_t& out) {
  return __builtin_mul_overflow(a, b, &out);
}

}  // namespace

void GraphReader::fail(const std::string& what) const {
  fail(ErrorCode::damaged, what);
}
void GraphReader::fail(ErrorCode code, const std::string& what) const {
  throw Error(code, display_name_ + ": " + what);
}

namespace {
const char* file_type_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}
}  // namespace

GraphReader GraphReader::open(const std::filesystem::path& path) {
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
  GraphReader reader;
  reader.mapping_ = std::shared_ptr<const void>(
      address, [size](const void* p) { ::munmap(const_cast<void*>(p), size); });
  reader.bytes_ = {static_cast<const std::byte*>(address), size};
  reader.display_name_ = name;
  reader.validate();
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

void GraphReader::require_verified(VerifyLevel level, std::string_view user) const {
  if (!covers(verified_level_, level))
    fail(ErrorCode::invalid_argument,
         std::string(user) +
             " walks the payload and needs a reader opened with GraphReader::open(path, level)");
}

GraphReader GraphReader::from_memory(std::span<const std::byte> bytes, std::string display_name) {
  // Typed views need the file's 64-byte offsets to land on 8-byte boundaries in memory.
  if (reinterpret_cast<std::uintptr_t>(bytes.data()) % alignof(std::uint64_t) != 0)
    throw Error(display_name + ": internal error: buffer is not 8-byte aligned");
  GraphReader reader;
  reader.bytes_ = bytes;
  reader.display_name_ = std::move(display_name);
  reader.validate();
  return reader;
}

void GraphReader::validate() {
  if (bytes_.size() < format::kHeaderSize)
    fail(ErrorCode::not_mosb, "not a mosb file: " + std::to_string(bytes_.size()) +
                                  " bytes is shorter than the 128-byte header");
  std::memcpy(&header_, bytes_.data(), sizeof header_);

  // 1. Identity.
  const auto& magic = header_.magic;
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
  if (header_.byte_order_mark != format::kByteOrderMark)
    fail("byte-swapped mosb file (byte-order mark reads " + hex64(header_.byte_order_mark) + ")");
  // 2. Version and kind.
  if (header_.version_major != format::kVersionMajor)
    fail(ErrorCode::version,
         "prepared with format " + version_text(header_.version_major, header_.version_minor) +
             ", this reader reads format " + std::to_string(format::kVersionMajor) + ".x (up to " +
             version_text(format::kVersionMajor, format::kVersionMinor) + ")");
  if (header_.header_size != format::kHeaderSize)
    fail("header size " + std::to_string(header_.header_size) + " is not 128");
  if (header_.file_kind != static_cast<std::uint32_t>(format::FileKind::instance))
    fail("file kind " + std::to_string(header_.file_kind) + " is not a graph instance (1)");
  // 3. Truncation.
  if (header_.file_size != bytes_.size())
    fail(header_.file_size > bytes_.size()
             ? "truncated: header says " + std::to_string(header_.file_size) + " bytes, file has " +
                   std::to_string(bytes_.size())
             : "extended: header says " + std::to_string(header_.file_size) + " bytes, file has " +
                   std::to_string(bytes_.size()));
  // 4. Table bounds.
  std::uint64_t table_bytes = 0;
  if (header_.table_offset % format::kAlignment != 0 || header_.table_offset < format::kHeaderSize)
    fail("section table offset " + std::to_string(header_.table_offset) +
         " is not a 64-aligned offset after the header");
  if (mul_overflows(header_.section_count, sizeof(format::SectionEntry), table_bytes) ||
      header_.table_offset > bytes_.size() || table_bytes != bytes_.size() - header_.table_offset)
    fail("section table (" + std::to_string(header_.section_count) + " entries at offset " +
         std::to_string(header_.table_offset) + ") does not end at the end of the file (" +
         std::to_string(bytes_.size()) + " bytes)");
  // 5. Header checksum.
  const std::byte* table = bytes_.data() + header_.table_offset;
  {
    XXH3_state_t* state = XXH3_createState();
    XXH3_64bits_reset(state);
    XXH3_64bits_update(state, bytes_.data(), format::kHeaderChecksumOffset);
    XXH3_64bits_update(state, table, table_bytes);
    const std::uint64_t computed = XXH3_64bits_digest(state);
    XXH3_freeState(state);
#ifndef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION  // lets the fuzzer reach the checks behind it
    if (computed != header_.header_checksum)
#else
    if (computed != header_.header_checksum && false)
#endif
      fail("header checksum mismatch (stored " + hex64(header_.header_checksum) + ", computed " +
           hex64(computed) + "): header or section table is damaged");
  }
  // 6. Features.
  if (std::uint64_t unknown = header_.required_features & ~format::kKnownRequiredFeatures) {
    const int bit = std::countr_zero(unknown);
    fail(ErrorCode::version, "requires feature bit " + std::to_string(bit) +
                                 ", unknown to this reader (format " +
                                 version_text(format::kVersionMajor, format::kVersionMinor) + ")");
  }

  // 7. Entries.
  sections_.clear();
  sections_.reserve(header_.section_count);
  bool any_packed = false;
  for (std::uint32_t i = 0; i < header_.section_count; ++i) {
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
    if (e.encoding == static_cast<std::uint8_t>(format::Encoding::raw)) {
      if (e.stored_length != s.decoded_length)
        fail(label + ": stored length " + std::to_string(e.stored_length) + " differs from " +
             std::to_string(s.decoded_length) + " bytes of elements");
    } else if (e.encoding == static_cast<std::uint8_t>(format::Encoding::zstd)) {
      if (!(header_.required_features & format::kFeatureZstdSections))
        fail(label + ": zstd-encoded but the header lacks the zstd-sections feature");
      if (e.stored_length == 0) fail(label + ": zstd-encoded with stored length 0");
      any_packed = true;
    } else {
      fail(label + ": unknown encoding " + std::to_string(e.encoding));
    }
    if (e.offset % format::kAlignment != 0)
      fail(label + ": offset " + std::to_string(e.offset) + " is not 64-byte aligned");
    if (e.offset < format::kHeaderSize || e.offset > header_.table_offset ||
        e.stored_length > header_.table_offset - e.offset)
      fail(label + ": bytes " + std::to_string(e.offset) + "+" + std::to_string(e.stored_length) +
           " lie outside the data area [128, " + std::to_string(header_.table_offset) + ")");
    s.stored = bytes_.subspan(e.offset, e.stored_length);
    sections_.push_back(std::move(s));
  }
  if ((header_.required_features & format::kFeatureZstdSections) && !any_packed)
    fail("header declares zstd-sections but no section is zstd-encoded");
  {
    std::vector<const Section*> by_offset;
    for (const auto& s : sections_)
      if (s.entry.stored_length > 0) by_offset.push_back(&s);
    std::sort(by_offset.begin(), by_offset.end(),
              [](auto* a, auto* b) { return a->entry.offset < b->entry.offset; });
    for (std::size_t i = 1; i < by_offset.size(); ++i) {
      const auto& prev = by_offset[i - 1]->entry;
      if (prev.offset + prev.stored_length > by_offset[i]->entry.offset)
        fail("sections '" + by_offset[i - 1]->name + "' and '" + by_offset[i]->name + "' overlap");
    }
  }

  // 8. Kinds, counts and names.
  const std::uint64_t n = header_.vertex_count, m = header_.arc_count;
  if (n >= 0xFFFFFFFFULL || m >= 0xFFFFFFFFULL)
    fail("vertex count " + std::to_string(n) + " or arc count " + std::to_string(m) +
         " exceeds the format limit of 2^32-2");
  // Names are unique within a kind (§4), known or not: one hash set keeps open O(section_count).
  {
    std::unordered_set<std::string> seen;
    seen.reserve(sections_.size());
    for (const auto& s : sections_) {
      std::string key(reinterpret_cast<const char*>(&s.entry.kind), sizeof s.entry.kind);
      key += s.name;
      if (!seen.insert(std::move(key)).second)
        fail("section '" + s.name + "': a second " +
             (s.kind ? std::string(format::to_string(*s.kind))
                     : "kind " + std::to_string(s.entry.kind)) +
             " section of that name");
    }
  }
  std::fill(std::begin(structural_), std::end(structural_), SIZE_MAX);
  std::size_t metadata_index = SIZE_MAX;
  cost_indices_.clear();
  for (std::size_t i = 0; i < sections_.size(); ++i) {
    const auto& s = sections_[i];
    if (!s.kind) continue;  // a later minor's kind: ignored
    const std::string label = "section '" + s.name + "'";
    auto expect = [&](bool ok, const std::string& what) {
      if (!ok) fail(label + ": " + what);
    };
    auto expect_rows = [&](std::uint64_t rows, const char* what) {
      expect(s.entry.row_count == rows, "has " + std::to_string(s.entry.row_count) + " rows, but " +
                                            what + " is " + std::to_string(rows));
    };
    const auto k = *s.kind;
    switch (k) {
      case SectionKind::metadata:
        expect(metadata_index == SIZE_MAX, "a second metadata section");
        expect(s.type == ElementType::u8 && s.entry.row_width == 1, "metadata must be u8 x 1");
        metadata_index = i;
        break;
      case SectionKind::cost:
        expect(format::is_unsigned(s.type) || format::is_float(s.type),
               "cost type " + std::string(format::to_string(s.type)) + " is not unsigned or float");
        expect(s.entry.row_width == 1, "cost columns have width 1");
        expect_rows(m, "the arc count");
        cost_indices_.push_back(i);
        break;
      case SectionKind::vertex_data:
        expect_rows(n, "the vertex count");
        break;
      case SectionKind::arc_data:
        expect_rows(m, "the arc count");
        break;
      case SectionKind::queries:
        expect(s.type == ElementType::u32 && s.entry.row_width == 2, "queries must be u32 x 2");
        break;
      default:
        for (const auto& shape : kStructural)
          if (shape.kind == k) {
            const auto slot = static_cast<std::size_t>(k);
            expect(structural_[slot] == SIZE_MAX,
                   "a second " + std::string(format::to_string(k)) + " section");
            expect(s.type == shape.type && s.entry.row_width == 1,
                   "must be " + std::string(format::to_string(shape.type)) + " x 1");
            expect_rows(shape.per_vertex_plus_one ? n + 1 : m,
                        shape.per_vertex_plus_one ? "the vertex count + 1" : "the arc count");
            structural_[slot] = i;
          }
    }
  }
  if (metadata_index == SIZE_MAX) fail("no metadata section");
  for (const auto& shape : kStructural)
    if (structural_[static_cast<std::size_t>(shape.kind)] == SIZE_MAX)
      fail("no " + std::string(format::to_string(shape.kind)) + " section");
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

void GraphReader::check_access(const Section& s, ElementType wanted) const {
  if (s.is_packed())
    fail(ErrorCode::packed, "section '" + s.name +
                                "' is zstd-packed and cannot be mapped zero-copy; unpack the "
                                "file first");
  if (s.type != wanted)
    fail(ErrorCode::invalid_argument, "section '" + s.name + "' holds " +
                                          std::string(format::to_string(s.type)) + " values, not " +
                                          std::string(format::to_string(wanted)));
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

std::span<const Query> GraphReader::queries(std::string_view name) const {
  const Section* s = find(SectionKind::queries, name);
  if (!s) fail(ErrorCode::not_found, "no query set named '" + std::string(name) + "'");
  auto raw = values<std::uint32_t>(*s);
  return {reinterpret_cast<const Query*>(raw.data()), raw.size() / 2};
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

std::string GraphReader::digest() const {
  std::vector<format::SectionEntry> normalized;
  normalized.reserve(sections_.size());
  for (const auto& s : sections_) {
    auto e = s.entry;
    e.encoding = 0;
    e.offset = 0;
    e.stored_length = 0;
    normalized.push_back(e);
  }
  const XXH128_hash_t hash =
      XXH3_128bits(normalized.data(), normalized.size() * sizeof(format::SectionEntry));
  return hex64(hash.high64) + hex64(hash.low64);
}

}  // namespace mosb
