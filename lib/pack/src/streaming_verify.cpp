// verify_file_streaming: verify at level full in working memory that does not grow with the file.
//
// Every section is read once, front to back, one chunk at a time: a raw section straight from the
// mapping (each page let go once read), a zstd frame whole (when small) or through a streaming
// decoder, a large shuffled or delta frame from its content held in a spill file, read back plane
// by plane. The reverse CSR is checked against the transpose of the forward CSR in the order of §4:
// built in memory by derive_transpose when both fit the budget, else in buckets of heads spilled
// to the spill file and sorted one at a time; it is compared with stored sections and hashed for
// derived ones (encoding 4). The rest of §9's rules see the chunks the checksums do (mosb::rules).
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "codec.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/large_array.hpp"
#include "mosb/internal/transpose.hpp"
#include "mosb/internal/verify_rules.hpp"
#include "mosb/internal/xxh3.hpp"
#include "mosb/pack.hpp"
#include "mosb/verify.hpp"

namespace mosb {

namespace {

namespace fs = std::filesystem;
using namespace packing;
using format::ElementType;
using format::Encoding;
using format::SectionKind;
using rules::Problem;

// Bytes per chunk: a multiple of every element size and of the page size, and below glibc's mmap
// threshold, so that a chunk buffer is reused memory, not a fresh mapping to fault in.
constexpr std::size_t kChunk = std::size_t{64} << 10;
constexpr std::size_t kPage = 4096;

}  // namespace

// Large blocks a workspace keeps between checks, in classes of powers of two from 1 MiB, each with
// the length of it already populated (a reuse populates only what it needs beyond that).
struct VerifyWorkspace::Blocks {
  struct Block {
    void* p;
    std::size_t length, populated;
  };
  static constexpr std::size_t kKept = std::size_t{64} << 20;
  std::vector<Block> free, used;
  std::size_t kept = 0;  // populated bytes of the free blocks

  static std::size_t class_of(std::size_t bytes) {
    return std::bit_ceil(std::max(bytes, kLargeArrayBytes));
  }
  void* take(std::size_t bytes) {
    const std::size_t length = class_of(bytes);
    auto it = std::find_if(free.begin(), free.end(),
                           [length](const Block& b) { return b.length == length; });
    Block block{nullptr, length, 0};
    if (it != free.end()) {
      block = *it;
      kept -= block.populated;
      free.erase(it);
    } else {
      block.p = map_large(length, false);
    }
    if (bytes > block.populated) {
      auto* from = static_cast<char*>(block.p) + block.populated;
      ::madvise(from, bytes - block.populated, MADV_POPULATE_WRITE);
      block.populated = bytes;
    }
    used.push_back(block);
    return block.p;
  }
  // Kept for the next check while the free blocks hold at most kKept populated bytes, the
  // smallest given up first (the large ones cost most to fault in again).
  void give(void* p) noexcept {
    const auto it =
        std::find_if(used.begin(), used.end(), [p](const Block& b) { return b.p == p; });
    const Block block = *it;
    used.erase(it);
    std::sort(free.begin(), free.end(),
              [](const Block& a, const Block& b) { return a.populated > b.populated; });
    while (!free.empty() && kept + block.populated > kKept &&
           free.back().populated < block.populated) {
      kept -= free.back().populated;
      unmap_large(free.back().p, free.back().length);
      free.pop_back();
    }
    if (kept + block.populated > kKept) return unmap_large(block.p, block.length);
    free.push_back(block);
    kept += block.populated;
  }
  ~Blocks() {
    for (const auto& b : free) unmap_large(b.p, b.length);
  }
};

VerifyWorkspace::VerifyWorkspace() : blocks_(std::make_unique<Blocks>()) {}
VerifyWorkspace::~VerifyWorkspace() = default;

namespace {

// Buffers written in full before they are read: uninitialized, and a large one in huge pages,
// populated in one call (a fault per 4 KiB page cost as much as decoding into it), or taken from
// a workspace, where an earlier check left it populated.
template <class T>
struct BufferAllocator : LargeArrayAllocator<T> {
  VerifyWorkspace::Blocks* blocks = nullptr;
  BufferAllocator() = default;
  explicit BufferAllocator(VerifyWorkspace::Blocks* from) noexcept : blocks(from) {}
  template <class U>
  BufferAllocator(const BufferAllocator<U>& other) noexcept : blocks(other.blocks) {}
  template <class U>
  struct rebind {
    using other = BufferAllocator<U>;
  };
  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kLargeArrayBytes) return LargeArrayAllocator<T>::allocate(n);
    if (blocks) return static_cast<T*>(blocks->take(bytes));
    return static_cast<T*>(map_large(bytes, true));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (blocks && n * sizeof(T) >= kLargeArrayBytes) return blocks->give(p);
    LargeArrayAllocator<T>::deallocate(p, n);
  }
  template <class U>
  bool operator==(const BufferAllocator<U>& other) const noexcept {
    return blocks == other.blocks;
  }
};
template <class T>
using Buffer = std::vector<T, BufferAllocator<T>>;

// The decoding context of this thread's whole-frame decodes, made once.
ZSTD_DCtx* thread_decoder() {
  thread_local std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(),
                                                                            ZSTD_freeDCtx);
  if (!context) throw std::bad_alloc();
  return context.get();
}

// An unnamed temporary file (O_TMPFILE): it has no name to clean up and is gone when closed, even
// when the process is killed. Space a region no longer needs is given back (hole punching).
class Spill {
 public:
  Spill(const std::vector<fs::path>& directories, const std::string& name) {
    for (const auto& directory : directories) {
      if (directory.empty()) continue;
      fd_ = ::open(directory.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
      if (fd_ >= 0) return;
    }
    throw Error(ErrorCode::io, name +
                                   ": cannot create a temporary file to check it in bounded "
                                   "memory (tried the scratch directory, the file's directory, "
                                   "$TMPDIR and /tmp): " +
                                   std::strerror(errno));
  }
  ~Spill() { ::close(fd_); }
  Spill(const Spill&) = delete;
  Spill& operator=(const Spill&) = delete;

  // A new region of `bytes` bytes at the end of the file.
  std::uint64_t allocate(std::uint64_t bytes) {
    const auto at = end_;
    end_ += bytes;
    return at;
  }
  void write(const void* data, std::size_t size, std::uint64_t at) {
    const auto* p = static_cast<const char*>(data);
    while (size > 0) {
      const ssize_t done = ::pwrite(fd_, p, size, static_cast<off_t>(at));
      if (done < 0 && errno == EINTR) continue;
      if (done <= 0) fail("write");
      p += done, size -= static_cast<std::size_t>(done), at += static_cast<std::uint64_t>(done);
    }
  }
  void read(void* data, std::size_t size, std::uint64_t at) {
    auto* p = static_cast<char*>(data);
    while (size > 0) {
      const ssize_t done = ::pread(fd_, p, size, static_cast<off_t>(at));
      if (done < 0 && errno == EINTR) continue;
      if (done <= 0) fail("read");
      p += done, size -= static_cast<std::size_t>(done), at += static_cast<std::uint64_t>(done);
    }
  }
  std::uint64_t size() const { return end_; }
  void release(std::uint64_t at, std::uint64_t bytes) {
    (void)::fallocate(fd_, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, static_cast<off_t>(at),
                      static_cast<off_t>(bytes));  // only space: failing costs nothing else
  }

 private:
  [[noreturn]] void fail(const char* what) {
    throw Error(ErrorCode::io, std::string("cannot ") + what +
                                   " the temporary file of a bounded-memory check: " +
                                   (errno ? std::strerror(errno) : "end of file"));
  }
  int fd_ = -1;
  std::uint64_t end_ = 0;
};

// What one check shares: the file's name, its memory budget, and the spill file, made on first use.
struct Context {
  std::string name;
  std::uint64_t memory;
  std::vector<fs::path> spill_directories;
  std::unique_ptr<Spill> spill_file;
  VerifyWorkspace::Blocks* blocks = nullptr;  // the caller's workspace, if any

  template <class T>
  BufferAllocator<T> allocator() const {
    return BufferAllocator<T>(blocks);
  }

  Spill& spill() {
    if (!spill_file) spill_file = std::make_unique<Spill>(spill_directories, name);
    return *spill_file;
  }
  // An encoded section up to this size is decoded whole, in memory.
  std::uint64_t whole_limit() const { return memory / 4; }
};

struct ZstdStream {
  ZstdStream() : context(ZSTD_createDStream()) {
    if (!context) throw std::bad_alloc();
  }
  ~ZstdStream() { ZSTD_freeDStream(context); }
  ZstdStream(const ZstdStream&) = delete;
  ZstdStream& operator=(const ZstdStream&) = delete;
  ZSTD_DStream* context;
};

// A section's decoded bytes, front to back, in chunks of kChunk bytes (the last one shorter).
class SectionReader {
 public:
  SectionReader(const Section& s, Context& context)
      : s_(s), context_(context), whole_(context.allocator<std::byte>()) {
    if (!is_encoded(s)) return;
    if (s.decoded_length / kMaxZstdRatio > s.entry.stored_length)
      fail_section(s, context.name,
                   "declares " + std::to_string(s.decoded_length) +
                       " decoded bytes, more than its " + std::to_string(s.entry.stored_length) +
                       "-byte zstd frame can hold");
    check_frame_header(s, context.name);
    encoding_ = static_cast<Encoding>(s.entry.encoding);
    width_ = format::element_size(s.type);
    if (s.decoded_length <= context.whole_limit()) {
      whole_.resize(s.decoded_length);
      const std::size_t decoded = ZSTD_decompressDCtx(
          thread_decoder(), whole_.data(), whole_.size(), s.stored.data(), s.stored.size());
      check_decoded(decoded);
    } else {
      stream_ = std::make_unique<ZstdStream>();
      input_ = {s.stored.data(), s.stored.size(), 0};
      if (encoding_ != Encoding::zstd) spill_planes();
    }
    if (encoding_ != Encoding::zstd) chunk_.resize(kChunk);
  }
  ~SectionReader() {
    if (spilled_) context_.spill().release(spill_at_, s_.decoded_length);
  }
  SectionReader(const SectionReader&) = delete;
  SectionReader& operator=(const SectionReader&) = delete;

  // The next chunk; empty at the end. Valid until the next call.
  std::span<const std::byte> next() {
    const std::uint64_t rest = s_.decoded_length - position_;
    const auto size = static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, rest));
    std::span<const std::byte> out;
    if (size == 0) {
      release_raw(s_.decoded_length);
      return {};
    }
    if (!is_encoded(s_)) {
      release_raw(position_);
      out = s_.stored.subspan(position_, size);
    } else if (encoding_ == Encoding::zstd && !stream_) {
      out = std::span<const std::byte>(whole_).subspan(position_, size);
    } else if (encoding_ == Encoding::zstd) {
      chunk_.resize(kChunk);
      decode_into(chunk_.data(), size);
      out = std::span<const std::byte>(chunk_).first(size);
    } else {
      out = unshuffle(size);
    }
    position_ += size;
    return out;
  }

 private:
  // Pages of a raw section before `to` are read: let them go from this process (the file keeps
  // them in the page cache), so that reading a section costs no resident memory beyond a chunk.
  void release_raw(std::uint64_t to) {
    if (is_encoded(s_)) return;
    auto page_start = [](const std::byte* p) {
      return p - reinterpret_cast<std::uintptr_t>(p) % kPage;
    };
    const std::byte* from = released_ ? released_ : page_start(s_.stored.data());
    const std::byte* until = page_start(s_.stored.data() + to);
    if (until > from) {
      (void)::madvise(const_cast<std::byte*>(from), static_cast<std::size_t>(until - from),
                      MADV_DONTNEED);
      released_ = until;
    }
  }

  void check_decoded(std::size_t decoded) {
    if (ZSTD_isError(decoded))
      fail_section(s_, context_.name,
                   "zstd frame does not decode (" + std::string(ZSTD_getErrorName(decoded)) + ")");
    if (decoded != s_.decoded_length)
      fail_section(s_, context_.name,
                   "zstd frame decodes to " + std::to_string(decoded) +
                       " bytes, the table declares " + std::to_string(s_.decoded_length));
  }

  // The next `size` bytes of the frame's content. zstd itself holds the frame to the content size
  // its header declares (the table's, check_frame_header), so what is left to catch here is a frame
  // that ends early, is truncated, or does not decode.
  void decode_into(std::byte* out, std::size_t size) {
    ZSTD_outBuffer output{out, size, 0};
    while (output.pos < output.size) {
      const std::size_t before = output.pos, consumed = input_.pos;
      const std::size_t left = ZSTD_decompressStream(stream_->context, &output, &input_);
      if (ZSTD_isError(left))
        fail_section(s_, context_.name,
                     "zstd frame does not decode (" + std::string(ZSTD_getErrorName(left)) + ")");
      decoded_ += output.pos - before;
      finished_ = left == 0;
      if ((finished_ && output.pos < output.size) ||
          (output.pos == before && input_.pos == consumed))
        check_decoded(decoded_);  // ended early, or stuck on a truncated frame
    }
    if (decoded_ == s_.decoded_length && !finished_) {  // the frame's end (and its checksum)
      std::byte extra{};
      ZSTD_outBuffer probe{&extra, 1, 0};
      const std::size_t left = ZSTD_decompressStream(stream_->context, &probe, &input_);
      if (ZSTD_isError(left))
        fail_section(s_, context_.name,
                     "zstd frame does not decode (" + std::string(ZSTD_getErrorName(left)) + ")");
      if (probe.pos != 0 || left != 0) check_decoded(decoded_ + probe.pos + (left != 0));
      finished_ = true;
    }
  }

  // A large shuffled (or delta) frame: its content, plane after plane, into the spill file, so
  // that each chunk of elements can then read its bytes of every plane.
  void spill_planes() {
    Spill& spill = context_.spill();
    spill_at_ = spill.allocate(s_.decoded_length);
    spilled_ = true;
    Buffer<std::byte> buffer(kChunk);
    for (std::uint64_t done = 0; done < s_.decoded_length;) {
      const auto size =
          static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, s_.decoded_length - done));
      decode_into(buffer.data(), size);
      spill.write(buffer.data(), size, spill_at_ + done);
      done += size;
    }
  }

  // The elements of the next `size` bytes, gathered from every plane, then summed for deltas.
  std::span<const std::byte> unshuffle(std::size_t size) {
    const std::uint64_t count = s_.decoded_length / width_, first = position_ / width_;
    const std::size_t elements = size / width_;
    // Byte k of element first + i is at planes[k * stride + i].
    const std::byte* planes = spilled_ ? nullptr : whole_.data() + first;
    std::uint64_t stride = count;
    if (spilled_) {
      gathered_.resize(size);
      for (std::size_t k = 0; k < width_; ++k)
        context_.spill().read(gathered_.data() + k * elements, elements,
                              spill_at_ + k * count + first);
      planes = gathered_.data(), stride = elements;
    }
    with_width(width_, [&](auto width) {
      unshuffle_bytes<width()>(planes, stride, chunk_.data(), elements);
      if (encoding_ == Encoding::delta_zstd)
        carry_ = undelta_in_place<width()>(chunk_.data(), elements, carry_);
    });
    return std::span<const std::byte>(chunk_).first(size);
  }

  const Section& s_;
  Context& context_;
  Encoding encoding_ = Encoding::raw;
  std::size_t width_ = 1;
  std::uint64_t position_ = 0;
  const std::byte* released_ = nullptr;
  Buffer<std::byte> whole_, chunk_, gathered_;
  std::unique_ptr<ZstdStream> stream_;
  ZSTD_inBuffer input_{};
  std::uint64_t decoded_ = 0;
  bool finished_ = false;
  bool spilled_ = false;
  std::uint64_t spill_at_ = 0;
  std::uint64_t carry_ = 0;
};

template <class T>
std::span<const T> elements_of(std::span<const std::byte> chunk) {
  return {reinterpret_cast<const T*>(chunk.data()), chunk.size() / sizeof(T)};
}

// A section read through once: its checksum, and `f(chunk_elements, first_index)` on every chunk.
template <class T, class F>
void for_each_chunk(const Section& s, Context& context, Problem& checksum, F f) {
  SectionReader reader(s, context);
  Xxh3Stream hash;
  std::uint64_t first = 0;
  for (auto chunk = reader.next(); !chunk.empty(); chunk = reader.next()) {
    hash.update(chunk.data(), chunk.size());
    const auto values = elements_of<T>(chunk);
    f(values, first);
    first += values.size();
  }
  checksum = rules::checksum_problem(s, hash.digest());
}

// Its checksum, and `rule(chunk_elements, first_index)` on every chunk until it finds a problem.
template <class T, class Rule>
void read_section(const Section& s, Context& context, Problem& checksum, Problem& problem,
                  Rule rule) {
  for_each_chunk<T>(s, context, checksum, [&](std::span<const T> values, std::uint64_t first) {
    if (!problem) problem = rule(values, first);
  });
}

// One reverse CSR section as the transpose produces it, front to back: hashed (a derived section,
// whose checksum must then match) or compared with the stored section, read alongside.
template <class T>
class ReverseSink {
 public:
  ReverseSink(const Section& s, Context& context) : s_(s) {
    if (!is_derived(s)) stored_ = std::make_unique<SectionReader>(s, context);
  }
  void consume(std::span<const T> built) {
    if (!stored_) {
      hash_.update(built.data(), built.size_bytes());
      written_ += built.size();
      return;
    }
    while (!built.empty()) {
      if (stored_chunk_.empty()) {
        const auto chunk = stored_->next();
        if (chunk.empty()) return;  // not possible: the table gives both the same length
        hash_.update(chunk.data(), chunk.size());
        stored_chunk_ = elements_of<T>(chunk);
      }
      const std::size_t k = std::min(built.size(), stored_chunk_.size());
      if (!mismatch_ && std::memcmp(stored_chunk_.data(), built.data(), k * sizeof(T)) != 0)
        for (std::size_t i = 0; i < k; ++i)
          if (stored_chunk_[i] != built[i]) {
            mismatch_ = Mismatch{written_ + i, stored_chunk_[i], built[i]};
            break;
          }
      built = built.subspan(k), stored_chunk_ = stored_chunk_.subspan(k), written_ += k;
    }
  }
  void consume(T value) { consume(std::span<const T>(&value, 1)); }
  // After the last element: the checksum problem, and the first entry that differs.
  void finish(Problem& checksum, Problem& transpose) {
    if (stored_)
      for (auto chunk = stored_->next(); !chunk.empty(); chunk = stored_->next())
        hash_.update(chunk.data(), chunk.size());
    checksum = rules::checksum_problem(s_, hash_.digest());
    if (mismatch_)
      transpose = rules::in_section(
          s_, "reverse-transpose",
          "entry " + std::to_string(mismatch_->index) + " is " + std::to_string(mismatch_->stored) +
              ", the transpose of the forward CSR (§4) has " + std::to_string(mismatch_->built));
  }

 private:
  struct Mismatch {
    std::uint64_t index;
    T stored, built;
  };
  const Section& s_;
  std::unique_ptr<SectionReader> stored_;
  std::span<const T> stored_chunk_;
  Xxh3Stream hash_;
  std::uint64_t written_ = 0;
  std::optional<Mismatch> mismatch_;
};

// The reverse CSR of §4 built from the forward CSR's two sections, read once, and checked against
// the file's three reverse sections; on the way the forward sections' checksums and rules.
struct CsrCheck {
  Problem forward_offsets_checksum, forward_targets_checksum, forward_offsets, forward_targets;
  Problem reverse_checksum[3], transpose[3];
  bool forward_is_csr = false;
};

// The three reverse sections, fed a vertex range at a time.
struct ReverseSinks {
  ReverseSink<std::uint64_t> offsets;
  ReverseSink<std::uint32_t> sources, arcs;
  std::uint64_t entries = 0;  // in-list entries fed so far
  Buffer<std::uint64_t> offsets_buffer;

  // Vertices [v0, v0 + count.size()) whose in-degrees are `count`, and their in-lists.
  void feed(std::span<const std::uint64_t> in_degrees, std::span<const std::uint32_t> tails,
            std::span<const std::uint32_t> arc_ids) {
    for (std::size_t i = 0; i < in_degrees.size(); i += kChunk / 8) {
      const auto part = in_degrees.subspan(i, std::min(kChunk / 8, in_degrees.size() - i));
      offsets_buffer.resize(part.size());
      for (std::size_t k = 0; k < part.size(); ++k) {
        offsets_buffer[k] = entries;
        entries += part[k];
      }
      offsets.consume(std::span<const std::uint64_t>(offsets_buffer));
    }
    sources.consume(tails);
    arcs.consume(arc_ids);
  }
  // After the last vertex: each section's checksum problem and first difference.
  void finish(CsrCheck& out) {
    offsets.finish(out.reverse_checksum[0], out.transpose[0]);
    sources.finish(out.reverse_checksum[1], out.transpose[1]);
    arcs.finish(out.reverse_checksum[2], out.transpose[2]);
  }
};

// Arcs as the transpose needs them, in arc id order within any range of heads.
struct ArcRecord {
  std::uint32_t arc, head, tail;
};

// The in-lists of the heads [v0, v1), from `records` (arcs in ascending id, all with heads in the
// range), by one counting sort.
void feed_range(ReverseSinks& sinks, std::uint64_t v0, std::uint64_t v1,
                std::span<const std::uint32_t> arcs, std::span<const std::uint32_t> heads,
                std::span<const std::uint32_t> tails) {
  Buffer<std::uint64_t> start(v1 - v0 + 1);
  std::fill(start.begin(), start.end(), 0);
  for (const auto h : heads) ++start[h - v0 + 1];
  Buffer<std::uint64_t> in_degrees(start.begin() + 1, start.end());
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  Buffer<std::uint32_t> list_tails(heads.size()), list_arcs(heads.size());
  for (std::size_t i = 0; i < heads.size(); ++i) {
    const auto at = start[heads[i] - v0]++;
    list_tails[at] = tails[i];
    list_arcs[at] = arcs[i];
  }
  sinks.feed(in_degrees, list_tails, list_arcs);
}

// The forward CSR's arcs (in id order, each with its head and tail) into the reverse CSR's order
// when they do not fit the memory: spilled in blocks per range of heads (a bucket), then each
// bucket sorted alone, a bucket too large for the memory in narrower ranges.
class Transposer {
 public:
  Transposer(Context& context, std::uint64_t n, std::uint64_t m) : context_(context), n_(n) {
    const std::uint64_t need = 16 * m + 8 * (n + 1);  // records, in-lists, counts
    buckets_ = std::clamp<std::uint64_t>((need + context.memory / 2 - 1) / (context.memory / 2), 1,
                                         std::max<std::uint64_t>(n, 1));
    width_ = std::max<std::uint64_t>((n + buckets_ - 1) / buckets_, 1);
    block_ = std::max<std::uint64_t>(context.memory / 4 / buckets_ / sizeof(ArcRecord), 64);
    pending_.resize(buckets_);
    blocks_.resize(buckets_);
    counts_.resize(buckets_, 0);
  }

  // Arc `arc` (ids ascending, from 0) from `tail` to `head` (below n, or it is left out: the
  // forward CSR is then no CSR, which is reported instead).
  void add(std::uint32_t arc, std::uint32_t head, std::uint32_t tail) {
    if (head >= n_) return;
    const auto b = head / width_;
    auto& pending = pending_[b];
    pending.push_back({arc, head, tail});
    ++counts_[b];
    if (pending.size() == block_) flush(b);
  }

  void finish(ReverseSinks& sinks) {
    for (std::uint64_t b = 0; b < buckets_; ++b) flush(b);
    pending_ = {};
    for (std::uint64_t b = 0; b < buckets_; ++b)
      feed_bucket(sinks, std::min(n_, b * width_), std::min(n_, (b + 1) * width_), blocks_[b],
                  counts_[b]);
    sinks.offsets.consume(sinks.entries);  // reverse_offsets[n] = m
  }

 private:
  struct Block {
    std::uint64_t at, count;
  };

  void flush(std::uint64_t b) {
    auto& pending = pending_[b];
    if (pending.empty()) return;
    Spill& spill = context_.spill();
    const Block block{spill.allocate(pending.size() * sizeof(ArcRecord)), pending.size()};
    spill.write(pending.data(), pending.size() * sizeof(ArcRecord), block.at);
    blocks_[b].push_back(block);
    pending.clear();
  }

  // Calls f(record) for each record of `blocks`, in arc order.
  template <class F>
  void read_blocks(const std::vector<Block>& blocks, F f) {
    Buffer<ArcRecord> buffer;
    for (const auto& block : blocks) {
      buffer.resize(block.count);
      context_.spill().read(buffer.data(), block.count * sizeof(ArcRecord), block.at);
      for (const auto& r : buffer) f(r);
    }
  }

  // The heads [v0, v1) holding `count` arcs: sorted at once when they fit the memory, else in
  // ranges of about the memory's worth of arcs each (counted first), one pass over the bucket per
  // range; a single head with more arcs than that needs no sort: its arcs come in id order.
  void feed_bucket(ReverseSinks& sinks, std::uint64_t v0, std::uint64_t v1,
                   const std::vector<Block>& blocks, std::uint64_t count) {
    const std::uint64_t fits = std::max<std::uint64_t>(context_.memory / 2 / 24, 64);
    std::vector<std::pair<std::uint64_t, std::uint64_t>> ranges;  // [first, last) heads
    if (count <= fits) {
      ranges.emplace_back(v0, v1);
    } else {
      std::vector<std::uint64_t> in_degree(v1 - v0, 0);
      read_blocks(blocks, [&](const ArcRecord& r) { ++in_degree[r.head - v0]; });
      std::uint64_t first = v0, held = 0;
      for (std::uint64_t v = v0; v < v1; ++v) {
        if (held > 0 && held + in_degree[v - v0] > fits)
          ranges.emplace_back(first, v), first = v, held = 0;
        held += in_degree[v - v0];
      }
      ranges.emplace_back(first, v1);
    }
    Buffer<std::uint32_t> arcs, heads, tails;
    for (const auto& range : ranges) {
      // Not a structured binding: clang 14's lambdas cannot capture one.
      const std::uint64_t first = range.first, last = range.second;
      arcs.clear(), heads.clear(), tails.clear();
      if (last - first == 1 && count > fits) {
        // One head: its in-list is its arcs in id order, fed a chunk at a time.
        std::uint64_t degree = 0;
        read_blocks(blocks, [&](const ArcRecord& r) { degree += r.head == first; });
        sinks.feed(std::span<const std::uint64_t>(&degree, 1), {}, {});
        read_blocks(blocks, [&](const ArcRecord& r) {
          if (r.head != first) return;
          tails.push_back(r.tail), arcs.push_back(r.arc);
          if (tails.size() == kChunk / 4) {
            sinks.sources.consume(std::span<const std::uint32_t>(tails));
            sinks.arcs.consume(std::span<const std::uint32_t>(arcs));
            tails.clear(), arcs.clear();
          }
        });
        sinks.sources.consume(std::span<const std::uint32_t>(tails));
        sinks.arcs.consume(std::span<const std::uint32_t>(arcs));
        continue;
      }
      read_blocks(blocks, [&](const ArcRecord& r) {
        if (r.head < first || r.head >= last) return;
        arcs.push_back(r.arc), heads.push_back(r.head), tails.push_back(r.tail);
      });
      feed_range(sinks, first, last, arcs, heads, tails);
    }
    for (const auto& block : blocks)
      context_.spill().release(block.at, block.count * sizeof(ArcRecord));
  }

  Context& context_;
  std::uint64_t n_;
  std::uint64_t buckets_ = 1, width_ = 1, block_ = 0;
  std::vector<std::vector<ArcRecord>> pending_;  // per bucket, not yet spilled
  std::vector<std::vector<Block>> blocks_;       // per bucket, spilled, in arc order
  std::vector<std::uint64_t> counts_;
};

// The forward offsets' rules, seen a chunk at a time: never decreasing (across chunks too), and
// from 0 to m (step 9 of FORMAT.md §9, which the open checks only for a raw section).
struct ForwardOffsetsRule {
  const Section& s;
  Problem problem;
  std::uint64_t front = 0, back = 0;  // the first and the last offset seen
  bool seen = false;

  void check(std::span<const std::uint64_t> chunk, std::uint64_t first) {
    if (chunk.empty()) return;
    if (!problem && seen && back > chunk.front()) {
      const std::uint64_t pair[] = {back, chunk.front()};
      problem = rules::check_offsets(s, pair, first - 1);
    }
    if (!problem && !rules::offsets_ascend(chunk)) problem = rules::check_offsets(s, chunk, first);
    if (!seen) front = chunk.front();
    seen = true, back = chunk.back();
  }
  // After the last chunk: the first problem, the ends' included.
  Problem finish(std::uint64_t m) {
    if (!problem && (front != 0 || back != m))
      problem = rules::in_section(s, "offsets-ends",
                                  "offsets run from " + std::to_string(front) + " to " +
                                      std::to_string(back) + ", not from 0 to the arc count " +
                                      std::to_string(m));
    return problem;
  }
};

ReverseSinks sinks_for(const GraphReader& reader, Context& context) {
  return {{*reader.all(SectionKind::reverse_offsets).front(), context},
          {*reader.all(SectionKind::reverse_sources).front(), context},
          {*reader.all(SectionKind::reverse_arcs).front(), context},
          0,
          {}};
}

// The forward CSR in buckets of heads, spilled (Transposer), read once in lockstep: arc a leaves
// the vertex u with offsets[u] <= a < offsets[u + 1].
CsrCheck check_csr_in_buckets(const GraphReader& reader, Context& context) {
  const auto section = [&](SectionKind kind) -> const Section& {
    return *reader.all(kind).front();
  };
  const Section &fo = section(SectionKind::forward_offsets),
                &ft = section(SectionKind::forward_targets);
  const std::uint64_t n = reader.vertex_count(), m = reader.arc_count();
  CsrCheck out;
  Transposer transposer(context, n, m);
  {
    SectionReader offsets_reader(fo, context);
    Xxh3Stream offsets_hash, targets_hash;
    std::span<const std::uint64_t> offsets;  // the current chunk
    std::uint64_t offsets_first = 0;
    ForwardOffsetsRule offsets_rule{fo, {}};
    // offsets[v] for v at or after the current chunk; false past the end.
    auto offset_at = [&](std::uint64_t v, std::uint64_t& value) {
      while (v >= offsets_first + offsets.size()) {
        const auto chunk = offsets_reader.next();
        if (chunk.empty()) return false;
        offsets_hash.update(chunk.data(), chunk.size());
        offsets_first += offsets.size();
        offsets = elements_of<std::uint64_t>(chunk);
        offsets_rule.check(offsets, offsets_first);
      }
      value = offsets[v - offsets_first];
      return true;
    };

    SectionReader targets_reader(ft, context);
    std::uint64_t tail = 0, tail_end = 0, arc = 0;
    offset_at(std::min<std::uint64_t>(1, n), tail_end);
    for (auto chunk = targets_reader.next(); !chunk.empty(); chunk = targets_reader.next()) {
      targets_hash.update(chunk.data(), chunk.size());
      const auto targets = elements_of<std::uint32_t>(chunk);
      if (!out.forward_targets && !rules::ids_below(targets, n))
        out.forward_targets = rules::check_ids(ft, targets, n, "target-range", "arc", arc);
      for (const std::uint32_t head : targets) {
        while (arc >= tail_end && tail + 1 < n) {
          ++tail;
          if (!offset_at(tail + 1, tail_end)) break;
        }
        transposer.add(static_cast<std::uint32_t>(arc), head, static_cast<std::uint32_t>(tail));
        ++arc;
      }
    }
    std::uint64_t last = 0;
    while (offset_at(offsets_first + offsets.size(), last)) {  // the rest, for the rules and hash
    }
    out.forward_offsets_checksum = rules::checksum_problem(fo, offsets_hash.digest());
    out.forward_targets_checksum = rules::checksum_problem(ft, targets_hash.digest());
    out.forward_offsets = offsets_rule.finish(m);
  }
  out.forward_is_csr = !out.forward_offsets && !out.forward_targets;

  auto sinks = sinks_for(reader, context);
  transposer.finish(sinks);
  sinks.finish(out);
  return out;
}

// True when the forward CSR and its transpose fit the memory (16 (n + 1) + 12 m bytes): checked
// in memory, else in buckets spilled to disk.
bool csr_fits(const GraphReader& reader, std::uint64_t memory) {
  return 16 * (reader.vertex_count() + 1) + 12 * reader.arc_count() <= memory;
}

// The forward CSR in memory, when it and its transpose fit: the transpose by derive_transpose, as
// unpacking derives it.
CsrCheck check_csr(const GraphReader& reader, Context& context) {
  const std::uint64_t n = reader.vertex_count(), m = reader.arc_count();
  if (!csr_fits(reader, context.memory)) return check_csr_in_buckets(reader, context);
  const Section& fo = *reader.all(SectionKind::forward_offsets).front();
  const Section& ft = *reader.all(SectionKind::forward_targets).front();
  CsrCheck out;
  Buffer<std::uint64_t> offsets(n + 1, context.allocator<std::uint64_t>());
  Buffer<std::uint32_t> targets(m, context.allocator<std::uint32_t>());
  ForwardOffsetsRule offsets_rule{fo, {}};
  for_each_chunk<std::uint64_t>(
      fo, context, out.forward_offsets_checksum, [&](auto values, std::uint64_t first) {
        std::memcpy(offsets.data() + first, values.data(), values.size_bytes());
        offsets_rule.check(values, first);
      });
  for_each_chunk<std::uint32_t>(
      ft, context, out.forward_targets_checksum, [&](auto values, std::uint64_t first) {
        std::memcpy(targets.data() + first, values.data(), values.size_bytes());
        if (!out.forward_targets && !rules::ids_below(values, n))
          out.forward_targets = rules::check_ids(ft, values, n, "target-range", "arc", first);
      });
  out.forward_offsets = offsets_rule.finish(m);
  out.forward_is_csr = !out.forward_offsets && !out.forward_targets;
  auto sinks = sinks_for(reader, context);
  if (out.forward_is_csr) {
    Buffer<std::uint64_t> reverse_offsets(n + 1, context.allocator<std::uint64_t>());
    Buffer<std::uint32_t> reverse_sources(m, context.allocator<std::uint32_t>()),
        reverse_arcs(m, context.allocator<std::uint32_t>());
    derive_transpose(offsets, targets, reverse_offsets.data(), reverse_sources.data(),
                     reverse_arcs.data());
    offsets = {}, targets = {};
    sinks.offsets.consume(std::span<const std::uint64_t>(reverse_offsets));
    sinks.sources.consume(std::span<const std::uint32_t>(reverse_sources));
    sinks.arcs.consume(std::span<const std::uint32_t>(reverse_arcs));
  }
  sinks.finish(out);
  return out;
}

// Every other section (not the CSR's five): its checksum and the rule of its kind.
void check_other_sections(const GraphReader& reader, Context& context,
                          std::vector<Problem>& checksums, std::vector<Problem>& values,
                          std::string& metadata_text) {
  const std::uint64_t n = reader.vertex_count();
  const auto& sections = reader.sections();
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const Section& s = sections[i];
    const auto kind = s.kind;
    if (kind == SectionKind::forward_offsets || kind == SectionKind::forward_targets ||
        kind == SectionKind::reverse_offsets || kind == SectionKind::reverse_sources ||
        kind == SectionKind::reverse_arcs)
      continue;
    auto none = [](auto, std::uint64_t) { return Problem{}; };
    if (kind == SectionKind::cost && s.type == ElementType::f32) {
      read_section<float>(s, context, checksums[i], values[i], [&](auto v, std::uint64_t first) {
        return rules::check_float_values(s, v, "cost", "arc", "costs", first);
      });
    } else if (kind == SectionKind::cost && s.type == ElementType::f64) {
      read_section<double>(s, context, checksums[i], values[i], [&](auto v, std::uint64_t first) {
        return rules::check_float_values(s, v, "cost", "arc", "costs", first);
      });
    } else if (kind == SectionKind::queries) {
      read_section<std::uint32_t>(
          s, context, checksums[i], values[i], [&](auto v, std::uint64_t first) {
            return rules::check_ids(s, v, n, "query-range", "endpoint", first);
          });
    } else if (kind == SectionKind::query_reference) {
      read_section<double>(s, context, checksums[i], values[i], [&](auto v, std::uint64_t first) {
        return rules::check_float_values(s, v, "reference", "query", "has", first);
      });
    } else if (kind == SectionKind::metadata) {
      read_section<char>(s, context, checksums[i], values[i],
                         [&](std::span<const char> v, std::uint64_t) {
                           metadata_text.append(v.data(), v.size());
                           return Problem{};
                         });
    } else {
      read_section<std::byte>(s, context, checksums[i], values[i], none);
    }
  }
}

Problem check_metadata(const GraphReader& reader, const std::string& text) {
  const Section& s = *reader.all(SectionKind::metadata).front();
  Metadata metadata;
  try {
    metadata = Metadata::parse(text);
  } catch (const Error& e) {
    return rules::in_section(s, "metadata", e.what());
  }
  return rules::metadata_problem(reader, metadata);
}

std::vector<fs::path> spill_directories(const fs::path& file, const fs::path& scratch) {
  std::vector<fs::path> out{scratch, file.parent_path().empty() ? "." : file.parent_path()};
  if (const char* tmp = std::getenv("TMPDIR")) out.emplace_back(tmp);
  out.emplace_back("/tmp");
  return out;
}

// Refuses, before anything is spilled, a check whose spill file could grow past the limit.
void check_spill_limit(const GraphReader& reader, const Context& context,
                       const StreamingVerifyOptions& options) {
  const std::uint64_t size = reader.bytes().size();
  const std::uint64_t limit = options.disk.value_or(default_check_disk(size, context.memory));
  const std::uint64_t bound = streaming_spill_bound(reader, context.memory);
  if (bound <= limit) return;
  throw Error(ErrorCode::no_memory,
              {context.name + ": checking it in " + std::to_string(context.memory) +
                   " bytes of memory needs up to " + std::to_string(bound) +
                   " bytes of disk for its spill file, more than the limit of " +
                   std::to_string(limit) + " bytes (" +
                   (options.disk ? std::string("as asked")
                                 : "the default: " + std::to_string(kCheckDiskPerFileByte) +
                                       " times its " + std::to_string(size) + " bytes or " +
                                       std::to_string(kCheckDiskPerMemoryByte) +
                                       " times the memory, whichever is more") +
                   "; ",
               setting("streaming_verify.disk"), " SIZE, or more ",
               setting("streaming_verify.memory"), ", allows it)"});
}

}  // namespace

std::uint64_t streaming_spill_bound(const GraphReader& reader, std::uint64_t memory) {
  memory = std::max<std::uint64_t>(memory, 4096);
  // The transpose in buckets: every arc's record (Transposer), all written before any is read.
  std::uint64_t bound = csr_fits(reader, memory) ? 0 : reader.arc_count() * sizeof(ArcRecord);
  // A shuffled or delta frame too large to decode whole: its content (SectionReader). Regions
  // given back are not reused, so the file's size is the sum, whatever the holes punched.
  for (const Section& s : reader.sections())
    if (is_encoded(s) && !is_derived(s) &&
        s.entry.encoding != static_cast<std::uint8_t>(Encoding::zstd) &&
        s.decoded_length > memory / 4)
      bound += s.decoded_length;
  return bound;
}

FileVerification verify_file_streaming(const fs::path& path,
                                       const StreamingVerifyOptions& options) {
  const auto file = map_file(path);
  Context context{path.string(), std::max<std::uint64_t>(options.memory, 4096),
                  spill_directories(path, options.scratch_directory), nullptr,
                  options.workspace ? options.workspace->blocks_.get() : nullptr};
  // The open checks (§9 steps 1-9); raw forward offsets' ends are checked here.
  const auto reader = GraphReader::adopt(file, context.name);
  // A derived reverse CSR needs the forward one in the shapes of §4: refused as unpacking refuses.
  (void)transpose_plan(reader.sections(), context.name);
  check_spill_limit(reader, context, options);
  const auto& sections = reader.sections();
  std::vector<Problem> checksums(sections.size()), values(sections.size());
  std::string metadata_text;
  const CsrCheck csr = check_csr(reader, context);
  check_other_sections(reader, context, checksums, values, metadata_text);

  // The first problem, in verify()'s order: checksums (a derived section's once the forward CSR
  // is one, else what unpacking says), the forward CSR's rules, the transpose, the other rules,
  // the metadata, the padding.
  const auto index_of = [&](SectionKind kind) {
    return static_cast<std::size_t>(reader.all(kind).front() - sections.data());
  };
  checksums[index_of(SectionKind::forward_offsets)] = csr.forward_offsets_checksum;
  checksums[index_of(SectionKind::forward_targets)] = csr.forward_targets_checksum;
  const SectionKind reverse[] = {SectionKind::reverse_offsets, SectionKind::reverse_sources,
                                 SectionKind::reverse_arcs};
  const bool derives = std::any_of(sections.begin(), sections.end(), is_derived);
  for (int k = 0; k < 3; ++k) {
    const auto i = index_of(reverse[k]);
    if (!is_derived(sections[i]) || csr.forward_is_csr) checksums[i] = csr.reverse_checksum[k];
  }
  auto result = [&](Problem problem) {
    return FileVerification{std::move(problem), reader.digest(),
                            context.spill_file ? context.spill_file->size() : 0};
  };
  for (auto& p : checksums)
    if (p) return result(p);
  if (derives && !csr.forward_is_csr)
    throw Error(ErrorCode::damaged,
                context.name +
                    ": the reverse CSR cannot be derived (transpose encoding): the forward CSR "
                    "is not one (offsets from 0 to m, never decreasing, every target below n)");
  if (csr.forward_offsets) return result(csr.forward_offsets);
  if (csr.forward_targets) return result(csr.forward_targets);
  for (const auto& p : csr.transpose)
    if (p) return result(p);
  for (auto& p : values)
    if (p) return result(p);
  if (auto p = check_metadata(reader, metadata_text)) return result(p);
  return result(find_padding_problem(reader));
}

}  // namespace mosb
