// Regenerates spec/golden/1.1/packed/: valid/small.packed.mosb (spec/golden/1.0/valid/small.mosb
// packed: plain zstd sections only), valid/grid.packed.mosb (a 12 x 10 Grid, costs 1..1000: its
// columns take the shuffle and delta encodings) and the invalid files of packed_faults.hpp, listed
// in invalid/EXPECTED.tsv. Usage: mosb_make_golden_packed SPEC_GOLDEN_DIR (e.g. spec/golden)
#include <iostream>

#include "mosb/converters/grid_generator.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/pack.hpp"
#include "packed_faults.hpp"

using namespace mosb;
using namespace mosb::testing;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: mosb_make_golden_packed DIR (e.g. spec/golden)\n";
    return 2;
  }
  const std::filesystem::path golden = argv[1];
  const auto root = golden / "1.1" / "packed";
  std::filesystem::create_directories(root / "valid");
  std::filesystem::create_directories(root / "invalid");
  pack_file(golden / "1.0" / "valid" / "small.mosb", root / "valid" / "small.packed.mosb", {});
  const auto plain = std::filesystem::temp_directory_path() / "mosb-golden-grid.mosb";
  write_graph(converters::generate_grid({12, 10, 3, 7, 1, 1000}), plain);
  pack_file(plain, root / "valid" / "grid.packed.mosb", {});
  std::filesystem::remove(plain);
  const Bytes valid = read_bytes(root / "valid" / "grid.packed.mosb");
  std::ofstream expected(root / "invalid" / "EXPECTED.tsv");
  expected << "# file\texpected message fragment (GraphReader::load, mosb unpack)\n";
  for (const auto& fault : kPackedFaults) {
    Bytes b = valid;
    fault.apply(b);
    write_bytes(root / "invalid" / fault.file, b);
    expected << fault.file << '\t' << fault.expected << '\n';
  }
  std::cout << "wrote " << root.string() << "\n";
  return 0;
}
