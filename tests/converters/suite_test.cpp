// spec/suite.json is the suite: the built-in copy is the file, and what the builders make is what
// it says (names, sizes, views, raw inputs).
#include "mosb/converters/suite.hpp"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "mosb/converters/netmaker_generator.hpp"
#include "mosb/converters/raw_suite.hpp"
#include "mosb/manifest.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;

namespace {
nlohmann::json description() {
  return nlohmann::json::parse(converters::suite_description_json());
}
}  // namespace

TEST_CASE("the built-in suite description is spec/suite.json, byte for byte") {
  const auto file = testing::slurp(std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "suite.json");
  CHECK(file == std::string(converters::suite_description_json()));
  CHECK(description().at("seed") == 1);
}

TEST_CASE("the published generated suite is the description's 49 Grids then 12 NetMakers") {
  const auto instances = converters::published_generated_suite();
  REQUIRE(instances.size() == 49 + 12);
  CHECK(instances.front().name == "Grid-300x300");
  CHECK(instances[48].name == "Grid-600x600");
  CHECK(instances[49].name == "NetMaker-N10000-I20-1");
  CHECK(instances.back().name == "NetMaker-N30000-I50-2");
  CHECK(converters::paper_grid_sizes() ==
        description().at("generated").at(0).at("sizes").get<std::vector<std::uint32_t>>());
}

TEST_CASE("every generated benchmark carries the views the description lists") {
  testing::TempDir dir;
  const auto suite = description();  // a range-for over a temporary's member would dangle
  for (const auto& generated : suite.at("generated")) {
    const auto generator = generated.at("generator").get<std::string>();
    CAPTURE(generator);
    const auto instances = generator == "grid" ? converters::grid_suite(1, {6})
                                               : converters::netmaker_suite(1, {10000});
    const auto out = dir / generator;
    converters::run_suite(out, {instances.front()}, {1, {}, {}});
    const auto manifest = read_manifest(out / "MANIFEST");
    REQUIRE(manifest.entries.size() == 1);
    auto views = generated.at("views").get<std::vector<std::string>>();
    // NetMaker's view is one per size, as the paper's Table 1 splits it.
    if (generator == "netmaker") {
      CHECK(views == std::vector<std::string>{"NetMaker-{size}_3"});
      views = {"NetMaker-10k_3"};
      CHECK(converters::netmaker_view(300, 3) == "NetMaker-300_3");
      CHECK(converters::netmaker_view(30000, 2) == "NetMaker-30k_2");
      CHECK(converters::netmaker_view(0, 3) == "NetMaker-0_3");
    }
    CHECK(manifest.entries[0].views == views);
  }
}

TEST_CASE("the raw recipes are the description's, with its inputs in order") {
  testing::TempDir dir;
  testing::write_text(dir / "other-map.guards", "");
  const auto recipes = converters::raw_recipes(dir.path());
  std::vector<std::string> names;
  for (const auto& r : recipes) names.push_back(r.name);
  CHECK(names == std::vector<std::string>{"DIMACS-FLA", "DIMACS-NY", "GER_10",
                                          "Games-GUARDS-other-map", "Games-GUARDS-random512-20-1",
                                          "Panda-RRG_2", "Panda-RRG_8"});
  const auto& ny = recipes[1];
  REQUIRE(ny.inputs.size() == 5);
  CHECK(ny.inputs[0].name == "USA-road-d.NY.gr.gz");
  CHECK(ny.inputs[2].name == "USA-road-d.NY.co.gz");
  CHECK(ny.inputs[3].name == "NY.elev");
  CHECK(ny.inputs[3].optional);
  CHECK(ny.inputs[4].name == "USA-road-NY-queries");
  CHECK(recipes[3].inputs[1].name == "other-map.guards");
  CHECK(recipes[6].inputs[0].name == "Panda-RRG_8.graphml");
}
