// Views: GraphReader's §7 view keys (parsed by view_keys) resolved to objective indices, how
// converters write views and how commands choose one (mosb/views.hpp).
#include "mosb/views.hpp"

#include <algorithm>

#include "mosb/format.hpp"
#include "mosb/internal/choices.hpp"

namespace mosb {

std::vector<std::string> GraphReader::view_names() const {
  std::vector<std::string> names;
  for (auto& keys : view_keys(metadata())) names.push_back(std::move(keys.name));
  return names;
}

View GraphReader::resolve(ViewKeys keys) const {
  View view{std::move(keys.name), {}, std::move(keys.query_set)};
  for (const auto& objective : keys.objectives) {
    const auto index = find_objective(objective);
    if (!index)
      fail("view '" + view.name + "' names objective '" + objective +
           "', which is not a cost section");
    view.objectives.push_back(*index);
  }
  if (!view.query_set.empty() && !find(format::SectionKind::queries, view.query_set))
    fail("view '" + view.name + "' names query set '" + view.query_set +
         "', which is not a queries section");
  return view;
}

std::vector<View> GraphReader::views() const {
  std::vector<View> views;
  for (auto& keys : view_keys(metadata())) views.push_back(resolve(std::move(keys)));
  return views;
}

std::optional<View> GraphReader::find_view(std::string_view name) const {
  auto keys = view_keys(metadata());
  const auto found =
      std::lower_bound(keys.begin(), keys.end(), name,
                       [](const ViewKeys& k, std::string_view n) { return k.name < n; });
  if (found == keys.end() || found->name != name) return std::nullopt;
  return resolve(std::move(*found));
}

View GraphReader::view(std::string_view name) const {
  if (auto found = find_view(name)) return std::move(*found);
  fail(ErrorCode::not_found,
       "no view '" + std::string(name) + "' " + choices_text(name, view_names(), "views"));
}

namespace {

// A user's text in a message: control characters shown as '?', at most 40 characters.
std::string shown(std::string_view text) {
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    out += (c < 0x20 || c == 0x7F) ? '?' : static_cast<char>(c);
  }
  return out + (text.size() > 40 ? "...'" : "'");
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

template <class Graph>
void add_views_to(Graph& graph, const std::vector<ViewSpec>& views) {
  std::vector<std::string> columns, sets;
  for (const auto& c : graph.costs) columns.push_back(c.name);
  for (const auto& q : graph.queries) sets.push_back(q.name);
  add_views(graph.metadata, columns, sets, views);
}

}  // namespace

namespace {

// `where` (the setting, and the text given for it) comes first in each refusal.
std::vector<std::string> parse_objective_list(std::string_view text, const Message& where) {
  auto refuse = [&where](const std::string& problem) {
    auto parts = where;
    parts.emplace_back(": " + problem);
    return Error(ErrorCode::invalid_argument, std::move(parts));
  };
  std::vector<std::string> list;
  while (true) {
    const auto comma = text.find(',');
    std::string objective(text.substr(0, comma));
    if (!format::is_valid_section_name(objective))
      throw refuse("empty or invalid objective name " + shown(objective));
    for (const auto& seen : list)
      if (seen == objective) throw refuse("objective '" + objective + "' listed twice");
    list.push_back(std::move(objective));
    if (comma == std::string_view::npos) return list;
    text = text.substr(comma + 1);
  }
}

}  // namespace

std::vector<std::string> parse_objective_list(std::string_view text) {
  return parse_objective_list(text, {setting("objectives")});
}

ViewSpec parse_view_spec(std::string_view text) {
  const Message where = {setting("view"), " " + shown(text)};
  auto refuse = [&where](const std::string& problem) {
    auto parts = where;
    parts.emplace_back(": " + problem);
    return Error(ErrorCode::invalid_argument, std::move(parts));
  };
  const auto equals = text.find('=');
  if (equals == std::string_view::npos) throw refuse("expected NAME=OBJ1,OBJ2,...[@QUERYSET]");
  ViewSpec view;
  view.name = std::string(text.substr(0, equals));
  auto rest = text.substr(equals + 1);
  if (const auto at = rest.find('@'); at != std::string_view::npos) {
    view.queries = std::string(rest.substr(at + 1));
    rest = rest.substr(0, at);
  }
  if (!Metadata::is_valid_key(view.name))
    throw refuse("the view name must be 1 or more of [A-Za-z0-9_.+-]");
  if (!format::is_valid_section_name(view.queries))
    throw refuse("the query set name must be " + std::string(format::kSectionNameRule));
  view.objectives = parse_objective_list(rest, where);
  return view;
}

void add_views(Metadata& metadata, const std::vector<std::string>& columns,
               const std::vector<std::string>& query_sets, const std::vector<ViewSpec>& views) {
  auto contains = [](const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  std::vector<std::string> seen;
  for (const auto& view : views) {
    if (contains(seen, view.name))
      throw Error(ErrorCode::invalid_argument,
                  {setting("view"), " '" + view.name + "' given twice"});
    seen.push_back(view.name);
    for (const auto& objective : view.objectives)
      if (!contains(columns, objective))
        throw Error(ErrorCode::not_found,
                    {setting("view"), " '" + view.name + "': objective '" + objective +
                                          "' is not a column (columns: " + joined(columns) + ")"});
    const std::string key = "view." + view.name;
    metadata.set(key + ".objectives", joined(view.objectives));
    // A replaced default view must not keep a query set the new one does not name.
    metadata.erase(key + ".queries");
    if (contains(query_sets, view.queries)) metadata.set(key + ".queries", view.queries);
    // The intended query set survives in the parameters for `mosb queries import|generate`.
    if (!view.queries.empty())
      metadata.set("source.param." + key, joined(view.objectives) + "@" + view.queries);
  }
}

void add_views(GraphInput& graph, const std::vector<ViewSpec>& views) {
  add_views_to(graph, views);
}

void add_views(StreamedGraph& graph, const std::vector<ViewSpec>& views) {
  add_views_to(graph, views);
}

std::optional<View> select_view(const GraphReader& reader, const ViewChoice& choice) {
  if (choice.empty()) return std::nullopt;
  if (!choice.view.empty() && !choice.objectives.empty())
    throw Error(ErrorCode::invalid_argument,
                {"give ", setting("view"), " or ", setting("objectives"),
                 ", not both (a view is a name for an objective list)"});
  View selected;
  if (!choice.view.empty()) selected = reader.view(choice.view);
  if (!choice.objectives.empty()) {
    selected.objectives.clear();
    for (const auto& name : choice.objectives)
      selected.objectives.push_back(reader.objective_index(name));
  } else if (choice.view.empty()) {
    for (std::size_t j = 0; j < reader.objective_count(); ++j) selected.objectives.push_back(j);
  }
  if (!choice.queries.empty()) {
    if (!reader.find(format::SectionKind::queries, choice.queries)) {
      throw Error(ErrorCode::not_found,
                  reader.display_name() + ": no query set '" + choice.queries + "' " +
                      choices_text(choice.queries, reader.query_set_names(), "query sets"));
    }
    selected.query_set = choice.queries;
  }
  return selected;
}

View solution_selection(const GraphReader& reader, const ViewChoice& choice) {
  auto selected = select_view(reader, choice);
  if (!selected || (choice.view.empty() && choice.objectives.empty()))
    throw Error(ErrorCode::invalid_argument,
                {reader.display_name() + ": give a view or an objective list (", setting("view"),
                 " V or ", setting("objectives"), " A,B,...)"});
  if (choice.view.empty()) {
    for (const auto& view : reader.views())
      if (view.objectives == selected->objectives) {
        selected->name = view.name;
        if (selected->query_set.empty()) selected->query_set = view.query_set;
        break;
      }
  }
  if (selected->query_set.empty())
    throw Error(ErrorCode::invalid_argument,
                {reader.display_name() + ": no query set for these objectives (" +
                     (selected->name.empty() ? std::string("no view has them")
                                             : "view '" + selected->name + "' names none") +
                     "); give ",
                 setting("queries"), " SET"});
  return *selected;
}

}  // namespace mosb
