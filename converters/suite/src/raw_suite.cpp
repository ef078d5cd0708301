#include "mosb/converters/raw_suite.hpp"

#include <algorithm>
#include <set>
#include <system_error>

#include "mosb/converters/dimacs_converter.hpp"
#include "mosb/converters/dimacs_extended.hpp"
#include "mosb/converters/fmi_converter.hpp"
#include "mosb/converters/guards_converter.hpp"
#include "mosb/converters/objective.hpp"
#include "mosb/converters/query_sets.hpp"
#include "mosb/converters/roadmap_converter.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/instance_editor.hpp"

namespace mosb::converters {

namespace {

constexpr const char* kCompressedSuffixes[] = {".gz", ".bz2", ".xz", ".zst"};

std::string strip_compression(const std::string& name) {
  for (std::string_view suffix : kCompressedSuffixes)
    if (name.size() > suffix.size() && name.ends_with(suffix))
      return name.substr(0, name.size() - suffix.size());
  return name;
}

// `mosb queries import FILE --set default --in-place QUERIES`: the same two library calls.
std::function<void(const std::filesystem::path&)> import_default_queries(
    const std::filesystem::path& queries) {
  if (queries.empty()) return {};
  return [queries](const std::filesystem::path& file) {
    const auto reader = GraphReader::open(file, VerifyLevel::full);
    QueryImportOptions options;
    options.file = queries;
    auto edit = import_query_set(reader, "default", options, false);
    rewrite_instance(reader, edit.metadata, {std::move(edit.set)}, file);
  };
}

// DIMACS-NY (views DIMACS-NY_2 and, with the elevation file, DIMACS-Extended-NY_3/_4/_5) and
// DIMACS-FLA (DIMACS-FLA_2): spec/families/road.md, "Recipe".
RawRecipe dimacs_recipe(const std::string& region, bool extended, bool queries) {
  RawRecipe r;
  r.name = "DIMACS-" + region;
  r.inputs = {{"USA-road-d." + region + ".gr.gz"},
              {"USA-road-t." + region + ".gr.gz"},
              {"USA-road-d." + region + ".co.gz"}};
  if (extended) r.inputs.push_back({region + ".elev", true});
  if (queries) r.inputs.push_back({"USA-road-" + region + "-queries", true});
  r.instance = [region, name = r.name,
                extended](const std::vector<std::filesystem::path>& paths) -> SuiteInstance {
    DimacsOptions o;
    o.gr_files = {paths[0].string(), paths[1].string()};
    o.objectives = {parse_objective("distance", "convert dimacs"),
                    parse_objective("time", "convert dimacs")};
    o.co_file = paths[2].string();
    o.name = name;
    ExtendedOptions e;
    e.views.push_back(parse_view_spec("DIMACS-" + region + "_2=distance,time"));
    if (extended && !paths[3].empty()) {
      e.elevation_file = paths[3].string();
      e.avg_outdegree = true;
      e.hop = true;
      const std::string prefix = "DIMACS-Extended-" + region;
      e.views.push_back(parse_view_spec(prefix + "_3=distance,time,elevation"));
      e.views.push_back(parse_view_spec(prefix + "_4=distance,time,elevation,avg_outdegree"));
      e.views.push_back(parse_view_spec(prefix + "_5=distance,time,elevation,avg_outdegree,hop"));
    }
    const std::filesystem::path query_file = paths.size() > 4 ? paths[4] : "";
    return {name, [o, e] { return convert_dimacs_extended(o, e); },
            import_default_queries(query_file)};
  };
  return r;
}

// GER_10: the paper's 10,000-vertex extract in the FMI multi-cost layout (spec/families/ger.md).
RawRecipe ger10_recipe() {
  RawRecipe r;
  r.name = "GER_10";
  r.inputs = {{"GER_10.txt"}};
  r.instance = [](const std::vector<std::filesystem::path>& paths) -> SuiteInstance {
    FmiOptions o;
    o.file = paths[0].string();
    o.cost_count = 10;
    o.name = "GER_10";
    return {"GER_10", [o] { return convert_fmi(o); }, {}};
  };
  return r;
}

// One GUARDS map: MAP.map with its guards MAP.guards (spec/families/games.md), view Games-GUARDS_2.
RawRecipe guards_recipe(const std::string& map) {
  RawRecipe r;
  r.name = "Games-GUARDS-" + map;
  r.inputs = {{map + ".map"}, {map + ".guards"}};
  r.instance = [name = r.name](const std::vector<std::filesystem::path>& paths) -> SuiteInstance {
    GuardsOptions o;
    o.map_file = paths[0].string();
    o.guards_file = paths[1].string();
    return {name, [o] { return convert_guards(o).graph; }, {}};
  };
  return r;
}

// Panda-RRG_2 (aggregate clearance) and Panda-RRG_8 (per link): OMPL GraphML roadmaps
// (spec/families/robots.md).
RawRecipe panda_recipe(const std::string& name, ClearanceMode clearance) {
  RawRecipe r;
  r.name = name;
  r.inputs = {{name + ".graphml"}};
  r.instance = [name, clearance](const std::vector<std::filesystem::path>& paths) -> SuiteInstance {
    RoadmapOptions o;
    o.graphml_file = paths[0].string();
    o.clearance = clearance;
    o.name = name;
    return {name, [o] { return convert_roadmap(o); }, {}};
  };
  return r;
}

// The paper names one of its 12 GUARDS maps exactly (random512-20-1); the others are found by
// their guard files.
std::set<std::string> guards_maps(const std::filesystem::path& raw_dir) {
  std::set<std::string> maps = {"random512-20-1"};
  std::error_code ec;
  for (std::filesystem::directory_iterator it(raw_dir, ec), end; !ec && it != end;
       it.increment(ec)) {
    const auto name = strip_compression(it->path().filename().string());
    constexpr std::string_view kSuffix = ".guards";
    if (name.size() > kSuffix.size() && name.ends_with(kSuffix))
      maps.insert(name.substr(0, name.size() - kSuffix.size()));
  }
  if (ec) throw Error(raw_dir.string() + ": cannot list the raw-source directory: " + ec.message());
  return maps;
}

}  // namespace

std::vector<std::string> raw_input_candidates(const std::string& name) {
  const auto plain = strip_compression(name);
  std::vector<std::string> out = {name};
  if (plain != name) out.push_back(plain);
  for (std::string_view suffix : kCompressedSuffixes) {
    auto candidate = plain + std::string(suffix);
    if (std::find(out.begin(), out.end(), candidate) == out.end())
      out.push_back(std::move(candidate));
  }
  return out;
}

std::vector<RawRecipe> raw_recipes(const std::filesystem::path& raw_dir) {
  std::vector<RawRecipe> out;
  out.push_back(dimacs_recipe("NY", true, true));
  out.push_back(dimacs_recipe("FLA", false, false));
  out.push_back(ger10_recipe());
  for (const auto& map : guards_maps(raw_dir)) out.push_back(guards_recipe(map));
  out.push_back(panda_recipe("Panda-RRG_2", ClearanceMode::aggregate));
  out.push_back(panda_recipe("Panda-RRG_8", ClearanceMode::per_link));
  std::sort(out.begin(), out.end(),
            [](const RawRecipe& a, const RawRecipe& b) { return a.name < b.name; });
  return out;
}

RawPlan plan_raw_suite(const std::filesystem::path& raw_dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(raw_dir, ec))
    throw Error(raw_dir.string() + ": the raw-source directory does not exist");
  RawPlan plan;
  for (const auto& recipe : raw_recipes(raw_dir)) {
    RawStatus status{recipe.name, {}};
    std::vector<std::filesystem::path> paths;
    for (const auto& input : recipe.inputs) {
      std::filesystem::path found;
      for (const auto& candidate : raw_input_candidates(input.name))
        if (std::filesystem::is_regular_file(raw_dir / candidate, ec)) {
          found = raw_dir / candidate;
          break;
        }
      if (found.empty() && !input.optional) status.missing.push_back(input.name);
      paths.push_back(std::move(found));
    }
    if (status.missing.empty()) plan.instances.push_back(recipe.instance(paths));
    plan.statuses.push_back(std::move(status));
  }
  return plan;
}

}  // namespace mosb::converters
