// Regenerates spec/golden/1.1/references/: the valid instance from golden_references_input() and
// invalid ones, each with one fault in its query reference, listed with the level at which it
// fails in invalid/EXPECTED.tsv (the format of spec/golden/1.0/invalid/EXPECTED.tsv).
// Usage: mosb_make_golden_references spec/golden/1.1/references
#include <fstream>
#include <functional>
#include <iostream>

#include "golden_references.hpp"
#include "mosb/file_writer.hpp"
#include "mosb/graph_reader.hpp"

using namespace mosb;
using format::ElementType;
using format::SectionKind;

namespace {

// How a fault rewrites the reference section: its name, type, width and payload.
struct Reference {
  std::string name;
  ElementType type;
  std::uint32_t width;
  std::vector<std::byte> bytes;
};

struct Fault {
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
void write_faulty(const GraphReader& valid, const Fault& fault, const std::filesystem::path& out) {
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

const Fault kFaults[] = {
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

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: mosb_make_golden_references DIR (e.g. spec/golden/1.1/references)\n";
    return 2;
  }
  const std::filesystem::path root = argv[1];
  std::filesystem::create_directories(root / "valid");
  std::filesystem::create_directories(root / "invalid");
  write_graph(testing::golden_references_input(), root / "valid" / "references.mosb");
  const auto valid = GraphReader::open(root / "valid" / "references.mosb", VerifyLevel::full);
  std::ofstream expected(root / "invalid" / "EXPECTED.tsv");
  expected << "# file\tlevel at which it fails\texpected message fragment\n";
  for (const auto& fault : kFaults) {
    write_faulty(valid, fault, root / "invalid" / fault.file);
    expected << fault.file << '\t' << fault.level << '\t' << fault.expected << '\n';
  }
  std::cout << "wrote " << root.string() << "\n";
  return 0;
}
