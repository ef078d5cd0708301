// Regenerates spec/golden/1.1/packed/: valid/small.packed.mosb (spec/golden/1.0/valid/small.mosb
// packed with --keep-reverse), valid/grid.packed.mosb (a 12 x 10 Grid,
// costs 1..1000, --keep-reverse: its columns take the shuffle and delta encodings); and
// spec/golden/1.2/packed/valid/grid.packed.mosb (the same Grid packed by default: its reverse CSR
// derived, encoding 4). Each directory's invalid/ holds the files of packed_faults.hpp, listed in
// invalid/EXPECTED.tsv. Usage: mosb_make_golden_packed SPEC_GOLDEN_DIR (e.g. spec/golden)
#include <iostream>

#include "mosb/converters/grid_generator.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/pack.hpp"
#include "packed_faults.hpp"

using namespace mosb;
using namespace mosb::testing;

namespace {

// invalid/F for each fault F applied to valid/grid.packed.mosb, and invalid/EXPECTED.tsv.
template <std::size_t N>
void write_invalid(const std::filesystem::path& dir, const PackedFault (&faults)[N]) {
  const Bytes valid = read_bytes(dir / "valid" / "grid.packed.mosb");
  std::ofstream expected(dir / "invalid" / "EXPECTED.tsv");
  expected << "# file\texpected message fragment (GraphReader::load, mosb unpack)\n";
  for (const auto& fault : faults) {
    Bytes b = valid;
    fault.apply(b);
    write_bytes(dir / "invalid" / fault.file, b);
    expected << fault.file << '\t' << fault.expected << '\n';
  }
  std::cout << "wrote " << dir.string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: mosb_make_golden_packed DIR (e.g. spec/golden)\n";
    return 2;
  }
  const std::filesystem::path golden = argv[1];
  const auto plain = std::filesystem::temp_directory_path() / "mosb-golden-grid.mosb";
  write_graph(converters::generate_grid({12, 10, 3, 7, 1, 1000}), plain);
  // 1.1: every section compressed (--keep-reverse); 1.2: the reverse CSR derived.
  PackOptions keep_reverse;
  keep_reverse.derive_reverse = false;
  const auto v11 = golden / "1.1" / "packed";
  const auto v12 = golden / "1.2" / "packed";
  for (const auto& dir : {v11, v12}) {
    std::filesystem::create_directories(dir / "valid");
    std::filesystem::create_directories(dir / "invalid");
  }
  pack_file(golden / "1.0" / "valid" / "small.mosb", v11 / "valid" / "small.packed.mosb",
            keep_reverse);
  pack_file(plain, v11 / "valid" / "grid.packed.mosb", keep_reverse);
  pack_file(plain, v12 / "valid" / "grid.packed.mosb", {});
  std::filesystem::remove(plain);
  write_invalid(v11, kPackedFaults);
  write_invalid(v12, kTransposeFaults);
  return 0;
}
