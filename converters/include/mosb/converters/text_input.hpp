// A raw input file read whole into memory, decompressed when its magic bytes say gzip, bzip2, xz or
// zstd (the file name is not consulted), with what the metadata records about the raw bytes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include "mosb/metadata.hpp"

namespace mosb::converters {

enum class Compression { none, gzip, bzip2, xz, zstd };

// By magic bytes only.
Compression detect_compression(std::string_view raw);
const char* compression_name(Compression c);

// Decompresses `raw` in memory; throws mosb::Error naming `display_name` on a corrupt stream.
std::string decompress(std::string_view raw, Compression c, const std::string& display_name);

struct TextInput {
  std::string display_name;  // the path as given, for messages only
  std::string base_name;     // file name without directories, for metadata
  std::uint64_t raw_size = 0;
  std::string raw_xxh3;      // XXH3-64 of the raw (possibly compressed) bytes, 16 lowercase hex
  Compression compression = Compression::none;
  std::string text;          // decompressed content
};

// Throws mosb::Error naming the file when it cannot be read or decompressed.
TextInput read_text_input(const std::filesystem::path& path);

// Provenance of raw input `index`: metadata source.input.<index>.name, .size and .xxh3 (spec §7).
void record_input(Metadata& metadata, std::size_t index, const TextInput& input);

// A default benchmark name: `base` stripped of each compression suffix (.gz .bz2 .xz .zst .zstd),
// then of each of `extensions`, in that order ("NY.gr.gz" with {".gr"} -> "NY").
std::string benchmark_name_from(std::string base, std::initializer_list<std::string_view> extensions);

}  // namespace mosb::converters
