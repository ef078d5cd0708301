// Byte-level surgery on mosb files for tests: read, patch fields, recompute checksums.
#pragma once

#include <xxhash.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "mosb/format.hpp"

namespace mosb::testing {

using Bytes = std::vector<std::byte>;

inline Bytes read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Bytes bytes(chars.size());
  std::memcpy(bytes.data(), chars.data(), chars.size());
  return bytes;
}

inline void write_bytes(const std::filesystem::path& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

inline format::FileHeader header_of(const Bytes& b) {
  format::FileHeader h;
  std::memcpy(&h, b.data(), sizeof h);
  return h;
}

inline void set_header(Bytes& b, const format::FileHeader& h) {
  std::memcpy(b.data(), &h, sizeof h);
}

inline std::size_t entry_offset(const Bytes& b, std::size_t i) {
  return header_of(b).table_offset + i * sizeof(format::SectionEntry);
}

inline format::SectionEntry entry_of(const Bytes& b, std::size_t i) {
  format::SectionEntry e;
  std::memcpy(&e, b.data() + entry_offset(b, i), sizeof e);
  return e;
}

inline void set_entry(Bytes& b, std::size_t i, const format::SectionEntry& e) {
  std::memcpy(b.data() + entry_offset(b, i), &e, sizeof e);
}

inline std::size_t find_entry(const Bytes& b, std::string_view name) {
  for (std::size_t i = 0; i < header_of(b).section_count; ++i)
    if (format::name_of(entry_of(b, i)) == name) return i;
  throw std::runtime_error("no section " + std::string(name));
}

// Recomputes the header checksum over header and table, as a writer would.
inline void reseal_header(Bytes& b) {
  auto h = header_of(b);
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  XXH3_64bits_update(state, b.data(), format::kHeaderChecksumOffset);
  XXH3_64bits_update(state, b.data() + h.table_offset,
                     h.section_count * sizeof(format::SectionEntry));
  h.header_checksum = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  set_header(b, h);
}

// Recomputes section i's checksum, then the header's: the file passes the checksum level again.
inline void reseal_section(Bytes& b, std::size_t i) {
  auto e = entry_of(b, i);
  e.checksum = XXH3_64bits(b.data() + e.offset, e.stored_length);
  set_entry(b, i, e);
  reseal_header(b);
}

template <class T>
void poke(Bytes& b, std::size_t section, std::size_t index, T value) {
  const auto e = entry_of(b, section);
  std::memcpy(b.data() + e.offset + index * sizeof(T), &value, sizeof value);
}

}  // namespace mosb::testing
