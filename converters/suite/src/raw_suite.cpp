#include "mosb/converters/raw_suite.hpp"

#include <algorithm>
#include <optional>
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
#include "suite_description.hpp"

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

namespace description = suite_description;

// Input `name` of a recipe: its index in the recipe's `inputs` (the order `instance` gets paths).
std::size_t add_input(RawRecipe& r, std::string name, bool optional = false) {
  r.inputs.push_back({std::move(name), optional});
  return r.inputs.size() - 1;
}

// DIMACS-NY (views DIMACS-NY_2 and, with the elevation file, DIMACS-Extended-NY_3/_4/_5) and
// DIMACS-FLA (DIMACS-FLA_2): spec/families/road.md, "Recipe".
RawRecipe dimacs_recipe(const description::Json& d) {
  RawRecipe r;
  r.name = description::text(d, "name");
  std::vector<std::size_t> gr;
  for (const auto& file : description::texts(d, "gr")) gr.push_back(add_input(r, file));
  const auto co = add_input(r, description::text(d, "co"));
  DimacsOptions o;
  for (const auto& objective : description::texts(d, "objectives"))
    o.objectives.push_back(parse_objective(objective, "convert dimacs"));
  o.name = r.name;
  ExtendedOptions e;
  for (const auto& view : description::texts(d, "views")) e.views.push_back(parse_view_spec(view));
  // With its optional elevation file, the recipe derives and views what the file allows.
  std::optional<std::size_t> elevation;
  ExtendedOptions with_elevation = e;
  if (d.contains("elevation")) {
    const auto& elev = d.at("elevation");
    elevation = add_input(r, description::text(elev, "input"), true);
    for (const auto& derived : description::texts(elev, "derive")) {
      if (derived == "avg-outdegree")
        with_elevation.avg_outdegree = true;
      else if (derived == "hop")
        with_elevation.hop = true;
      else
        throw Error("spec/suite.json (built in): unknown derived objective '" + derived + "'");
    }
    for (const auto& view : description::texts(elev, "views"))
      with_elevation.views.push_back(parse_view_spec(view));
  }
  std::optional<std::size_t> queries;
  if (d.contains("queries")) {
    if (description::text(d.at("queries"), "set") != "default")
      throw Error("spec/suite.json (built in): a raw recipe's query set must be 'default'");
    queries = add_input(r, description::text(d.at("queries"), "input"), true);
  }
  r.instance = [name = r.name, gr, co, elevation, queries, o, e, with_elevation](
                   const std::vector<std::filesystem::path>& paths) mutable -> SuiteInstance {
    for (auto i : gr) o.gr_files.push_back(paths[i].string());
    o.co_file = paths[co].string();
    if (elevation && !paths[*elevation].empty()) {
      e = with_elevation;
      e.elevation_file = paths[*elevation].string();
    }
    const std::filesystem::path query_file = queries ? paths[*queries] : "";
    return {name, [o, e] { return convert_dimacs_extended(o, e); },
            import_default_queries(query_file)};
  };
  return r;
}

// GER_10: the paper's 10,000-vertex extract in the FMI multi-cost layout (spec/families/ger.md).
RawRecipe fmi_recipe(const description::Json& d) {
  RawRecipe r;
  r.name = description::text(d, "name");
  add_input(r, description::text(d, "input"));
  FmiOptions o;
  o.cost_count = description::count(d, "costs");
  o.name = r.name;
  r.instance = [o](const std::vector<std::filesystem::path>& paths) mutable -> SuiteInstance {
    o.file = paths[0].string();
    return {*o.name, [o] { return convert_fmi(o); }, {}};
  };
  return r;
}

// One GUARDS map: MAP.map with its guards MAP.guards (spec/families/games.md), view Games-GUARDS_2.
RawRecipe guards_recipe(const description::Json& d, const std::string& map) {
  RawRecipe r;
  const std::vector<std::pair<std::string, std::string>> values = {{"map", map}};
  r.name = description::expand(description::text(d, "name"), values);
  add_input(r, description::expand(description::text(d, "map"), values));
  add_input(r, description::expand(description::text(d, "guards"), values));
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
RawRecipe roadmap_recipe(const description::Json& d) {
  RawRecipe r;
  r.name = description::text(d, "name");
  add_input(r, description::text(d, "graphml"));
  RoadmapOptions o;
  const auto clearance = kClearanceModeNames.parse(description::text(d, "clearance"));
  if (!clearance) throw Error("spec/suite.json (built in): unknown clearance mode in " + r.name);
  o.clearance = *clearance;
  o.name = r.name;
  r.instance = [o](const std::vector<std::filesystem::path>& paths) mutable -> SuiteInstance {
    o.graphml_file = paths[0].string();
    return {*o.name, [o] { return convert_roadmap(o); }, {}};
  };
  return r;
}

// The maps the description names (the paper names one of its 12 GUARDS maps exactly), and every
// map whose file matches `maps_from` ("{map}.guards") in RAWDIR, since the others are found by
// their guard files.
std::set<std::string> guards_maps(const description::Json& d,
                                  const std::filesystem::path& raw_dir) {
  const auto names = description::texts(d, "maps");
  std::set<std::string> maps(names.begin(), names.end());
  const auto pattern = description::text(d, "maps_from");
  const auto at = pattern.find("{map}");
  if (at == std::string::npos)
    throw Error("spec/suite.json (built in): 'maps_from' must contain {map}");
  const auto prefix = pattern.substr(0, at), suffix = pattern.substr(at + 5);
  std::error_code ec;
  for (std::filesystem::directory_iterator it(raw_dir, ec), end; !ec && it != end;
       it.increment(ec)) {
    const auto name = strip_compression(it->path().filename().string());
    if (name.size() > prefix.size() + suffix.size() && name.starts_with(prefix) &&
        name.ends_with(suffix))
      maps.insert(name.substr(prefix.size(), name.size() - prefix.size() - suffix.size()));
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
  for (const auto& d : description::root().at("raw")) {
    const auto converter = description::text(d, "converter");
    const auto first = out.size();
    if (converter == "dimacs")
      out.push_back(dimacs_recipe(d));
    else if (converter == "fmi")
      out.push_back(fmi_recipe(d));
    else if (converter == "guards")
      for (const auto& map : guards_maps(d, raw_dir)) out.push_back(guards_recipe(d, map));
    else if (converter == "roadmap")
      out.push_back(roadmap_recipe(d));
    else
      throw Error("spec/suite.json (built in): unknown converter '" + converter + "'");
    for (auto r = out.begin() + static_cast<std::ptrdiff_t>(first); r != out.end(); ++r)
      r->source = description::text(d, "source");
  }
  std::sort(out.begin(), out.end(),
            [](const RawRecipe& a, const RawRecipe& b) { return a.name < b.name; });
  return out;
}

std::string raw_status_text(const RawStatus& status) {
  if (status.missing.empty()) return status.name + ": built";
  std::string missing;
  for (const auto& name : status.missing) missing += (missing.empty() ? "" : ", ") + name;
  return status.name + ": skipped: missing " + missing + " (from: " + status.source + ")";
}

RawPlan plan_raw_suite(const std::filesystem::path& raw_dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(raw_dir, ec))
    throw Error(raw_dir.string() + ": the raw-source directory does not exist");
  RawPlan plan;
  for (const auto& recipe : raw_recipes(raw_dir)) {
    RawStatus status{recipe.name, {}, recipe.source};
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
