// Regenerates spec/golden/1.1/solutions/: the valid solution file (golden_solutions.hpp, bound to
// spec/golden/1.0/valid/small.mosb) and the invalid files of solution_faults.hpp, listed with the
// expected failure in invalid/EXPECTED.tsv.
// Usage: mosb_make_golden_solutions SPEC_GOLDEN_DIR (e.g. spec/golden)
#include <fstream>
#include <iostream>

#include "golden_solutions.hpp"
#include "solution_faults.hpp"

using namespace mosb;
using namespace mosb::testing;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: mosb_make_golden_solutions DIR (e.g. spec/golden)\n";
    return 2;
  }
  const std::filesystem::path golden = argv[1];
  const auto root = golden / "1.1" / "solutions";
  std::filesystem::create_directories(root / "valid");
  std::filesystem::create_directories(root / "invalid");
  const auto instance = GraphReader::open(golden / "1.0" / "valid" / "small.mosb");
  write_golden_solutions(instance, root / "valid" / "small.sol.mosb");
  const Bytes valid = read_bytes(root / "valid" / "small.sol.mosb");
  std::ofstream expected(root / "invalid" / "EXPECTED.tsv");
  expected << "# file\tstage at which it fails (open, payload)\texpected message fragment\n";
  for (const auto& fault : kSolutionFaults) {
    Bytes b = valid;
    fault.apply(b);
    write_bytes(root / "invalid" / fault.file, b);
    expected << fault.file << '\t' << fault.stage << '\t' << fault.expected << '\n';
  }
  std::cout << "wrote " << root.string() << "\n";
  return 0;
}
