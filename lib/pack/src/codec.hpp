// What decoding and checking a packed file share (spec/FORMAT.md §6): the encodings, the zstd
// frame's own checks, the byte shuffle and the deltas, the plan of a derived reverse CSR. Internal
// to the pack component (pack.cpp, streaming_verify.cpp).
#pragma once

#include <zstd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "mosb/container.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/internal/sections_by_kind.hpp"

namespace mosb::packing {

// The most a zstd frame can expand: a block decodes to at most 128 KiB and takes at least 4 bytes
// (a 3-byte block header and one RLE byte). A table that declares more for a frame is refused
// before anything is allocated (the decompression-bomb bound of FORMAT.md §6).
constexpr std::uint64_t kMaxZstdRatio = (std::uint64_t{128} << 10) / 4;

using format::Encoding;

inline bool is_encoded(const Section& s) {
  return s.entry.encoding != static_cast<std::uint8_t>(Encoding::raw);
}
inline bool is_derived(const Section& s) {
  return s.entry.encoding == static_cast<std::uint8_t>(Encoding::transpose);
}

// Where the sections of the CSR are in the table, when some reverse section is derived.
struct TransposePlan {
  std::size_t forward_offsets, forward_targets, reverse_offsets, reverse_sources, reverse_arcs;
};

// The five CSR sections, when there is exactly one of each kind with the type and width of §4 and
// each reverse section is as long as the forward one it is derived from (reverse_offsets as
// forward_offsets, the other two as forward_targets); else nullopt and, in `why`, what is not so.
// A section without stored bytes has no zstd ratio bound: these lengths bound what deriving it
// allocates by sections that have one.
inline std::optional<TransposePlan> csr_sections(const std::vector<Section>& sections,
                                                 std::string& why) {
  auto reject = [&](std::string what) {
    why = std::move(what);
    return std::nullopt;
  };
  const SectionsByKind table(sections, "");  // only its groups: no check throws
  auto one = [&](format::SectionKind kind, format::ElementType type) -> std::optional<std::size_t> {
    const std::string kind_name(format::to_string(kind));
    const auto found = table.all(kind);
    if (found.empty()) return reject("no " + kind_name + " section");
    const auto& s = sections[found[0]];
    if (s.type != type || s.entry.row_width != 1)
      return reject("section '" + s.name + "' is not " + std::string(format::to_string(type)) +
                    " x 1");
    if (found.size() > 1) return reject("two " + kind_name + " sections");
    return found[0];
  };
  using format::ElementType;
  using format::SectionKind;
  const auto fo = one(SectionKind::forward_offsets, ElementType::u64);
  const auto ft = one(SectionKind::forward_targets, ElementType::u32);
  const auto ro = one(SectionKind::reverse_offsets, ElementType::u64);
  const auto rs = one(SectionKind::reverse_sources, ElementType::u32);
  const auto ra = one(SectionKind::reverse_arcs, ElementType::u32);
  if (!fo || !ft || !ro || !rs || !ra) return std::nullopt;
  for (const auto& [reverse, forward] : {std::pair{*ro, *fo}, {*rs, *ft}, {*ra, *ft}})
    if (sections[reverse].decoded_length != sections[forward].decoded_length)
      return reject("section '" + sections[reverse].name + "' declares " +
                    std::to_string(sections[reverse].decoded_length) + " bytes, '" +
                    sections[forward].name + "' " +
                    std::to_string(sections[forward].decoded_length));
  return TransposePlan{*fo, *ft, *ro, *rs, *ra};
}

// The CSR sections of a file in which some section is derived, checked before anything is
// allocated.
inline std::optional<TransposePlan> transpose_plan(const std::vector<Section>& sections,
                                                   std::string_view name) {
  if (std::none_of(sections.begin(), sections.end(), is_derived)) return std::nullopt;
  std::string why;
  auto plan = csr_sections(sections, why);
  if (!plan)
    throw Error(ErrorCode::damaged, std::string(name) +
                                        ": the reverse CSR cannot be derived (transpose "
                                        "encoding): " +
                                        why);
  return plan;
}

// §6 byte shuffle: byte k of element i goes to k * count + i (grouping bytes of one significance,
// which are alike in a column of small or slowly changing values), and back.
template <std::size_t W>
void shuffle_bytes(const std::byte* in, std::byte* out, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t k = 0; k < W; ++k) out[k * count + i] = in[i * W + k];
}
// Elements [0, count) from planes `stride` bytes apart (byte k of element i at in[k * stride + i]):
// stride = count un-shuffles a whole section; a larger one, a window of it.
template <std::size_t W>
void unshuffle_bytes(const std::byte* in, std::size_t stride, std::byte* out, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t k = 0; k < W; ++k) out[i * W + k] = in[k * stride + i];
}

// Calls f(std::integral_constant<std::size_t, W>) for element size w in {1, 2, 4, 8}.
template <class F>
inline void with_width(std::size_t w, F&& f) {
  switch (w) {
    case 1:
      return f(std::integral_constant<std::size_t, 1>{});
    case 2:
      return f(std::integral_constant<std::size_t, 2>{});
    case 4:
      return f(std::integral_constant<std::size_t, 4>{});
    default:
      return f(std::integral_constant<std::size_t, 8>{});
  }
}

template <std::size_t W>
using Unsigned = std::conditional_t<
    W == 1, std::uint8_t,
    std::conditional_t<W == 2, std::uint16_t,
                       std::conditional_t<W == 4, std::uint32_t, std::uint64_t>>>;

// The wrapping differences x[i] - x[i-1] (x[-1] = 0) of a column of W-byte integers, in place,
// and their running sum.
template <std::size_t W>
void delta_in_place(std::byte* bytes, std::size_t count) {
  using T = Unsigned<W>;
  T previous = 0;
  for (std::size_t i = 0; i < count; ++i) {
    T x;
    std::memcpy(&x, bytes + i * W, W);
    const T d = static_cast<T>(x - previous);
    previous = x;
    std::memcpy(bytes + i * W, &d, W);
  }
}
// The running sum, continued from `sum` (the last element before these; 0 at the start), which
// it returns.
template <std::size_t W>
std::uint64_t undelta_in_place(std::byte* bytes, std::size_t count, std::uint64_t sum = 0) {
  using T = Unsigned<W>;
  auto running = static_cast<T>(sum);
  for (std::size_t i = 0; i < count; ++i) {
    T d;
    std::memcpy(&d, bytes + i * W, W);
    running = static_cast<T>(running + d);
    std::memcpy(bytes + i * W, &running, W);
  }
  return running;
}

// `bytes` bytes at p (aligned for T) as elements of type T.
template <class T>
std::span<const T> as_elements(const std::byte* p, std::uint64_t bytes) {
  return {reinterpret_cast<const T*>(p), static_cast<std::size_t>(bytes / sizeof(T))};
}

[[noreturn]] inline void fail_section(const Section& s, std::string_view name,
                                      const std::string& what) {
  throw Error(ErrorCode::damaged, std::string(name) + ": section '" + s.name + "': " + what);
}

// The stored bytes of `s` are one zstd frame, and its header declares s.decoded_length bytes of
// content: checked from the frame header alone, before anything is allocated for it.
inline void check_frame_header(const Section& s, std::string_view name) {
  auto fail = [&](const std::string& what) { fail_section(s, name, what); };
  const auto declared = ZSTD_getFrameContentSize(s.stored.data(), s.stored.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) fail("stored bytes are not a zstd frame");
  if (declared == ZSTD_CONTENTSIZE_UNKNOWN) fail("zstd frame does not declare its content size");
  if (declared != s.decoded_length)
    fail("zstd frame declares " + std::to_string(declared) + " bytes, the table " +
         std::to_string(s.decoded_length));
  const std::size_t frame = ZSTD_findFrameCompressedSize(s.stored.data(), s.stored.size());
  if (ZSTD_isError(frame))
    fail("zstd frame is truncated or damaged (" + std::string(ZSTD_getErrorName(frame)) + ")");
  if (frame != s.stored.size())
    fail(std::to_string(s.stored.size() - frame) + " bytes follow the zstd frame");
}

}  // namespace mosb::packing
