#include "mosb/hex.hpp"
#include "mosb/converters/text_input.hpp"

#include <xxhash.h>

#include <boost/iostreams/copy.hpp>
#include <boost/iostreams/device/array.hpp>
#include <boost/iostreams/device/back_inserter.hpp>
#include <boost/iostreams/filter/bzip2.hpp>
#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filter/lzma.hpp>
#include <boost/iostreams/filter/zstd.hpp>
#include <boost/iostreams/filtering_streambuf.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "mosb/error.hpp"

namespace mosb::converters {

namespace {

bool starts_with_bytes(std::string_view raw, std::initializer_list<unsigned char> magic) {
  if (raw.size() < magic.size()) return false;
  std::size_t i = 0;
  for (auto b : magic)
    if (static_cast<unsigned char>(raw[i++]) != b) return false;
  return true;
}


struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

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
    case Compression::none: return "none";
    case Compression::gzip: return "gzip";
    case Compression::bzip2: return "bzip2";
    case Compression::xz: return "xz";
    case Compression::zstd: return "zstd";
  }
  return "unknown";
}

std::string decompress(std::string_view raw, Compression c, const std::string& display_name) {
  if (c == Compression::none) return std::string(raw);
  namespace io = boost::iostreams;
  std::string out;
  try {
    io::filtering_istreambuf in;
    switch (c) {
      case Compression::gzip: in.push(io::gzip_decompressor()); break;
      case Compression::bzip2: in.push(io::bzip2_decompressor()); break;
      case Compression::xz: in.push(io::lzma_decompressor()); break;
      case Compression::zstd: in.push(io::zstd_decompressor()); break;
      case Compression::none: break;
    }
    in.push(io::array_source(raw.data(), raw.size()));
    io::copy(in, io::back_inserter(out));
  } catch (const std::exception& e) {
    throw Error(display_name + ": cannot decompress " + compression_name(c) + " data: " + e.what());
  }
  return out;
}

TextInput read_text_input(const std::filesystem::path& path) {
  TextInput input;
  input.display_name = path.string();
  input.base_name = path.filename().string();
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(input.display_name.c_str(), "rb"));
  if (!file) throw Error(input.display_name + ": cannot open: " + std::strerror(errno));
  std::string raw;
  char buffer[1 << 16];
  for (;;) {
    const std::size_t got = std::fread(buffer, 1, sizeof buffer, file.get());
    raw.append(buffer, got);
    if (got < sizeof buffer) {
      if (std::ferror(file.get())) throw Error(input.display_name + ": read error");
      break;
    }
  }
  input.raw_size = raw.size();
  input.raw_xxh3 = hex64(XXH3_64bits(raw.data(), raw.size()));
  input.compression = detect_compression(raw);
  if (input.compression == Compression::none)
    input.text = std::move(raw);
  else
    input.text = decompress(raw, input.compression, input.display_name);
  return input;
}

void record_input(Metadata& metadata, std::size_t index, const TextInput& input) {
  const std::string key = "source.input." + std::to_string(index);
  metadata.set(key + ".name", input.base_name);
  metadata.set(key + ".size", std::to_string(input.raw_size));
  metadata.set(key + ".xxh3", input.raw_xxh3);
}

std::string benchmark_name_from(std::string base, std::initializer_list<std::string_view> extensions) {
  // Each suffix in turn, so "bw.fmi.txt" with {".txt", ".fmi"} gives "bw".
  auto strip = [&](std::string_view ext) {
    if (base.size() > ext.size() && std::string_view(base).ends_with(ext)) base.resize(base.size() - ext.size());
  };
  for (std::string_view compression : {".gz", ".bz2", ".xz", ".zst", ".zstd"}) strip(compression);
  for (auto ext : extensions) strip(ext);
  return base;
}

}  // namespace mosb::converters
