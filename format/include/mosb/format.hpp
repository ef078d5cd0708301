// The on-disk layout of mosb format 1.3: the one source of truth that spec/FORMAT.md describes.
// Everything here is plain data with fixed sizes; every multi-byte field is little-endian.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <type_traits>

namespace mosb::format {

static_assert(std::endian::native == std::endian::little,
              "mosb maps files zero-copy and therefore needs a little-endian host");

inline constexpr std::uint16_t kVersionMajor = 1;
// The newest minor this code reads. A writer stamps a file with the lowest minor whose readers can
// read it (spec/FORMAT.md §2): instance files using only 1.0 features still say 1.0.
inline constexpr std::uint16_t kVersionMinor = 6;
// Solution files since 1.3 store path sums (u64 / i64 / f64 front_cost columns, path_sum_type);
// those of 1.1 and 1.2 stored each objective in its arc cost type (spec/SOLUTIONS.md §3).
inline constexpr std::uint16_t kSolutionSumsMinor = 3;
// A solution file without `solution.view`, bound to its front_cost columns' objective names alone
// (spec/SOLUTIONS.md §2), needs 1.4; one with a view stays 1.3.
inline constexpr std::uint16_t kSolutionObjectivesMinor = 4;
// A solution file with a `reported_runtime_seconds` statistic (the solver's own runtime) needs
// 1.5: a 1.4 reader refuses the section's name; one without it keeps its 1.3 or 1.4.
inline constexpr std::uint16_t kSolutionReportedRuntimeMinor = 5;
// A packed solution file (spec/SOLUTIONS.md §1) says 1.6: a 1.5 reader refuses it by its version
// instead of by its encodings. Unpacking restores the minor solution_layout_minor gives.
inline constexpr std::uint16_t kSolutionPackedMinor = 6;
// The minor of an unpacked solution file written since 1.3, from its content alone: whether it has
// a `reported_runtime_seconds` statistic and a `solution.view` key. Writing and unpacking a
// solution file both follow it, so unpacking restores the written bytes.
constexpr std::uint16_t solution_layout_minor(bool has_reported_runtime, bool has_view) {
  return has_reported_runtime ? kSolutionReportedRuntimeMinor
         : has_view           ? kSolutionSumsMinor
                              : kSolutionObjectivesMinor;
}
inline constexpr std::string_view kReportedRuntimeStatistic = "reported_runtime_seconds";
inline constexpr std::string_view kSolutionViewKey = "solution.view";

// PNG-style: a high-bit byte catches 7-bit transfers, CR LF catches CRLF->LF conversion,
// the lone LF catches LF->CRLF conversion, 0x1A stops `type` on DOS.
inline constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'M', 'O', 'S', 0x0D, 0x0A, 0x1A, 0x0A};
// Stored as the bytes 04 03 02 01; a reader that sees 01 02 03 04 has a byte-swapped file.
inline constexpr std::uint32_t kByteOrderMark = 0x01020304;

inline constexpr std::uint64_t kAlignment = 64;
inline constexpr std::uint32_t kHeaderSize = 128;
inline constexpr std::size_t kHeaderChecksumOffset = 120;
inline constexpr std::size_t kNameSize = 24;

enum class FileKind : std::uint32_t {
  instance = 1,
  solutions = 2,  // since 1.1: reference or solver fronts of one query set (spec/SOLUTIONS.md)
};

// Required features: a reader refuses a file with a required bit it does not know.
enum RequiredFeature : std::uint64_t {
  kFeatureZstdSections = 1ULL << 0,       // some section has encoding zstd (a packed file)
  kFeatureShuffleSections = 1ULL << 1,    // some section has encoding shuffle_zstd (1.1)
  kFeatureDeltaSections = 1ULL << 2,      // some section has encoding delta_zstd (1.1)
  kFeatureTransposeSections = 1ULL << 3,  // some section has encoding transpose (1.2)
};
inline constexpr std::uint64_t kKnownRequiredFeatures =
    kFeatureZstdSections | kFeatureShuffleSections | kFeatureDeltaSections |
    kFeatureTransposeSections;

// §2: a file's version_minor is the lowest minor whose readers can read it, so a file using only
// 1.0 features stays a 1.0 file, byte for byte.
constexpr std::uint16_t minimum_version_minor(std::uint64_t required_features) {
  if (required_features & kFeatureTransposeSections) return 2;
  return (required_features & (kFeatureShuffleSections | kFeatureDeltaSections)) ? 1 : 0;
}
// No optional features are defined in 1.0; readers ignore unknown optional bits.

struct FileHeader {
  std::array<std::uint8_t, 8> magic;
  std::uint32_t byte_order_mark;
  std::uint16_t version_major;
  std::uint16_t version_minor;
  std::uint32_t header_size;
  std::uint32_t file_kind;
  std::uint64_t required_features;
  std::uint64_t optional_features;
  std::uint64_t file_size;
  std::uint64_t table_offset;
  std::uint32_t section_count;
  std::uint32_t objective_count;
  std::uint64_t vertex_count;
  std::uint64_t arc_count;
  std::array<std::uint8_t, 40> reserved;
  std::uint64_t header_checksum;  // XXH3-64 of header bytes [0, 120) followed by the section table
};
static_assert(sizeof(FileHeader) == kHeaderSize);
static_assert(offsetof(FileHeader, byte_order_mark) == 8);
static_assert(offsetof(FileHeader, version_major) == 12);
static_assert(offsetof(FileHeader, header_size) == 16);
static_assert(offsetof(FileHeader, file_kind) == 20);
static_assert(offsetof(FileHeader, required_features) == 24);
static_assert(offsetof(FileHeader, optional_features) == 32);
static_assert(offsetof(FileHeader, file_size) == 40);
static_assert(offsetof(FileHeader, table_offset) == 48);
static_assert(offsetof(FileHeader, section_count) == 56);
static_assert(offsetof(FileHeader, objective_count) == 60);
static_assert(offsetof(FileHeader, vertex_count) == 64);
static_assert(offsetof(FileHeader, arc_count) == 72);
static_assert(offsetof(FileHeader, reserved) == 80);
static_assert(offsetof(FileHeader, header_checksum) == kHeaderChecksumOffset);

// The largest vertex or arc count (§4): ids are u32, and 2^32-1 stays free as a "no vertex" mark
// for solvers and the library's own searches.
inline constexpr std::uint64_t kMaxCount = 0xFFFFFFFEULL;

// The required feature bits that make a file packed: one per encoding other than raw (§6).
inline constexpr std::uint64_t kEncodingFeatures = kFeatureZstdSections | kFeatureShuffleSections |
                                                   kFeatureDeltaSections |
                                                   kFeatureTransposeSections;
// Whether a file is packed (§6): the one test every reader and command uses.
constexpr bool is_packed(const FileHeader& header) {
  return (header.required_features & kEncodingFeatures) != 0;
}

enum class SectionKind : std::uint16_t {
  metadata = 1,         // u8 x 1: UTF-8 "key=value\n" lines, sorted by key
  forward_offsets = 2,  // u64 x 1, n+1 rows: first outgoing arc of each vertex
  forward_targets = 3,  // u32 x 1, m rows: head of each arc
  reverse_offsets = 4,  // u64 x 1, n+1 rows: first incoming entry of each vertex
  reverse_sources = 5,  // u32 x 1, m rows: tail of each incoming arc
  reverse_arcs = 6,     // u32 x 1, m rows: forward arc id of each incoming arc
  cost = 7,             // unsigned or float x 1, m rows: one objective, named by the section
  vertex_data = 8,      // any type x width, n rows
  arc_data = 9,         // any type x width, m rows
  queries = 10,         // u32 x 2, one row per (start, goal) pair
  // Since 1.1, in solution files (file kind 2, spec/SOLUTIONS.md):
  solution_status = 11,      // u8 x 1, Q rows: the QueryStatus of each query
  front_offsets = 12,        // u64 x 1, Q+1 rows: first front vector of each query
  front_cost = 13,           // path_sum_type x 1 (1.3; 1.1: the arc type), F rows: one objective
  solution_statistics = 14,  // f64 or u64 x 1, Q rows: one statistic, named by it
  path_offsets = 15,         // u64 x 1, F+1 rows: first path vertex of each front vector
  path_vertices = 16,        // u32 x 1: the vertices of every path, concatenated
  // Since 1.1, in instance files (ignorable by a 1.0 reader, so the file stays 1.0):
  query_reference = 17,  // f64 x 1, one row per query of the set it is named after
};
inline constexpr std::uint16_t kLastSectionKind = 17;

enum class ElementType : std::uint8_t {
  u8 = 1,
  u16 = 2,
  u32 = 3,
  u64 = 4,
  i8 = 5,
  i16 = 6,
  i32 = 7,
  i64 = 8,
  f32 = 9,
  f64 = 10,
};

// §6. Encodings 1-3 store one zstd frame that declares its content size, the decoded length of
// the section; encoding 4 stores nothing. A reader must know the encoding's required feature bit.
enum class Encoding : std::uint8_t {
  raw = 0,           // the stored bytes are the elements
  zstd = 1,          // the frame's content is the elements
  shuffle_zstd = 2,  // the content is the elements' bytes grouped by significance (byte shuffle)
  delta_zstd = 3,    // the content is the byte shuffle of the wrapping differences x[i] - x[i-1]
                     // (x[-1] = 0) of an integer column
  transpose = 4,     // nothing is stored: a reverse CSR section, derived from the forward CSR
};
inline constexpr std::uint8_t kLastEncoding = 4;

// The required feature bit of a non-raw encoding.
constexpr std::uint64_t feature_of(Encoding e) {
  switch (e) {
    case Encoding::raw:
      return 0;
    case Encoding::zstd:
      return kFeatureZstdSections;
    case Encoding::shuffle_zstd:
      return kFeatureShuffleSections;
    case Encoding::delta_zstd:
      return kFeatureDeltaSections;
    case Encoding::transpose:
      return kFeatureTransposeSections;
  }
  return 0;
}

struct SectionEntry {
  std::array<char, kNameSize> name;  // UTF-8, NUL-padded, 1..24 bytes, no NUL inside
  std::uint16_t kind;
  std::uint8_t element_type;
  std::uint8_t encoding;
  std::uint32_t row_width;  // elements per row, >= 1
  std::uint64_t row_count;
  std::uint64_t offset;         // from the start of the file, a multiple of kAlignment
  std::uint64_t stored_length;  // bytes on disk
  std::uint64_t checksum;       // XXH3-64 (seed 0) of the decoded elements
};
static_assert(sizeof(SectionEntry) == 64);
static_assert(offsetof(SectionEntry, kind) == 24);
static_assert(offsetof(SectionEntry, element_type) == 26);
static_assert(offsetof(SectionEntry, encoding) == 27);
static_assert(offsetof(SectionEntry, row_width) == 28);
static_assert(offsetof(SectionEntry, row_count) == 32);
static_assert(offsetof(SectionEntry, offset) == 40);
static_assert(offsetof(SectionEntry, stored_length) == 48);
static_assert(offsetof(SectionEntry, checksum) == 56);

// Section names and metadata keys share one alphabet (§3, §7): [A-Za-z0-9_.+-].
constexpr bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '.' || c == '+' || c == '-';
}

// The section-name rule of §3, the one every writer, editor, converter and the reader apply.
inline constexpr std::string_view kSectionNameRule = "1-24 characters from [A-Za-z0-9_.+-]";
constexpr bool is_valid_section_name(std::string_view name) {
  if (name.empty() || name.size() > kNameSize) return false;
  for (char c : name)
    if (!is_name_char(c)) return false;
  return true;
}

// The name without its NUL padding.
inline std::string_view name_of(const SectionEntry& e) {
  std::size_t length = 0;
  while (length < kNameSize && e.name[length] != '\0') ++length;
  return {e.name.data(), length};
}

constexpr std::size_t element_size(ElementType t) {
  switch (t) {
    case ElementType::u8:
    case ElementType::i8:
      return 1;
    case ElementType::u16:
    case ElementType::i16:
      return 2;
    case ElementType::u32:
    case ElementType::i32:
    case ElementType::f32:
      return 4;
    case ElementType::u64:
    case ElementType::i64:
    case ElementType::f64:
      return 8;
  }
  return 0;
}

constexpr bool is_float(ElementType t) {
  return t == ElementType::f32 || t == ElementType::f64;
}
constexpr bool is_unsigned(ElementType t) {
  return t == ElementType::u8 || t == ElementType::u16 || t == ElementType::u32 ||
         t == ElementType::u64;
}
// The type a solution file (1.3) stores a path's cost sum in, for arc costs of type t: a sum of
// u16 arcs does not fit u16, so the widest type of the same family (spec/SOLUTIONS.md §3).
constexpr ElementType path_sum_type(ElementType t) {
  if (is_unsigned(t)) return ElementType::u64;
  if (is_float(t)) return ElementType::f64;
  return ElementType::i64;
}

std::optional<ElementType> element_type_from(std::uint8_t raw);
std::optional<SectionKind> section_kind_from(std::uint16_t raw);
std::string_view to_string(ElementType t);
std::string_view to_string(SectionKind k);
std::string_view to_string(FileKind k);  // "graph instance"; empty for a kind unknown here
std::string_view to_string(Encoding e);  // "delta-zstd"; empty for an encoding unknown here
std::optional<ElementType> parse_element_type(std::string_view name);

template <class T>
constexpr ElementType element_type_of();
template <>
constexpr ElementType element_type_of<std::uint8_t>() {
  return ElementType::u8;
}
template <>
constexpr ElementType element_type_of<std::uint16_t>() {
  return ElementType::u16;
}
template <>
constexpr ElementType element_type_of<std::uint32_t>() {
  return ElementType::u32;
}
template <>
constexpr ElementType element_type_of<std::uint64_t>() {
  return ElementType::u64;
}
template <>
constexpr ElementType element_type_of<std::int8_t>() {
  return ElementType::i8;
}
template <>
constexpr ElementType element_type_of<std::int16_t>() {
  return ElementType::i16;
}
template <>
constexpr ElementType element_type_of<std::int32_t>() {
  return ElementType::i32;
}
template <>
constexpr ElementType element_type_of<std::int64_t>() {
  return ElementType::i64;
}
template <>
constexpr ElementType element_type_of<float>() {
  return ElementType::f32;
}
template <>
constexpr ElementType element_type_of<double>() {
  return ElementType::f64;
}

// The one place that maps an element type to its C++ type: calls f(std::type_identity<T>{}) and
// returns its result (the same type for every T). `type` must be a known element type.
template <class F>
constexpr decltype(auto) visit_element_type(ElementType type, F&& f) {
  switch (type) {
    case ElementType::u8:
      return std::forward<F>(f)(std::type_identity<std::uint8_t>{});
    case ElementType::u16:
      return std::forward<F>(f)(std::type_identity<std::uint16_t>{});
    case ElementType::u32:
      return std::forward<F>(f)(std::type_identity<std::uint32_t>{});
    case ElementType::u64:
      return std::forward<F>(f)(std::type_identity<std::uint64_t>{});
    case ElementType::i8:
      return std::forward<F>(f)(std::type_identity<std::int8_t>{});
    case ElementType::i16:
      return std::forward<F>(f)(std::type_identity<std::int16_t>{});
    case ElementType::i32:
      return std::forward<F>(f)(std::type_identity<std::int32_t>{});
    case ElementType::i64:
      return std::forward<F>(f)(std::type_identity<std::int64_t>{});
    case ElementType::f32:
      return std::forward<F>(f)(std::type_identity<float>{});
    case ElementType::f64:
      break;
  }
  return std::forward<F>(f)(std::type_identity<double>{});
}

// Cost columns hold unsigned integers or floats (§6).
template <class T>
inline constexpr bool is_cost_type_v = std::is_floating_point_v<T> || std::is_unsigned_v<T>;

constexpr std::uint64_t align_up(std::uint64_t x) {
  return (x + kAlignment - 1) / kAlignment * kAlignment;
}

}  // namespace mosb::format
