// Regenerates one set of golden files under spec/golden/ (the DIR argument), each a valid file and
// invalid files made from it by one deliberate fault each, listed with the expected failure in the
// set's invalid/EXPECTED.tsv:
//   instance    1.0/: valid/small.mosb from golden_input() (a deliberate format change only)
//   packed      1.1/packed/: valid/small.packed.mosb (1.0/valid/small.mosb packed with
//               --keep-reverse), valid/grid.packed.mosb (a 12 x 10 Grid, costs 1..1000,
//               --keep-reverse: its columns take the shuffle and delta encodings); and
//               1.2/packed/valid/grid.packed.mosb (the same Grid packed by default: its reverse CSR
//               derived, encoding 4); the faults of packed_faults.hpp
//   references  1.1/references/: valid/references.mosb from golden_references_input(), faults in
//               its query reference
//   solutions   1.3/solutions/: valid/small.sol.mosb (golden_solutions.hpp, bound to
//               1.0/valid/small.mosb), the faults of solution_faults.hpp; 1.4/solutions/:
//               valid/objectives.sol.mosb (bound to an objective list alone); 1.5/solutions/:
//               valid/reported-runtime.sol.mosb (the solver's own runtime beside mosb's);
//               1.6/solutions/: valid/fronts.packed.sol.mosb (a packed solution file) and the
//               faults of packed_faults.hpp
// packed and solutions read 1.0/valid/small.mosb from DIR.
// Usage: mosb_make_golden instance|packed|references|solutions DIR (e.g. spec/golden)
#include <algorithm>
#include <fstream>
#include <functional>
#include <iostream>
#include <span>
#include <string>
#include <string_view>

#include "file_patch.hpp"
#include "golden_input.hpp"
#include "golden_references.hpp"
#include "golden_solutions.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/file_writer.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/pack.hpp"
#include "packed_faults.hpp"
#include "solution_faults.hpp"

using namespace mosb;
using namespace mosb::testing;
using format::ElementType;
using format::SectionKind;

namespace fs = std::filesystem;

namespace {

// DIR/invalid/: one file per fault, written by write(fault, path), and EXPECTED.tsv, which opens
// with `heading` and gives each file a line of the file name and columns(fault).
template <class Faults, class Write, class Columns>
void write_invalid(const fs::path& dir, std::string_view heading, const Faults& faults, Write write,
                   Columns columns) {
  fs::create_directories(dir / "invalid");
  std::ofstream expected(dir / "invalid" / "EXPECTED.tsv");
  expected << heading << '\n';
  for (const auto& fault : faults) {
    write(fault, dir / "invalid" / fault.file);
    expected << fault.file << '\t' << columns(fault) << '\n';
  }
  std::cout << "wrote " << dir.string() << "\n";
}

// The same for faults that patch the bytes of DIR/valid/VALID (fault.apply).
template <class Faults, class Columns>
void write_patched(const fs::path& dir, std::string_view valid, std::string_view heading,
                   const Faults& faults, Columns columns) {
  const Bytes bytes = read_bytes(dir / "valid" / valid);
  write_invalid(
      dir, heading, faults,
      [&](const auto& fault, const fs::path& path) {
        Bytes b = bytes;
        fault.apply(b);
        write_bytes(path, b);
      },
      columns);
}

// The level (or stage) at which a fault must fail, then the expected message fragment.
template <class Fault>
std::string level_and_message(const Fault& fault) {
  return std::string(fault.level) + '\t' + fault.expected;
}

// ---- instance: 1.0/ ----

struct InstanceFault {
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

const InstanceFault kInstanceFaults[] = {
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

void make_instance(const fs::path& golden) {
  const auto root = golden / "1.0";
  fs::create_directories(root / "valid");
  write_graph(golden_input(), root / "valid" / "small.mosb");
  write_patched(root, "small.mosb", "# file\tlevel at which it fails\texpected message fragment",
                kInstanceFaults, level_and_message<InstanceFault>);
}

// ---- packed: 1.1/packed/ and 1.2/packed/ ----

// The columns of a packed fault: only the expected message fragment.
const char* packed_message(const PackedFault& fault) {
  return fault.expected;
}

void make_packed(const fs::path& golden) {
  const auto plain = fs::temp_directory_path() / "mosb-golden-grid.mosb";
  write_graph(converters::generate_grid({12, 10, 3, 7, 1, 1000}), plain);
  // 1.1: every section compressed (--keep-reverse); 1.2: the reverse CSR derived.
  PackOptions keep_reverse;
  keep_reverse.derive_reverse = false;
  const auto v11 = golden / "1.1" / "packed";
  const auto v12 = golden / "1.2" / "packed";
  for (const auto& dir : {v11, v12}) fs::create_directories(dir / "valid");
  pack_file(golden / "1.0" / "valid" / "small.mosb", v11 / "valid" / "small.packed.mosb",
            keep_reverse);
  pack_file(plain, v11 / "valid" / "grid.packed.mosb", keep_reverse);
  pack_file(plain, v12 / "valid" / "grid.packed.mosb", {});
  fs::remove(plain);
  constexpr std::string_view heading =
      "# file\texpected message fragment (mosb::load, mosb unpack)";
  write_patched(v11, "grid.packed.mosb", heading, kPackedFaults, packed_message);
  write_patched(v12, "grid.packed.mosb", heading, kTransposeFaults, packed_message);
}

// ---- references: 1.1/references/ ----

// How a fault rewrites the reference section: its name, type, width and payload.
struct Reference {
  std::string name;
  ElementType type;
  std::uint32_t width;
  std::vector<std::byte> bytes;
};

struct ReferenceFault {
  const char* file;
  const char* level;  // "open" or a verify level
  const char* expected;
  std::function<void(Reference&)> reference;
  std::function<void(Metadata&)> metadata;
};

template <class T>
std::vector<std::byte> bytes_of(std::vector<T> values) {
  auto raw = std::as_bytes(std::span(values));
  return {raw.begin(), raw.end()};
}

// The valid file's sections copied in order through FileWriter (so every checksum matches what is
// written), with the fault applied to the reference section and the metadata.
void write_faulty(const GraphReader& valid, const ReferenceFault& fault,
                  const std::filesystem::path& out) {
  FileWriter writer(out);
  for (const auto& s : valid.sections()) {
    if (s.kind == SectionKind::metadata) {
      Metadata m = valid.metadata();
      if (fault.metadata) fault.metadata(m);
      const std::string text = m.serialize();
      writer.add_section(
          SectionKind::metadata, s.name, 1,
          std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    } else if (s.kind == SectionKind::query_reference) {
      Reference r{s.name, s.type, s.entry.row_width, {s.stored.begin(), s.stored.end()}};
      if (fault.reference) fault.reference(r);
      writer.begin_section(SectionKind::query_reference, r.name, r.type, r.width);
      writer.append(std::span(r.bytes));
      writer.end_section();
    } else {
      writer.begin_section(*s.kind, s.name, s.type, s.entry.row_width);
      writer.append(s.stored);
      writer.end_section();
    }
  }
  writer.commit(valid.vertex_count(), valid.arc_count());
}

const ReferenceFault kReferenceFaults[] = {
    {"reference-rows.mosb",
     "open",
     "section 'default': the query reference has 2 rows, but the query set has 3",
     [](Reference& r) {
       r.bytes = bytes_of(std::vector<double>{1, 2});
     },
     {}},
    {"reference-type.mosb",
     "open",
     "section 'default': query references must be f64 x 1",
     [](Reference& r) {
       r.type = ElementType::f32;
       r.bytes = bytes_of(std::vector<float>{1, 2, 3});
     },
     {}},
    {"reference-width.mosb",
     "open",
     "section 'default': query references must be f64 x 1",
     [](Reference& r) {
       r.width = 3;
       r.bytes = bytes_of(std::vector<double>{1, 2, 3});
     },
     {}},
    {"reference-orphan.mosb", "open", "section 'nosuch': a query reference naming no query set",
     [](Reference& r) { r.name = "nosuch"; },
     [](Metadata& m) {
       m.set("queries.nosuch.reference.objective", "distance");
       m.set("queries.nosuch.reference.source", "golden");
     }},
    {"reference-objective.mosb",
     "structure",
     "[metadata-reference] queries.default.reference.objective names objective 'nosuch'",
     {},
     [](Metadata& m) { m.set("queries.default.reference.objective", "nosuch"); }},
    {"reference-negative.mosb",
     "structure",
     "section 'default': [reference-nonnegative] query 1 has -1",
     [](Reference& r) {
       r.bytes = bytes_of(std::vector<double>{2.5, -1, 1e-3});
     },
     {}},
};

void make_references(const fs::path& golden) {
  const auto root = golden / "1.1" / "references";
  fs::create_directories(root / "valid");
  write_graph(golden_references_input(), root / "valid" / "references.mosb");
  const auto valid = GraphReader::open(root / "valid" / "references.mosb", VerifyLevel::full);
  write_invalid(
      root, "# file\tlevel at which it fails\texpected message fragment", kReferenceFaults,
      [&](const ReferenceFault& fault, const fs::path& path) { write_faulty(valid, fault, path); },
      level_and_message<ReferenceFault>);
}

// ---- solutions: 1.3/solutions/ (1.1/solutions/ keeps the files written before path sums) ----

// The columns of a solution fault: the stage at which it must fail, then the message fragment.
std::string stage_and_message(const SolutionFault& fault) {
  return std::string(fault.stage) + '\t' + fault.expected;
}

void make_solutions(const fs::path& golden) {
  const auto root = golden / "1.3" / "solutions";
  fs::create_directories(root / "valid");
  const auto instance = GraphReader::open(golden / "1.0" / "valid" / "small.mosb");
  write_golden_solutions(instance, root / "valid" / "small.sol.mosb");
  write_patched(root, "small.sol.mosb",
                "# file\tstage at which it fails (open, payload)\texpected message fragment",
                kSolutionFaults, stage_and_message);
  // 1.4: bound to an objective list no view names (no solution.view).
  fs::create_directories(golden / "1.4" / "solutions" / "valid");
  write_golden_objective_solutions(instance,
                                   golden / "1.4" / "solutions" / "valid" / "objectives.sol.mosb");
  // 1.5: the solver's own runtime beside mosb's (statistic reported_runtime_seconds).
  fs::create_directories(golden / "1.5" / "solutions" / "valid");
  write_golden_reported_runtime_solutions(
      instance, golden / "1.5" / "solutions" / "valid" / "reported-runtime.sol.mosb");
  // 1.6: a packed solution file, and the ways a packed one can be damaged or hostile.
  const auto v16 = golden / "1.6" / "solutions";
  fs::create_directories(v16 / "valid");
  const auto plain = fs::temp_directory_path() / "mosb-golden-fronts.sol.mosb";
  write_golden_packable_solutions(instance, plain);
  pack_file(plain, v16 / "valid" / "fronts.packed.sol.mosb", {});
  fs::remove(plain);
  write_patched(v16, "fronts.packed.sol.mosb",
                "# file\texpected message fragment (SolutionReader::open, mosb unpack)",
                kPackedSolutionFaults, packed_message);
}

struct GoldenSet {
  std::string_view name;
  void (*make)(const fs::path& golden);
};
constexpr GoldenSet kSets[] = {{"instance", make_instance},
                               {"packed", make_packed},
                               {"references", make_references},
                               {"solutions", make_solutions}};

}  // namespace

int main(int argc, char** argv) {
  const auto set = argc == 3 ? std::find_if(std::begin(kSets), std::end(kSets),
                                            [&](const GoldenSet& s) { return s.name == argv[1]; })
                             : std::end(kSets);
  if (set == std::end(kSets)) {
    std::cerr << "usage: mosb_make_golden instance|packed|references|solutions DIR (e.g. "
                 "spec/golden)\n";
    return 2;
  }
  set->make(argv[2]);
  return 0;
}
