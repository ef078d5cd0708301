// Export to DIMACS: convert -> export -> convert gives the same non-metadata sections, for both id
// bases; --view exports only its columns; queries and coordinates in the id base.
#include "mosb/converters/dimacs_export.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <map>
#include <string>

#include "mosb/converters/dimacs_converter.hpp"
#include "mosb/converters/dimacs_extended.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;
namespace fs = std::filesystem;

namespace {

using namespace mosb::testing;  // write_text, slurp

std::map<std::string, std::uint64_t> checksums(const GraphReader& r) {
  std::map<std::string, std::uint64_t> out;
  for (const auto& s : r.sections())
    if (s.name != "metadata")
      out[std::to_string(static_cast<int>(s.entry.kind)) + "/" + s.name] = s.entry.checksum;
  return out;
}

// Ids written with `base`: 4 vertices, arcs out of order by tail, a real-valued second column.
std::string graph_text(unsigned base, bool reals) {
  auto id = [base](int v) { return std::to_string(v + static_cast<int>(base)); };
  std::string text = "p sp 4 6\n";
  const int arcs[6][2] = {{2, 3}, {0, 1}, {1, 2}, {0, 2}, {3, 0}, {2, 3}};
  const char* ints[6] = {"7", "300", "1", "65536", "0", "2"};
  const char* floats[6] = {"0.1", "2.5", "1e-7", "3.0", "0.30000000000000004", "12345.678"};
  for (int k = 0; k < 6; ++k)
    text +=
        "a " + id(arcs[k][0]) + " " + id(arcs[k][1]) + " " + (reals ? floats[k] : ints[k]) + "\n";
  return text;
}

std::string coords_text(unsigned base) {
  std::string text = "p aux sp co 4\n";
  const long xy[4][2] = {
      {-73990000, 40750000}, {-73980000, 40760000}, {5, -6}, {2147483647, -2147483648L}};
  for (int v = 0; v < 4; ++v)
    text += "v " + std::to_string(v + static_cast<int>(base)) + " " + std::to_string(xy[v][0]) +
            " " + std::to_string(xy[v][1]) + "\n";
  return text;
}

GraphReader convert(const converters::DimacsOptions& o, bool derive, const fs::path& out) {
  auto g = converters::convert_dimacs(o);
  converters::ExtendedOptions extra;
  extra.hop = extra.avg_outdegree = derive;
  extra.views = {mosb::parse_view_spec("two=time,dist")};
  converters::append_derived_columns(g, extra, o.id_base);
  mosb::add_views(g, extra.views);
  write_graph(g, out);
  return GraphReader::open(out);
}

}  // namespace

TEST_CASE(
    "dimacs export: convert -> export -> convert keeps every non-metadata section, id base 0 and "
    "1") {
  for (unsigned base : {0u, 1u}) {
    CAPTURE(base);
    testing::TempDir dir;
    write_text(dir / "d.gr", graph_text(base, false));
    write_text(dir / "t.gr", graph_text(base, true));
    write_text(dir / "g.co", coords_text(base));
    converters::DimacsOptions o;
    o.gr_files = {(dir / "d.gr").string(), (dir / "t.gr").string()};
    o.objectives = {{"dist", "m"}, {"time", "s"}};
    o.co_file = (dir / "g.co").string();
    o.id_base = base;
    o.name = "B";
    const auto first = convert(o, true, dir / "first.mosb");
    REQUIRE(first.objective_count() == 4);

    const auto written =
        converters::export_dimacs(dir / "first.mosb", {dir / "out", {}, std::nullopt});
    REQUIRE(written.size() == 5);
    CHECK(written[0] == dir / "out" / "B-dist.gr");
    CHECK(written[4] == dir / "out" / "B.co");
    const auto text = slurp(dir / "out" / "B-dist.gr");
    CHECK(text.find("c instance digest " + first.digest() + "\n") != std::string::npos);
    CHECK(text.find("c objective dist unit m\np sp 4 6\n") != std::string::npos);
    const auto first_arc = "a " + std::to_string(base) + " " + std::to_string(1 + base) + " 300\n";
    CHECK(text.find(first_arc) != std::string::npos);

    converters::DimacsOptions again;
    for (const char* name : {"dist", "time", "avg_outdegree", "hop"})
      again.gr_files.push_back((dir / "out" / (std::string("B-") + name + ".gr")).string());
    again.objectives = {{"dist", "m"}, {"time", "s"}, {"avg_outdegree", ""}, {"hop", ""}};
    again.co_file = (dir / "out" / "B.co").string();
    again.id_base = base;
    again.name = "B";
    const auto second = convert(again, false, dir / "second.mosb");
    CHECK(checksums(second) == checksums(first));
    CHECK(second.metadata().get("id_base") == std::to_string(base));
    CHECK(second.objective(1).type == format::ElementType::f64);
  }
}

TEST_CASE("dimacs export: --view exports only its columns, in its order and its query set only") {
  testing::TempDir dir;
  GraphInput g;
  g.vertex_count = 3;
  g.tails = {2, 0};
  g.heads = {0, 1};
  g.costs.push_back({"a", "", std::vector<std::uint64_t>{1, 2}, std::nullopt});
  g.costs.push_back({"b", "", std::vector<double>{0.5, 1.0}, std::nullopt});
  g.costs.push_back({"c", "", std::vector<std::uint64_t>{5, 6}, std::nullopt});
  g.queries.push_back({"default", {{0, 2}, {1, 0}}});
  g.queries.push_back({"other", {{2, 2}}});
  g.metadata.set("benchmark", "T");
  g.metadata.set("id_base", "1");
  g.metadata.set("view.V.objectives", "c,b");
  g.metadata.set("view.V.queries", "default");
  write_graph(g, dir / "t.mosb");

  const auto all = converters::export_dimacs(dir / "t.mosb", {dir / "all", {}, std::nullopt});
  CHECK(all.size() == 5);
  CHECK(slurp(dir / "all" / "T-other.queries") == "3 3\n");
  CHECK(slurp(dir / "all" / "T-b.gr").find("p sp 3 2\na 1 2 1.0\na 3 1 0.5\n") !=
        std::string::npos);

  const auto view = converters::export_dimacs(dir / "t.mosb", {dir / "view", {"V", {}, {}}, 0u});
  REQUIRE(view.size() == 3);
  CHECK(view[0].filename() == "T-c.gr");
  CHECK(view[1].filename() == "T-b.gr");
  CHECK(view[2].filename() == "T-default.queries");
  CHECK(slurp(view[2]) == "0 2\n1 0\n");
  CHECK(slurp(view[0]).find("a 0 1 6\na 2 0 5\n") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "view" / "T-a.gr"));
  for (const auto& entry : fs::directory_iterator(dir / "view"))
    CHECK(entry.path().string().find(".tmp-") == std::string::npos);

  CHECK_THROWS_WITH_AS(converters::export_dimacs(dir / "t.mosb", {dir / "x", {"W", {}, {}}, {}}),
                       ((dir / "t.mosb").string() + ": no view 'W' (views: V)").c_str(), Error);

  // The view's objective list and query set given directly: the same files, no view needed.
  const auto listed =
      converters::export_dimacs(dir / "t.mosb", {dir / "list", {{}, {"c", "b"}, "default"}, 0u});
  REQUIRE(listed.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) CHECK(slurp(listed[i]) == slurp(view[i]));
}

TEST_CASE("dimacs export: reals print with '.' or an exponent and read back to the same value") {
  CHECK(converters::format_real_cost(1.0) == "1.0");
  CHECK(converters::format_real_cost(0.1) == "0.1");
  CHECK(converters::format_real_cost(1e22) == "1e+22");
  CHECK(converters::format_real_cost(static_cast<double>(0.1f)) == "0.10000000149011612");
}
