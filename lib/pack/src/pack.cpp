#include "mosb/pack.hpp"

#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "codec.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/file_writer.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/large_array.hpp"
#include "mosb/internal/parallel.hpp"
#include "mosb/internal/sections_by_kind.hpp"
#include "mosb/internal/transpose.hpp"
#include "mosb/internal/xxh3.hpp"
#include "mosb/metadata.hpp"
#include "mosb/verify.hpp"

namespace mosb {

namespace {

using namespace packing;
using format::Encoding;

// The content of the zstd frame of `s` under `encoding` (§6).
std::vector<std::byte> frame_content(const Section& s, Encoding encoding) {
  std::vector<std::byte> content(s.stored.begin(), s.stored.end());
  if (encoding == Encoding::zstd) return content;
  const std::size_t w = format::element_size(s.type), count = s.element_count();
  with_width(w, [&](auto width) {
    if (encoding == Encoding::delta_zstd) delta_in_place<width()>(content.data(), count);
    std::vector<std::byte> shuffled(content.size());
    shuffle_bytes<width()>(content.data(), shuffled.data(), count);
    content.swap(shuffled);
  });
  return content;
}

// A zero-filled, page-aligned buffer owned by a shared_ptr (the owner of a MappedFile): anonymous
// memory (map_large), which the kernel zeroes, so the image is written once, not cleared first,
// populated in one call: a page fault per 4 KiB cost more than decoding (FLA size: 0.30 GB/s with
// malloc and memset, 2.5 GB/s so). Populating commits no more than the memset it replaces did.
// `scratch` more bytes follow the image in the same mapping, at the next 64-byte boundary: room to
// decode a frame before un-shuffling it, without a second allocation and its page faults.
MappedFile allocate_image(std::uint64_t size, std::uint64_t scratch, std::string_view name) {
  std::uint64_t length = 0;
  if (__builtin_add_overflow(format::align_up(size), std::max<std::uint64_t>(scratch, 1), &length))
    length = UINT64_MAX;
  void* memory = nullptr;
  try {
    if (length > SIZE_MAX) throw std::bad_alloc();
    memory = map_large(length, true);
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::no_memory,
                std::string(name) + ": out of memory unpacking " + std::to_string(size) + " bytes");
  }
  MappedFile image;
  image.owner = std::shared_ptr<const void>(
      memory, [length](const void* p) { unmap_large(const_cast<void*>(p), length); });
  image.bytes = {static_cast<const std::byte*>(memory), static_cast<std::size_t>(size)};
  return image;
}

// Decodes the zstd frame of `s` into `out` (exactly s.decoded_length bytes) or throws.
// `scratch` holds s.decoded_length bytes when the encoding is not plain zstd.
void decode_frame(const Section& s, std::byte* out, ZSTD_DCtx* context, std::string_view name,
                  std::byte* scratch) {
  auto fail = [&](const std::string& what) { fail_section(s, name, what); };
  check_frame_header(s, name);
  const auto encoding = static_cast<Encoding>(s.entry.encoding);
  std::byte* content = out;
  if (encoding != Encoding::zstd) {
    content = scratch;
  }
  const std::size_t decoded =
      ZSTD_decompressDCtx(context, content, s.decoded_length, s.stored.data(), s.stored.size());
  if (ZSTD_isError(decoded))
    fail("zstd frame does not decode (" + std::string(ZSTD_getErrorName(decoded)) + ")");
  if (decoded != s.decoded_length)
    fail("zstd frame decodes to " + std::to_string(decoded) + " bytes, the table declares " +
         std::to_string(s.decoded_length));
  if (encoding == Encoding::zstd) return;
  const std::size_t count = s.element_count();
  with_width(format::element_size(s.type), [&](auto width) {
    unshuffle_bytes<width()>(content, count, out, count);
    if (encoding == Encoding::delta_zstd) undelta_in_place<width()>(out, count);
  });
}

std::vector<format::SectionEntry> table_of(const std::vector<Section>& sections) {
  std::vector<format::SectionEntry> table;
  table.reserve(sections.size());
  for (const auto& s : sections) table.push_back(s.entry);
  return table;
}

AtomicFile::Existing existing_for(const std::filesystem::path& in,
                                  const std::filesystem::path& out) {
  std::error_code error;
  return std::filesystem::equivalent(in, out, error) ? AtomicFile::Existing::rewrite_in_place
                                                     : AtomicFile::Existing::replace;
}

// The canonical layout, the bomb bound, each frame's declared content size and the shapes the
// derived sections need, before any allocation: every section gets its decoded offset. Returns
// the end of the last one.
std::uint64_t lay_out_decoded(std::vector<Section>& sections, std::string_view display_name) {
  std::uint64_t position = format::kHeaderSize;
  for (auto& s : sections) {
    if (is_encoded(s) && !is_derived(s) && s.decoded_length / kMaxZstdRatio > s.entry.stored_length)
      throw Error(ErrorCode::damaged,
                  std::string(display_name) + ": section '" + s.name + "': declares " +
                      std::to_string(s.decoded_length) + " decoded bytes, more than its " +
                      std::to_string(s.entry.stored_length) + "-byte zstd frame can hold");
    if (is_encoded(s) && !is_derived(s)) check_frame_header(s, display_name);
    position = format::align_up(position);
    s.entry.offset = position;
    if (__builtin_add_overflow(position, s.decoded_length, &position))
      throw Error(ErrorCode::damaged, std::string(display_name) + ": decoded size overflows");
  }
  return position;
}

// A decoded section's bytes must match its checksum; then its entry says raw.
void check_and_mark_raw(Section& s, const std::byte* out, std::string_view display_name) {
  const std::uint64_t computed = XXH3_64bits(out + s.entry.offset, s.decoded_length);
  if (computed != s.entry.checksum)
    throw Error(ErrorCode::damaged, std::string(display_name) + ": section '" + s.name +
                                        "': checksum mismatch (stored " + hex64(s.entry.checksum) +
                                        ", computed " + hex64(computed) + ")");
  s.entry.encoding = static_cast<std::uint8_t>(format::Encoding::raw);
  s.entry.stored_length = s.decoded_length;
}

// Every section but the derived ones, decoded (or copied) into place and checked.
void decode_stored(std::vector<Section>& sections, std::byte* out, std::byte* scratch,
                   std::string_view display_name) {
  ZSTD_DCtx* context = ZSTD_createDCtx();
  if (!context) throw Error(ErrorCode::no_memory, std::string(display_name) + ": out of memory");
  try {
    for (auto& s : sections) {
      if (is_derived(s)) continue;  // once the forward CSR is decoded and checked
      std::byte* target = out + s.entry.offset;
      if (is_encoded(s))
        decode_frame(s, target, context, display_name, scratch);
      else if (!s.stored.empty())
        std::memcpy(target, s.stored.data(), s.stored.size());
      check_and_mark_raw(s, out, display_name);
    }
  } catch (...) {
    ZSTD_freeDCtx(context);
    throw;
  }
  ZSTD_freeDCtx(context);
}

// The derived sections, transposed from the decoded forward CSR straight into place, then checked.
void derive_reverse(std::vector<Section>& sections, const TransposePlan& derived, std::byte* out,
                    std::string_view display_name) {
  auto at = [&](std::size_t i) { return out + sections[i].entry.offset; };
  // A reverse section that is stored, not derived, is computed aside and left as decoded.
  const std::uint64_t n1 = sections[derived.reverse_offsets].decoded_length / 8;
  const std::uint64_t m = sections[derived.reverse_sources].decoded_length / 4;
  std::vector<std::uint64_t> aside_offsets;
  std::vector<std::uint32_t> aside_sources, aside_arcs;
  auto place = [&](std::size_t i, auto& aside, std::uint64_t count) {
    using T = typename std::remove_reference_t<decltype(aside)>::value_type;
    if (is_derived(sections[i])) return reinterpret_cast<T*>(at(i));
    aside.resize(count);
    return aside.data();
  };
  const auto& fo = sections[derived.forward_offsets];
  const auto& ft = sections[derived.forward_targets];
  if (!derive_transpose(as_elements<std::uint64_t>(at(derived.forward_offsets), fo.decoded_length),
                        as_elements<std::uint32_t>(at(derived.forward_targets), ft.decoded_length),
                        place(derived.reverse_offsets, aside_offsets, n1),
                        place(derived.reverse_sources, aside_sources, m),
                        place(derived.reverse_arcs, aside_arcs, m)))
    throw Error(ErrorCode::damaged,
                std::string(display_name) +
                    ": the reverse CSR cannot be derived (transpose encoding): the forward CSR "
                    "is not one (offsets from 0 to m, never decreasing, every target below n)");
  for (auto& s : sections)
    if (is_derived(s)) check_and_mark_raw(s, out, display_name);
}

// All that decoding allocates, the image, the scratch after it and the reverse sections derived
// aside, must fit in `max_memory` (0: available_memory()): checked before any of it is allocated.
void check_memory(const std::vector<Section>& sections, const std::optional<TransposePlan>& derived,
                  std::uint64_t image, std::uint64_t scratch, std::uint64_t max_memory,
                  std::string_view display_name) {
  std::uint64_t total = format::align_up(image);
  bool overflows = __builtin_add_overflow(total, scratch, &total);
  if (derived)
    for (const auto i : {derived->reverse_offsets, derived->reverse_sources, derived->reverse_arcs})
      if (!is_derived(sections[i]))
        overflows |= __builtin_add_overflow(total, sections[i].decoded_length, &total);
  const std::uint64_t cap = max_memory != 0 ? max_memory : available_memory();
  if (overflows || total > cap)
    throw Error(overflows ? ErrorCode::damaged : ErrorCode::no_memory,
                {std::string(display_name) + ": decoding needs " +
                     (overflows ? std::string("more than 2^64") : std::to_string(total)) +
                     " bytes of memory, more than the cap of " + std::to_string(cap) +
                     " bytes (the memory available, or ",
                 setting("max_memory"), ")"});
}

// The kind unpack_bytes and pack_file take a file as: a solution file when it says so, else an
// instance (whose checks then name what else it is).
format::FileKind packable_kind(std::span<const std::byte> bytes) {
  return stated_file_kind(bytes) == format::FileKind::solutions ? format::FileKind::solutions
                                                                : format::FileKind::instance;
}

// SOLUTIONS.md §1: a packed solution file says 1.6 or later (parse_container refuses the
// transpose encoding outside an instance).
void refuse_packed_minor(const Container& container, std::string_view display_name) {
  if (is_packed(container.header) && container.header.version_minor < format::kSolutionPackedMinor)
    throw Error(ErrorCode::damaged,
                std::string(display_name) + ": a packed solution file states format 1." +
                    std::to_string(container.header.version_minor) + ", packed ones are 1." +
                    std::to_string(format::kSolutionPackedMinor) + " or later");
}

// The minor a packed solution file unpacks to, from its decoded content (its metadata and the
// names of its statistics), as the writer chose it.
std::uint16_t unpacked_solutions_minor(const std::vector<Section>& sections, const std::byte* out,
                                       std::string_view display_name) {
  bool reported = false, view = false;
  for (const auto& s : sections) {
    if (s.kind == format::SectionKind::solution_statistics &&
        s.name == format::kReportedRuntimeStatistic)
      reported = true;
    if (s.kind != format::SectionKind::metadata) continue;
    try {
      const auto metadata = Metadata::parse(
          std::string_view(reinterpret_cast<const char*>(out + s.entry.offset), s.decoded_length));
      const auto value = metadata.get(format::kSolutionViewKey);
      view = value && !value->empty();
    } catch (const Error& e) {
      throw Error(ErrorCode::damaged,
                  std::string(display_name) + ": section 'metadata': " + e.what());
    }
  }
  return format::solution_layout_minor(reported, view);
}

}  // namespace

std::uint64_t available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  while (meminfo >> key >> kib) {
    if (key == "MemAvailable:") return kib << 10;
    meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  const long pages = sysconf(_SC_AVPHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return UINT64_MAX;  // unknown: the other bounds hold
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

MappedFile unpack_bytes(std::span<const std::byte> bytes, std::string_view display_name,
                        std::uint64_t max_memory) {
  const auto kind = packable_kind(bytes);
  const auto container = parse_container(bytes, display_name, kind);
  auto sections = container.sections;
  const std::uint64_t position = lay_out_decoded(sections, display_name);
  const auto derived =
      kind == format::FileKind::instance ? transpose_plan(sections, display_name) : std::nullopt;
  if (kind == format::FileKind::instance) {
    // The instance's own checks: each section's length is the one the header's counts give it.
    (void)GraphReader::from_memory(bytes, std::string(display_name));
  } else {
    // A solution file's lengths are its own (SOLUTIONS.md §3): the frames' bound and the memory
    // cap below limit what decoding allocates, and its reader checks the decoded sections. The
    // stored bytes' own gaps (FORMAT.md §1: zero), which decoding does not carry over, are checked
    // here, so a packed file passes only where its unpacked form would.
    refuse_packed_minor(container, display_name);
    if (const auto problem = find_padding_problem(bytes, container))
      throw Error(ErrorCode::damaged, std::string(display_name) + ": file is damaged: " + *problem);
  }
  auto header = container.header;
  header.table_offset = format::align_up(position);
  header.file_size = header.table_offset + sections.size() * sizeof(format::SectionEntry);
  header.required_features &= ~format::kEncodingFeatures;
  // An instance's minor follows its features (§2); a solution file's, its content (below).
  if (kind == format::FileKind::instance)
    header.version_minor =
        std::min(header.version_minor, format::minimum_version_minor(header.required_features));

  std::uint64_t scratch_size = 0;
  for (const auto& s : sections)
    if (is_encoded(s) && !is_derived(s) &&
        s.entry.encoding != static_cast<std::uint8_t>(Encoding::zstd))
      scratch_size = std::max(scratch_size, s.decoded_length);
  check_memory(sections, derived, header.file_size, std::max<std::uint64_t>(scratch_size, 1),
               max_memory, display_name);
  auto image = allocate_image(header.file_size, scratch_size, display_name);
  auto* out = const_cast<std::byte*>(image.bytes.data());
  decode_stored(sections, out, out + format::align_up(header.file_size), display_name);
  if (derived) derive_reverse(sections, *derived, out, display_name);
  if (kind == format::FileKind::solutions && is_packed(container.header))
    header.version_minor = unpacked_solutions_minor(sections, out, display_name);

  const auto table = table_of(sections);
  std::memcpy(out + header.table_offset, table.data(), table.size() * sizeof table[0]);
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  XXH3_64bits_update(state, &header, format::kHeaderChecksumOffset);
  XXH3_64bits_update(state, table.data(), table.size() * sizeof table[0]);
  header.header_checksum = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  std::memcpy(out, &header, sizeof header);
  return image;
}

namespace {

// What verify at `level` finds in an instance from its unpacked form `image`: the image's checks
// at that level, then (at structure and full) the padding of the instance's own bytes `file`,
// which unpacking does not carry over (a packed file's frames keep it).
std::optional<std::string> decoded_problem(const MappedFile& file, const MappedFile& image,
                                           const std::string& name, VerifyLevel level,
                                           const Progress& progress = {}) {
  if (packable_kind(file.bytes) == format::FileKind::solutions) {
    // Its checksums and padding were checked while unpacking; its fronts are its reader's to
    // check (SolutionReader, at every open), which this library does not know.
    return std::nullopt;
  }
  const auto reader = GraphReader::from_memory(image.bytes, name);
  if (auto problem = verify(reader, level, progress)) return problem;
  if (!covers(level, VerifyLevel::structure)) return std::nullopt;
  return find_padding_problem(GraphReader::from_memory(file.bytes, name));
}

// Pack and unpack write nothing from a damaged input: its checksums were checked while unpacking
// it into `image`; here its structure and padding (verify at level full, in all).
void refuse_damaged(const MappedFile& file, const MappedFile& image, const std::string& name) {
  if (auto problem = decoded_problem(file, image, name, VerifyLevel::structure))
    throw Error(ErrorCode::damaged, name + ": file is damaged: " + *problem + "; nothing written");
}

}  // namespace

std::string unpack_file(const std::filesystem::path& in, const std::filesystem::path& out,
                        std::uint64_t max_memory) {
  const auto file = map_file(in);
  const auto image = unpack_bytes(file.bytes, in.string(), max_memory);
  // The image is the output, byte for byte: checking it checks what is written.
  refuse_damaged(file, image, in.string());
  AtomicFile writer(out, existing_for(in, out));
  writer.write(image.bytes.data(), image.bytes.size());
  writer.commit();
  return content_digest(
      parse_container(image.bytes, in.string(), packable_kind(file.bytes)).sections);
}

namespace {

// A file packing can restore byte for byte: in the writer's canonical layout (or packed already,
// so unpacked first), with no header bits the writer does not write. Returns the unpacked image's
// container.
Container parse_packable(const MappedFile& file, const MappedFile& image, const std::string& name) {
  const auto kind = packable_kind(file.bytes);
  const auto input = parse_container(file.bytes, name, kind);
  if (!is_packed(input.header) &&
      (image.bytes.size() != file.bytes.size() ||
       std::memcmp(image.bytes.data(), file.bytes.data(), file.bytes.size()) != 0))
    throw Error(ErrorCode::invalid_argument,
                name +
                    ": not in the canonical layout of the mosb writer (section order, 64-byte "
                    "alignment, zero padding), so unpacking could not restore its exact bytes; "
                    "rewrite it with a mosb command first");
  auto container = parse_container(image.bytes, name, kind);
  const auto& reserved = container.header.reserved;
  if (container.header.optional_features != 0 ||
      std::any_of(reserved.begin(), reserved.end(), [](std::uint8_t b) { return b != 0; }))
    throw Error(ErrorCode::invalid_argument,
                name +
                    ": has optional feature bits or reserved header bytes the mosb writer does "
                    "not write, so unpacking could not restore its exact bytes");
  if (kind == format::FileKind::solutions) {
    const auto minor = container.header.version_minor;
    if (minor < format::kSolutionSumsMinor)
      throw Error(ErrorCode::invalid_argument,
                  name + ": a solution file of format 1." + std::to_string(minor) + " (before 1." +
                      std::to_string(format::kSolutionSumsMinor) +
                      ") has no packed form; write it again with mosb solutions merge");
    if (minor != unpacked_solutions_minor(container.sections, image.bytes.data(), name))
      throw Error(ErrorCode::invalid_argument,
                  name + ": states format 1." + std::to_string(minor) +
                      ", not the minor the mosb writer gives its content, so unpacking could not "
                      "restore its exact bytes");
  }
  return container;
}

// The reverse CSR is not stored where it is the transpose of the forward CSR, as every valid
// file's is (§4): unpacking derives it again (encoding transpose). Compared here, so a file that
// breaks §4 keeps its reverse sections as they are. Returns, per section, whether it is derived.
std::vector<bool> derived_sections(const std::vector<Section>& sections) {
  std::vector<bool> derived(sections.size(), false);
  std::string not_derivable;
  if (const auto plan = csr_sections(sections, not_derivable)) {
    const auto& fo = sections[plan->forward_offsets].stored;
    const auto& ft = sections[plan->forward_targets].stored;
    const auto offsets = as_elements<std::uint64_t>(fo.data(), fo.size());
    const auto targets = as_elements<std::uint32_t>(ft.data(), ft.size());
    std::vector<std::uint64_t> reverse_offsets(offsets.size());
    std::vector<std::uint32_t> reverse_sources(targets.size()), reverse_arcs(targets.size());
    if (derive_transpose(offsets, targets, reverse_offsets.data(), reverse_sources.data(),
                         reverse_arcs.data())) {
      auto same = [&](std::size_t i, const auto& computed) {
        const auto& stored = sections[i].stored;
        derived[i] = stored.size() == computed.size() * sizeof computed[0] &&
                     std::memcmp(stored.data(), computed.data(), stored.size()) == 0;
      };
      same(plan->reverse_offsets, reverse_offsets);
      same(plan->reverse_sources, reverse_sources);
      same(plan->reverse_arcs, reverse_arcs);
    }
  }
  return derived;
}

// One section as one frame under the encoding that gives the fewest bytes (ties: the lower
// encoding), kept only when it is smaller than the elements. The metadata stays raw: a few
// hundred bytes that keep a packed file self-describing (inspect reads the benchmark name and
// views without decoding anything). Leaves `kept` empty and `encoding_kept` raw when nothing is
// kept.
void encode_section(const Section& s, bool derived, int level, const std::string& name,
                    std::vector<std::byte>& kept, Encoding& encoding_kept) {
  if (derived) {
    encoding_kept = Encoding::transpose;
    return;
  }
  if (s.stored.empty() || s.kind == format::SectionKind::metadata) return;
  std::vector<Encoding> candidates = {Encoding::zstd};
  if (format::element_size(s.type) > 1) candidates.push_back(Encoding::shuffle_zstd);
  if (!format::is_float(s.type)) candidates.push_back(Encoding::delta_zstd);
  std::unique_ptr<ZSTD_CCtx, std::size_t (*)(ZSTD_CCtx*)> context(ZSTD_createCCtx(), ZSTD_freeCCtx);
  if (!context) throw Error(ErrorCode::no_memory, name + ": out of memory");
  for (const auto encoding : candidates) {
    const auto content = frame_content(s, encoding);
    std::vector<std::byte> frame(ZSTD_compressBound(content.size()));
    const std::size_t size = ZSTD_compressCCtx(context.get(), frame.data(), frame.size(),
                                               content.data(), content.size(), level);
    if (ZSTD_isError(size))
      throw Error(name + ": section '" + s.name + "': zstd compression failed");
    if (size >= s.stored.size() || (!kept.empty() && size >= kept.size())) continue;
    frame.resize(size);
    kept = std::move(frame);
    encoding_kept = encoding;
  }
  if (kept.empty()) return;
  // Verified before it is written: the frame decodes to the very bytes.
  Section encoded = s;
  encoded.entry.encoding = static_cast<std::uint8_t>(encoding_kept);
  encoded.stored = kept;
  std::vector<std::byte> check(s.stored.size()), scratch(s.stored.size());
  std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx*)> dcontext(ZSTD_createDCtx(),
                                                                   ZSTD_freeDCtx);
  if (!dcontext) throw Error(ErrorCode::no_memory, name + ": out of memory");
  decode_frame(encoded, check.data(), dcontext.get(), name, scratch.data());
  if (std::memcmp(check.data(), s.stored.data(), check.size()) != 0)
    throw Error(name + ": section '" + s.name + "': zstd frame does not decode to its bytes");
}

}  // namespace

std::string pack_file(const std::filesystem::path& in, const std::filesystem::path& out,
                      const PackOptions& options) {
  const std::string name = in.string();
  if (options.level < 1 || options.level > ZSTD_maxCLevel())
    throw Error(ErrorCode::invalid_argument, name + ": zstd level " +
                                                 std::to_string(options.level) + " is not in 1.." +
                                                 std::to_string(ZSTD_maxCLevel()));
  const auto file = map_file(in);
  const auto image = unpack_bytes(file.bytes, name, options.max_memory);
  refuse_damaged(file, image, name);
  const auto container = parse_packable(file, image, name);
  const auto& sections = container.sections;
  const auto kind = static_cast<format::FileKind>(container.header.file_kind);

  const std::vector<bool> derived = options.derive_reverse && kind == format::FileKind::instance
                                        ? derived_sections(sections)
                                        : std::vector<bool>(sections.size());
  std::vector<std::vector<std::byte>> frames(sections.size());
  std::vector<Encoding> encodings(sections.size(), Encoding::raw);
  parallel_for(sections.size(), options.threads, [&](std::size_t i) {
    encode_section(sections[i], derived[i], options.level, name, frames[i], encodings[i]);
  });

  FileWriter writer(out, existing_for(in, out));
  writer.set_file_kind(kind);
  if (kind == format::FileKind::solutions)  // SOLUTIONS.md §1: packed, 1.6; else as it was
    writer.require_minor(std::any_of(encodings.begin(), encodings.end(),
                                     [](Encoding e) { return e != Encoding::raw; })
                             ? format::kSolutionPackedMinor
                             : container.header.version_minor);
  for (std::size_t i = 0; i < sections.size(); ++i) {
    auto entry = sections[i].entry;
    entry.encoding = static_cast<std::uint8_t>(encodings[i]);
    writer.add_encoded_section(entry, encodings[i] == Encoding::raw
                                          ? sections[i].stored
                                          : std::span<const std::byte>(frames[i]));
  }
  // The packed file, complete under its temporary name, must unpack to its input's bytes and
  // verify as its input did.
  writer.expect_digest(content_digest(container.sections));
  writer.check_before_commit([&](const std::filesystem::path& temporary) {
    const auto packed = map_file(temporary);
    try {
      const auto again = unpack_bytes(packed.bytes, name, options.max_memory);
      refuse_damaged(packed, again, name);
      if (again.bytes.size() != image.bytes.size() ||
          std::memcmp(again.bytes.data(), image.bytes.data(), image.bytes.size()) != 0)
        throw Error(ErrorCode::damaged, name + ": unpacks to other bytes than its input's");
    } catch (const Error& e) {
      throw Error(ErrorCode::io, name + ": internal error: the packed file does not verify (" +
                                     e.what() + "); nothing written");
    }
  });
  writer.commit(container.header.vertex_count, container.header.arc_count);
  return content_digest(container.sections);
}

namespace {
// The file's bytes, decoded when packed.
MappedFile map_decoded(const std::filesystem::path& path, std::uint64_t max_memory) {
  auto file = map_file(path);
  return stated_packed(file.bytes) ? unpack_bytes(file.bytes, path.string(), max_memory) : file;
}
}  // namespace

GraphReader load(const std::filesystem::path& path, std::uint64_t max_memory) {
  return GraphReader::adopt(map_decoded(path, max_memory), path.string());
}

GraphReader load(const std::filesystem::path& path, VerifyLevel level, std::uint64_t max_memory) {
  return GraphReader::adopt(map_decoded(path, max_memory), path.string(), level);
}

FileVerification verify_file(const std::filesystem::path& path, VerifyLevel level,
                             std::uint64_t max_memory, const Progress& progress) {
  const auto file = map_file(path);
  const std::string name = path.string();
  if (level == VerifyLevel::header || !stated_packed(file.bytes)) {
    // Opening checks the header and the table (the header level) and decodes nothing.
    const auto opened = GraphReader::adopt(file, name);
    return {verify(opened, level, progress), opened.digest()};
  }
  // Decoding first, so that a damaged packed file gets the message unpack gives it.
  const auto image = unpack_bytes(file.bytes, name, max_memory);
  const auto problem = decoded_problem(file, image, name, level, progress);
  return {problem, GraphReader::adopt(file, name).digest()};
}

}  // namespace mosb
