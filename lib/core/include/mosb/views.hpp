// Benchmark views (spec/FORMAT.md §7, spec/SOLUTIONS.md §1): the one mechanism every converter
// uses to write them (ViewSpec, add_views) and every command uses to choose what it evaluates
// (ViewChoice, select_view). A view is a named shortcut for an objective list and its query set;
// a command given the list and the set directly needs no view, so no instance is edited (an edit
// changes the content digest that published solution files are bound to).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/metadata.hpp"

namespace mosb {

// A view a converter writes: `NAME=OBJ1,OBJ2,...[@QUERYSET]` (the --view option of every
// `convert` and `generate` command).
struct ViewSpec {
  std::string name;
  std::vector<std::string> objectives;
  std::string queries = "default";  // empty: no intended set (the first one added becomes it)
};

// Parses the text of one --view option; throws mosb::Error naming the setting "view" ("view 'TEXT':
// ...").
ViewSpec parse_view_spec(std::string_view text);

// Parses `OBJ1,OBJ2,...` (ViewChoice::objectives): valid section names, none twice; throws
// mosb::Error naming the setting "objectives" (see MessagePart).
std::vector<std::string> parse_objective_list(std::string_view text);

// Writes view.NAME.objectives, and view.NAME.queries only when `query_sets` holds that set (a later
// `mosb queries import|generate` adds it), keeping the intended set in
// `source.param.view.NAME = OBJ,...@SET` (not for an empty SET). A view of a name the metadata
// already has (a family's default view) is replaced. Refuses objectives not in `columns` and a name
// given twice.
void add_views(Metadata& metadata, const std::vector<std::string>& columns,
               const std::vector<std::string>& query_sets, const std::vector<ViewSpec>& views);
// The same on a converter's output (its cost column names and query sets).
void add_views(GraphInput& graph, const std::vector<ViewSpec>& views);
void add_views(StreamedGraph& graph, const std::vector<ViewSpec>& views);

// What a command evaluates: a view by name, or an objective list (with or without a view), and a
// query set that overrides the view's. Every field empty: the command's default.
struct ViewChoice {
  std::string view;                     // --view NAME
  std::vector<std::string> objectives;  // --objectives A,B,...
  std::string queries;                  // --queries SET
  bool empty() const { return view.empty() && objectives.empty() && queries.empty(); }
};

// Resolves `choice` on `reader`: nullopt when it is empty; otherwise a View whose name is the
// view's (empty without one), objectives the listed ones, else the view's, else every objective in
// table order, and query set `choice.queries`, else the view's (empty when neither names one).
// Throws mosb::Error naming the file: not_found for an unknown view, objective or query set,
// invalid_argument for both a view and an objective list.
std::optional<View> select_view(const GraphReader& reader, const ViewChoice& choice);

// What a solution file is bound to for `choice` (spec/SOLUTIONS.md §2): select_view's result,
// where an objective list given without a view is named after the first of `reader`'s views with
// exactly that list, in order (so the file says format 1.3), and takes that view's query set
// unless `choice.queries` names one; without such a view it stays unnamed (format 1.4). Throws as
// select_view, and invalid_argument naming the file for an empty choice or no query set.
View solution_selection(const GraphReader& reader, const ViewChoice& choice);

}  // namespace mosb
