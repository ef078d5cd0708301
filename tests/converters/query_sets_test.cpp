// converters/queries/query_sets.hpp: which views a new query set becomes the set of.
#include "mosb/converters/query_sets.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/views.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

// Two columns and views: `free` (no set, no intent), `meant` (meant for set `scen`) and `bound`
// (has set `default`).
GraphReader three_views(const testing::TempDir& dir) {
  GraphInput g;
  g.vertex_count = 3;
  g.tails = {0, 1};
  g.heads = {1, 2};
  g.costs.push_back({"a", "", std::vector<std::uint64_t>{1, 2}, std::nullopt});
  g.costs.push_back({"b", "", std::vector<std::uint64_t>{3, 4}, std::nullopt});
  g.queries.push_back({"default", {{0, 2}}});
  add_views(g, {{"free", {"a", "b"}, ""}, {"meant", {"b"}, "scen"}, {"bound", {"a"}, "default"}});
  write_graph(g, dir / "v.mosb");
  return GraphReader::open(dir / "v.mosb", VerifyLevel::full);
}

}  // namespace

TEST_CASE("query sets: a new set becomes the set of the views that have none and mean no other") {
  testing::TempDir dir;
  const auto r = three_views(dir);
  CHECK(r.metadata().get("source.param.view.meant") == "b@scen");
  CHECK_FALSE(r.metadata().get("source.param.view.free").has_value());
  converters::QueryDrawOptions draw;
  draw.count = 2;
  auto edit = converters::draw_query_set(r, "other", draw, false);
  CHECK(edit.bound_views == std::vector<std::string>{"free"});
  CHECK(edit.metadata.get("view.free.queries") == "other");
  CHECK_FALSE(edit.metadata.get("view.meant.queries").has_value());
  CHECK(edit.metadata.get("view.bound.queries") == "default");

  edit = converters::draw_query_set(r, "scen", draw, false);
  CHECK(edit.bound_views == std::vector<std::string>{"free", "meant"});

  draw.binding.view = "bound";
  edit = converters::draw_query_set(r, "other", draw, false);
  CHECK(edit.bound_views == std::vector<std::string>{"bound"});
  CHECK(edit.metadata.get("view.bound.queries") == "other");
  CHECK_FALSE(edit.metadata.get("view.free.queries").has_value());

  draw.binding.view = "nope";
  CHECK_THROWS_WITH_AS(converters::draw_query_set(r, "other", draw, false),
                       doctest::Contains("no view 'nope' (views: bound, free, meant)"), Error);
}

TEST_CASE("views: a --view of a default view's name replaces it, its old set included") {
  GraphInput g;
  g.costs.push_back({"a", "", std::vector<std::uint64_t>{}, std::nullopt});
  g.costs.push_back({"b", "", std::vector<std::uint64_t>{}, std::nullopt});
  g.queries.push_back({"default", {}});
  add_views(g, {{"V", {"a", "b"}, "default"}});
  CHECK(g.metadata.get("view.V.queries") == "default");
  add_views(g, {parse_view_spec("V=b@later")});
  CHECK(g.metadata.get("view.V.objectives") == "b");
  CHECK_FALSE(g.metadata.get("view.V.queries").has_value());
  CHECK(g.metadata.get("source.param.view.V") == "b@later");
  CHECK_THROWS_WITH_AS(parse_objective_list("a,,b"),
                       "objectives: empty or invalid objective name ''", Error);
}
