// Regenerates spec/golden/<version>/: the valid file from golden_input() and invalid files made
// from it by one deliberate fault each, listed with the expected failure in invalid/EXPECTED.tsv.
// Usage: mosb_make_golden spec/golden/1.0
#include <algorithm>
#include <fstream>
#include <iostream>

#include "file_patch.hpp"
#include "golden_input.hpp"

using namespace mosb;
using namespace mosb::testing;

namespace {

struct Fault {
  const char* file;
  const char* level;  // the verify level at which it must fail ("open" = at open)
  const char* expected;
  void (*apply)(Bytes&);
};

void set_field(Bytes& b, void (*edit)(format::FileHeader&)) {
  auto h = header_of(b);
  edit(h);
  set_header(b, h);
}

const Fault kFaults[] = {
    {"truncated.mosb", "open", "truncated: header says", [](Bytes& b) { b.resize(b.size() - 64); }},
    {"bad-magic.mosb", "open", "not a mosb file (wrong magic)",
     [](Bytes& b) { b[0] = std::byte{'P'}; }},
    {"byte-swapped.mosb", "open", "byte-swapped mosb file",
     [](Bytes& b) { std::reverse(b.begin(), b.begin() + 8); }},
    {"text-mode.mosb", "open", "damaged by a text-mode transfer",
     [](Bytes& b) { b.erase(b.begin() + 4); }},
    {"newer-major.mosb", "open", "prepared with format 2.0, this reader reads format 1.x",
     [](Bytes& b) {
       set_field(b, [](auto& h) {
         h.version_major = 2;
         h.version_minor = 0;
       });
     }},
    {"unknown-feature.mosb", "open", "requires feature bit 7, unknown to this reader",
     [](Bytes& b) {
       set_field(b, [](auto& h) { h.required_features |= 1ULL << 7; });
       reseal_header(b);
     }},
    {"header-checksum.mosb", "open", "header checksum mismatch",
     [](Bytes& b) { b[90] = std::byte{1}; }},
    {"overlap.mosb", "open", "overlap",
     [](Bytes& b) {
       auto e = entry_of(b, 3);
       e.offset = entry_of(b, 2).offset;
       set_entry(b, 3, e);
       reseal_header(b);
     }},
    {"misaligned.mosb", "open", "is not 64-byte aligned",
     [](Bytes& b) {
       auto e = entry_of(b, 2);
       e.offset += 4;
       set_entry(b, 2, e);
       reseal_header(b);
     }},
    {"count-mismatch.mosb", "open", "rows, but the vertex count + 1 is",
     [](Bytes& b) {
       set_field(b, [](auto& h) { h.vertex_count += 1; });
       reseal_header(b);
     }},
    {"table-past-end.mosb", "open", "does not end at the end of the file",
     [](Bytes& b) { set_field(b, [](auto& h) { h.table_offset += 64; }); }},
    {"section-checksum.mosb", "checksums", "section 'time': [checksum] mismatch",
     [](Bytes& b) { b[entry_of(b, find_entry(b, "time")).offset] ^= std::byte{1}; }},
    {"target-range.mosb", "structure", "section 'forward_targets': [target-range]",
     [](Bytes& b) {
       auto s = find_entry(b, "forward_targets");
       poke<std::uint32_t>(b, s, 0, 9);
       reseal_section(b, s);
     }},
    {"not-transpose.mosb", "structure", "section 'reverse_arcs': [reverse-transpose]",
     [](Bytes& b) {
       auto s = find_entry(b, "reverse_arcs");
       poke<std::uint32_t>(b, s, 0, 1);
       reseal_section(b, s);
     }},
    // A non-zero byte in the alignment gap after the metadata payload: every checksum still holds.
    {"padding.mosb", "structure", "[padding] byte",
     [](Bytes& b) {
       const auto e = entry_of(b, find_entry(b, "metadata"));
       b[e.offset + e.stored_length] = std::byte{0x2A};
     }},
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: mosb_make_golden DIR (e.g. spec/golden/1.0)\n";
    return 2;
  }
  const std::filesystem::path root = argv[1];
  std::filesystem::create_directories(root / "valid");
  std::filesystem::create_directories(root / "invalid");
  write_graph(golden_input(), root / "valid" / "small.mosb");
  const Bytes valid = read_bytes(root / "valid" / "small.mosb");
  std::ofstream expected(root / "invalid" / "EXPECTED.tsv");
  expected << "# file\tlevel at which it fails\texpected message fragment\n";
  for (const auto& fault : kFaults) {
    Bytes b = valid;
    fault.apply(b);
    write_bytes(root / "invalid" / fault.file, b);
    expected << fault.file << '\t' << fault.level << '\t' << fault.expected << '\n';
  }
  std::cout << "wrote " << root.string() << "\n";
  return 0;
}
