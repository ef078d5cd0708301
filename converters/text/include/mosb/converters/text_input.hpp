// Raw input files of the text converters. An InputFile maps a plain file (zero-copy: the parser
// reads the page cache) and streams a compressed one (gzip, bzip2, xz or zstd, told by its magic
// bytes, not by its name) through a bounded buffer, in chunks that end at line ends; either way
// it records what the metadata says about the raw bytes. read_text_input() keeps the older
// whole-text API (the text in one std::string) for parsers that need it.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/converters/text_scan.hpp"
#include "mosb/metadata.hpp"
#include "mosb/progress.hpp"

namespace mosb::converters {

enum class Compression { none, gzip, bzip2, xz, zstd };

// By magic bytes only.
Compression detect_compression(std::string_view raw);
const char* compression_name(Compression c);

// What is known of an input file before its text is read.
struct InputFacts {
  std::string display_name;  // the path as given, for messages only
  std::string base_name;     // file name without directories, for metadata
  std::uint64_t raw_size = 0;
  std::string raw_xxh3;  // XXH3-64 of the raw (possibly compressed) bytes, 16 lowercase hex
  Compression compression = Compression::none;
};

// Progress of reading a converter's inputs (stage "read"), in raw bytes over all of them: the
// files parsed on several threads add to one count, and the reports go out one at a time.
class ReadProgress {
 public:
  ReadProgress() = default;
  // `files`: the inputs, for their sizes (a file that cannot be sized counts 0).
  ReadProgress(Progress progress, const std::vector<std::string>& files);
  void add(std::uint64_t raw_bytes);  // thread-safe

 private:
  Progress progress_;
  std::uint64_t total_ = 0;
  std::atomic<std::uint64_t> done_{0};
  std::mutex report_;
};

// The text of an input file in chunks (text::TextSource). Memory: a plain regular file is mapped,
// not copied; compressed input is decoded through a buffer of 1 MiB that grows only to hold the
// longest line; input that is not a regular file (a pipe) is read whole first. Errors are
// mosb::Error naming the file; a compressed stream that ends early or does not decode says the
// file is truncated or corrupt.
class InputFile final : public text::TextSource {
 public:
  explicit InputFile(const std::filesystem::path& path);
  ~InputFile() override;
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const InputFacts& facts() const { return facts_; }
  const std::string& display_name() const { return facts_.display_name; }
  // An estimate of the text's size in bytes, for reservations only: exact for plain input,
  // 16 times the raw size for compressed input (its decoded size is known only at the end).
  std::uint64_t size_hint() const;

  bool next_chunk(std::string_view& chunk) override;
  // Starts the text again from its first byte (an error path that scans a file twice).
  void rewind();
  // Counts the raw bytes each chunk consumes into `progress` (which must outlive the reading).
  void count_into(ReadProgress* progress) { progress_ = progress; }

 private:
  bool next_chunk_of_text(std::string_view& chunk);

  struct Stream;
  InputFacts facts_;
  std::unique_ptr<Stream> stream_;
  ReadProgress* progress_ = nullptr;
  std::uint64_t counted_ = 0;  // raw bytes already added to progress_
};

// A whole input in memory.
struct TextInput : InputFacts {
  std::string text;  // decompressed content
};

// Throws mosb::Error naming the file when it cannot be read or decompressed.
// With `max_bytes`, a text (decompressed) longer than that is refused once it passes it, before
// more is decoded: a small compressed file can decode to gigabytes.
TextInput read_text_input(const std::filesystem::path& path, std::uint64_t max_bytes = UINT64_MAX);

// Provenance of raw input `index`: metadata source.input.<index>.name, .size and .xxh3 (spec §7).
void record_input(Metadata& metadata, std::size_t index, const InputFacts& input);

// A default benchmark name: `base` stripped of each compression suffix (.gz .bz2 .xz .zst .zstd),
// then of each of `extensions`, in that order ("NY.gr.gz" with {".gr"} -> "NY"); bytes that are
// not UTF-8 escaped as \\xHH (escape_for_terminal), since metadata is UTF-8.
std::string benchmark_name_from(std::string base,
                                std::initializer_list<std::string_view> extensions);

// The bound declared sizes are checked against: this machine's physical memory (sysconf).
std::uint64_t physical_memory_bytes();

// Bytes per vertex that building an instance needs at its peak: forward and reverse offsets of
// 8 bytes each and a fill cursor of 8 (lib/core/src/graph_builder.cpp).
inline constexpr std::uint64_t kBuildBytesPerVertex = 24;

// A declared vertex count is untrusted: fails "FILE:LINE:COLUMN: the header declares N vertices:
// X GiB, more than the Y GiB of physical memory" when kBuildBytesPerVertex * n exceeds
// physical_memory_bytes().
void check_declared_vertices(const std::string& file, std::uint64_t line, std::uint64_t column,
                             std::uint64_t vertex_count);

// Runs `work`, turning std::bad_alloc into one line naming the input: "FILE: out of memory
// converting this input".
[[noreturn]] void fail_out_of_memory(const std::string& file);
template <class Work>
decltype(auto) naming_input_on_out_of_memory(const std::string& file, Work&& work) {
  try {
    return work();
  } catch (const std::bad_alloc&) {
    fail_out_of_memory(file);
  }
}

}  // namespace mosb::converters
