#include "mosb/converters/text_input.hpp"

#include <bzlib.h>
#include <fcntl.h>
#include <lzma.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>
#include <zstd.h>
#include <zstd_errors.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "mosb/checksum.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/internal/utf8.hpp"

namespace mosb::converters {

namespace {

bool starts_with_bytes(std::string_view raw, std::initializer_list<unsigned char> magic) {
  if (raw.size() < magic.size()) return false;
  std::size_t i = 0;
  for (auto b : magic)
    if (static_cast<unsigned char>(raw[i++]) != b) return false;
  return true;
}

// A decoder of one compression format, stepped over input and output windows.
class Codec {
 public:
  virtual ~Codec() = default;
  // Decodes from `in` into `out`, setting what it consumed and produced; true when a stream
  // (gzip member, bzip2 stream, zstd frame; for xz all of them) has ended. `last` says that `in`
  // reaches the end of the file. Throws std::runtime_error with the library's words on bad data.
  virtual bool step(const char* in, std::size_t in_size, bool last, std::size_t& consumed,
                    char* out, std::size_t out_size, std::size_t& produced) = 0;
  // Ready for a further concatenated stream.
  virtual void reset() = 0;
};

constexpr std::size_t kStepInput = std::size_t{1} << 30;  // the libraries count in 32 bits

class GzipCodec final : public Codec {
 public:
  GzipCodec() {
    if (inflateInit2(&z_, 16 + MAX_WBITS) != Z_OK) throw std::bad_alloc();
  }
  ~GzipCodec() override { inflateEnd(&z_); }
  bool step(const char* in, std::size_t in_size, bool, std::size_t& consumed, char* out,
            std::size_t out_size, std::size_t& produced) override {
    z_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in));
    z_.avail_in = static_cast<uInt>(std::min(in_size, kStepInput));
    z_.next_out = reinterpret_cast<Bytef*>(out);
    z_.avail_out = static_cast<uInt>(std::min(out_size, kStepInput));
    const auto in_before = z_.avail_in, out_before = z_.avail_out;
    const int r = inflate(&z_, Z_NO_FLUSH);
    consumed = in_before - z_.avail_in;
    produced = out_before - z_.avail_out;
    if (r == Z_STREAM_END) return true;
    if (r == Z_OK || r == Z_BUF_ERROR) return false;
    if (r == Z_MEM_ERROR) throw std::bad_alloc();
    throw std::runtime_error(z_.msg ? z_.msg : "zlib error " + std::to_string(r));
  }
  void reset() override { inflateReset(&z_); }

 private:
  z_stream z_{};
};

class Bzip2Codec final : public Codec {
 public:
  Bzip2Codec() { init(); }
  ~Bzip2Codec() override { BZ2_bzDecompressEnd(&s_); }
  bool step(const char* in, std::size_t in_size, bool, std::size_t& consumed, char* out,
            std::size_t out_size, std::size_t& produced) override {
    s_.next_in = const_cast<char*>(in);
    s_.avail_in = static_cast<unsigned>(std::min(in_size, kStepInput));
    s_.next_out = out;
    s_.avail_out = static_cast<unsigned>(std::min(out_size, kStepInput));
    const auto in_before = s_.avail_in, out_before = s_.avail_out;
    const int r = BZ2_bzDecompress(&s_);
    consumed = in_before - s_.avail_in;
    produced = out_before - s_.avail_out;
    if (r == BZ_STREAM_END) return true;
    if (r == BZ_OK) return false;
    if (r == BZ_MEM_ERROR) throw std::bad_alloc();
    throw std::runtime_error(r == BZ_DATA_ERROR_MAGIC ? "not bzip2 data"
                             : r == BZ_DATA_ERROR     ? "data integrity error"
                                                      : "bzip2 error " + std::to_string(r));
  }
  void reset() override {
    BZ2_bzDecompressEnd(&s_);
    init();
  }

 private:
  void init() {
    s_ = bz_stream{};
    if (BZ2_bzDecompressInit(&s_, 0, 0) != BZ_OK) throw std::bad_alloc();
  }
  bz_stream s_{};
};

class XzCodec final : public Codec {
 public:
  XzCodec() { init(); }
  ~XzCodec() override { lzma_end(&s_); }
  bool step(const char* in, std::size_t in_size, bool last, std::size_t& consumed, char* out,
            std::size_t out_size, std::size_t& produced) override {
    s_.next_in = reinterpret_cast<const std::uint8_t*>(in);
    s_.avail_in = in_size;
    s_.next_out = reinterpret_cast<std::uint8_t*>(out);
    s_.avail_out = out_size;
    const lzma_ret r = lzma_code(&s_, last ? LZMA_FINISH : LZMA_RUN);
    consumed = in_size - s_.avail_in;
    produced = out_size - s_.avail_out;
    if (r == LZMA_STREAM_END) return true;
    if (r == LZMA_OK || r == LZMA_BUF_ERROR) return false;
    if (r == LZMA_MEM_ERROR) throw std::bad_alloc();
    throw std::runtime_error(r == LZMA_FORMAT_ERROR ? "not xz data"
                             : r == LZMA_DATA_ERROR
                                 ? "data error"
                                 : "xz error " + std::to_string(static_cast<int>(r)));
  }
  void reset() override {
    lzma_end(&s_);
    init();
  }

 private:
  void init() {
    s_ = LZMA_STREAM_INIT;
    // Concatenated streams and stream padding are decoded in one go (LZMA_FINISH ends them).
    if (lzma_stream_decoder(&s_, UINT64_MAX, LZMA_CONCATENATED) != LZMA_OK) throw std::bad_alloc();
  }
  lzma_stream s_ = LZMA_STREAM_INIT;
};

class ZstdCodec final : public Codec {
 public:
  ZstdCodec() : d_(ZSTD_createDStream()) {
    if (d_ == nullptr) throw std::bad_alloc();
  }
  ~ZstdCodec() override { ZSTD_freeDStream(d_); }
  bool step(const char* in, std::size_t in_size, bool, std::size_t& consumed, char* out,
            std::size_t out_size, std::size_t& produced) override {
    ZSTD_inBuffer input{in, in_size, 0};
    ZSTD_outBuffer output{out, out_size, 0};
    const std::size_t r = ZSTD_decompressStream(d_, &output, &input);
    consumed = input.pos;
    produced = output.pos;
    if (ZSTD_isError(r)) {
      if (ZSTD_getErrorCode(r) == ZSTD_error_memory_allocation) throw std::bad_alloc();
      throw std::runtime_error(ZSTD_getErrorName(r));
    }
    return r == 0;  // a frame ended and its output is flushed
  }
  void reset() override { ZSTD_DCtx_reset(d_, ZSTD_reset_session_only); }

 private:
  ZSTD_DStream* d_;
};

std::unique_ptr<Codec> make_codec(Compression c) {
  switch (c) {
    case Compression::gzip:
      return std::make_unique<GzipCodec>();
    case Compression::bzip2:
      return std::make_unique<Bzip2Codec>();
    case Compression::xz:
      return std::make_unique<XzCodec>();
    case Compression::zstd:
      return std::make_unique<ZstdCodec>();
    case Compression::none:
      break;
  }
  return nullptr;
}

constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
// Plain input is handed out in chunks of about this size; whole pages are released behind them.
constexpr std::size_t kPlainChunkBytes = std::size_t{8} << 20;
std::size_t page_bytes() {
  static const long size = ::sysconf(_SC_PAGESIZE);
  return size > 0 ? static_cast<std::size_t>(size) : 4096;
}

}  // namespace

Compression detect_compression(std::string_view raw) {
  if (starts_with_bytes(raw, {0x1F, 0x8B})) return Compression::gzip;
  if (starts_with_bytes(raw, {'B', 'Z', 'h'})) return Compression::bzip2;
  if (starts_with_bytes(raw, {0xFD, '7', 'z', 'X', 'Z', 0x00})) return Compression::xz;
  if (starts_with_bytes(raw, {0x28, 0xB5, 0x2F, 0xFD})) return Compression::zstd;
  return Compression::none;
}

const char* compression_name(Compression c) {
  switch (c) {
    case Compression::none:
      return "none";
    case Compression::gzip:
      return "gzip";
    case Compression::bzip2:
      return "bzip2";
    case Compression::xz:
      return "xz";
    case Compression::zstd:
      return "zstd";
  }
  return "unknown";
}

// The raw bytes (mapped, or read whole when the file cannot be mapped) and, for compressed
// input, the decoder with its bounded buffer.
struct InputFile::Stream {
  void* mapping = nullptr;
  std::size_t mapped_size = 0;
  std::string owned;  // raw bytes of an input that is not a regular file
  std::string_view raw;

  std::unique_ptr<Codec> codec;
  std::size_t raw_pos = 0;
  bool decoded_all = false;
  std::vector<char> buffer;
  std::size_t filled = 0;          // bytes of `buffer` holding text
  std::size_t delivered = 0;       // bytes of `buffer` already returned as a chunk
  std::size_t plain_pos = 0;       // plain input: bytes of `raw` already returned as chunks
  std::size_t plain_released = 0;  // plain mapped input: bytes of `raw` given back to the kernel

  ~Stream() {
    if (mapping != nullptr) munmap(mapping, mapped_size);
  }

  // Decodes into buffer[filled, end); returns the bytes added (0 only at the end of the data).
  std::size_t decode(const InputFacts& facts) {
    const char* format = compression_name(facts.compression);
    std::size_t added = 0;
    while (filled + added < buffer.size() && !decoded_all) {
      std::size_t consumed = 0, produced = 0;
      bool ended = false;
      try {
        ended =
            codec->step(raw.data() + raw_pos, raw.size() - raw_pos, true, consumed,
                        buffer.data() + filled + added, buffer.size() - filled - added, produced);
      } catch (const std::runtime_error& e) {
        throw Error(facts.display_name + ": corrupt " + format + " data (" + e.what() +
                    "): the file is truncated or corrupt");
      }
      raw_pos += consumed;
      added += produced;
      if (ended) {
        if (raw_pos == raw.size())
          decoded_all = true;
        else
          codec->reset();  // a further concatenated stream follows
        continue;
      }
      if (consumed == 0 && produced == 0) {
        if (raw_pos == raw.size())
          throw Error(facts.display_name + ": the " + format +
                      " data ends before its end marker: the file is truncated or corrupt");
        throw Error(facts.display_name + ": corrupt " + format +
                    " data: the file is truncated or corrupt");
      }
    }
    return added;
  }
};

InputFile::InputFile(const std::filesystem::path& path) : stream_(std::make_unique<Stream>()) {
  facts_.display_name = path.string();
  facts_.base_name = path.filename().string();
  auto& s = *stream_;
  // O_NONBLOCK: opening a FIFO that no process writes to would wait forever. The flag is cleared
  // at once, so a pipe with a writer is read to its end as before.
  const int fd = ::open(facts_.display_name.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw Error(facts_.display_name + ": cannot open: " + std::strerror(errno));
  if (const int flags = ::fcntl(fd, F_GETFL); flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  struct stat st {};
  const bool have_stat = ::fstat(fd, &st) == 0;
  bool mapped = false;
  if (have_stat && S_ISREG(st.st_mode)) {
    if (st.st_size == 0) {
      mapped = true;
    } else {
      // MAP_POPULATE faults the pages in at once, much cheaper than one fault per page.
      void* p = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ,
                       MAP_PRIVATE | MAP_POPULATE, fd, 0);
      if (p != MAP_FAILED) {
        s.mapping = p;
        s.mapped_size = static_cast<std::size_t>(st.st_size);
        s.raw = std::string_view(static_cast<const char*>(p), s.mapped_size);
        ::madvise(p, s.mapped_size, MADV_SEQUENTIAL);
        mapped = true;
      }
    }
  }
  if (!mapped) {
    char buffer[1 << 16];
    try {
      read_chunks(fd, path, buffer,
                  [&](const char* data, std::size_t size) { s.owned.append(data, size); });
    } catch (...) {
      ::close(fd);
      throw;
    }
    s.raw = s.owned;
  }
  ::close(fd);
  if (have_stat && S_ISFIFO(st.st_mode) && s.raw.empty())
    throw Error(facts_.display_name +
                ": is a FIFO with no writer, or an empty one: nothing to read");
  facts_.raw_size = s.raw.size();
  facts_.raw_xxh3 = hex64(xxh3_64(s.raw.data(), s.raw.size()));
  facts_.compression = detect_compression(s.raw);
  rewind();
}

InputFile::~InputFile() = default;

std::uint64_t InputFile::size_hint() const {
  return facts_.compression == Compression::none ? facts_.raw_size : 16 * facts_.raw_size;
}

void InputFile::rewind() {
  auto& s = *stream_;
  s.plain_pos = 0;
  s.plain_released = 0;
  s.raw_pos = 0;
  s.decoded_all = false;
  s.filled = s.delivered = 0;
  s.codec.reset();
  if (facts_.compression != Compression::none) {
    s.codec = make_codec(facts_.compression);
    if (s.buffer.size() < kChunkBytes) s.buffer.resize(kChunkBytes);
  }
}

bool InputFile::next_chunk(std::string_view& chunk) {
  const bool more = next_chunk_of_text(chunk);
  if (progress_) {
    // Raw bytes consumed: the plain text handed out, or the compressed bytes decoded.
    const auto& s = *stream_;
    const std::uint64_t consumed = s.codec ? s.raw_pos : s.plain_pos;
    if (consumed > counted_) progress_->add(consumed - counted_);
    counted_ = std::max(counted_, consumed);
  }
  return more;
}

bool InputFile::next_chunk_of_text(std::string_view& chunk) {
  auto& s = *stream_;
  if (!s.codec) {
    // A mapped file's pages already read are given back (a chunk is valid until the next call),
    // so a streaming parser holds about one chunk of the text in memory, not the whole file.
    if (s.mapping != nullptr) {
      const std::size_t page = page_bytes();
      const std::size_t release_end = s.plain_pos / page * page;
      if (release_end > s.plain_released) {
        ::madvise(static_cast<char*>(s.mapping) + s.plain_released, release_end - s.plain_released,
                  MADV_DONTNEED);
        s.plain_released = release_end;
      }
    }
    if (s.plain_pos == s.raw.size()) return false;
    // Chunks end after a newline, as the decoded ones do, unless a line is longer than a chunk.
    std::size_t end = std::min(s.raw.size(), s.plain_pos + kPlainChunkBytes);
    if (end < s.raw.size()) {
      const auto window = s.raw.substr(s.plain_pos, end - s.plain_pos);
      const auto newline = window.rfind('\n');
      if (newline != std::string_view::npos) {
        end = s.plain_pos + newline + 1;
      } else {
        const auto next = s.raw.find('\n', end);
        end = next == std::string_view::npos ? s.raw.size() : next + 1;
      }
    }
    chunk = s.raw.substr(s.plain_pos, end - s.plain_pos);
    s.plain_pos = end;
    return true;
  }
  // The bytes after the last chunk (a line not yet ended) move to the front.
  std::memmove(s.buffer.data(), s.buffer.data() + s.delivered, s.filled - s.delivered);
  s.filled -= s.delivered;
  s.delivered = 0;
  for (;;) {
    if (s.filled == s.buffer.size())
      s.buffer.resize(2 * s.buffer.size());  // a line longer than the buffer
    const std::size_t before = s.filled;
    const std::size_t added = s.decode(facts_);
    s.filled += added;
    if (added == 0) {  // the end of the text
      if (s.filled == 0) return false;
      chunk = std::string_view(s.buffer.data(), s.filled);
      s.delivered = s.filled;
      return true;
    }
    const std::string_view fresh(s.buffer.data() + before, added);
    const auto last_newline = fresh.rfind('\n');
    if (last_newline != std::string_view::npos) {
      s.delivered = before + last_newline + 1;
      chunk = std::string_view(s.buffer.data(), s.delivered);
      return true;
    }
  }
}

ReadProgress::ReadProgress(Progress progress, const std::vector<std::string>& files)
    : progress_(std::move(progress)) {
  for (const auto& file : files) {
    std::error_code error;
    const auto size = std::filesystem::file_size(file, error);
    if (!error) total_ += size;
  }
}

void ReadProgress::add(std::uint64_t raw_bytes) {
  if (!progress_) return;
  done_ += raw_bytes;
  const std::lock_guard lock(report_);
  // The sum read under the lock: a report never goes back, and the last one has every byte (a
  // sum taken before the lock could be overtaken by another thread's larger one).
  const std::uint64_t done = done_.load();
  progress_("read", std::min(done, total_), total_);
}

TextInput read_text_input(const std::filesystem::path& path, std::uint64_t max_bytes) {
  InputFile file(path);
  TextInput input;
  static_cast<InputFacts&>(input) = file.facts();
  std::string_view chunk;
  while (file.next_chunk(chunk)) {
    if (chunk.size() > max_bytes - input.text.size())
      throw Error(input.display_name + ": more than " + std::to_string(max_bytes) +
                  " bytes of text (the output limit)");
    input.text.append(chunk);
  }
  return input;
}

void record_input(Metadata& metadata, std::size_t index, const InputFacts& input) {
  const std::string key = "source.input." + std::to_string(index);
  // A file name is bytes; metadata values are UTF-8 (§7): a name that is not is kept escaped.
  metadata.set(key + ".name", escape_for_terminal(input.base_name));
  metadata.set(key + ".size", std::to_string(input.raw_size));
  metadata.set(key + ".xxh3", input.raw_xxh3);
}

std::string benchmark_name_from(std::string base,
                                std::initializer_list<std::string_view> extensions) {
  // Each suffix in turn, so "bw.fmi.txt" with {".txt", ".fmi"} gives "bw".
  auto strip = [&](std::string_view ext) {
    if (base.size() > ext.size() && std::string_view(base).ends_with(ext))
      base.resize(base.size() - ext.size());
  };
  for (std::string_view compression : {".gz", ".bz2", ".xz", ".zst", ".zstd"}) strip(compression);
  for (auto ext : extensions) strip(ext);
  return escape_for_terminal(base);  // metadata is UTF-8 (§7); a file name need not be
}

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return UINT64_MAX;  // unknown: no bound
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

void check_declared_vertices(const std::string& file, std::uint64_t line, std::uint64_t column,
                             std::uint64_t vertex_count) {
  const std::uint64_t limit = physical_memory_bytes();
  if (vertex_count <= limit / kBuildBytesPerVertex) return;
  auto gib = [](double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", bytes / double(std::uint64_t{1} << 30));
    return std::string(text);
  };
  text::fail(file, line, column,
             "the header declares " + text::plural(vertex_count, "vertex") + ": " +
                 gib(double(vertex_count) * double(kBuildBytesPerVertex)) + " GiB, more than the " +
                 gib(double(limit)) + " GiB of physical memory");
}

void fail_out_of_memory(const std::string& file) {
  throw Error(file + ": out of memory converting this input");
}

}  // namespace mosb::converters
