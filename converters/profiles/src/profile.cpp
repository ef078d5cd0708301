#include "mosb/converters/profile.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "mosb/checksum.hpp"
#include "mosb/command_template.hpp"
#include "mosb/converters/solver_output.hpp"
#include "mosb/converters/toml_table.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/internal/source_error.hpp"
#include "placeholders.hpp"

namespace mosb::converters {

namespace {

constexpr std::array<std::string_view, 19> kPlaceholders = {
    "instance", "view",       "objectives", "query",   "source",   "target",  "front",
    "fronts",   "threads",    "executable", "gr",      "multi_gr", "queries", "co",
    "d",        "time_limit", "epsilon",    "gr:NAME", "OPTION"};

bool is_name(std::string_view text) {
  if (text.empty() || text.size() > 64) return false;
  return std::all_of(text.begin(), text.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
           c == '_';
  });
}

ProfileInput parse_input(TomlTable& root) {
  ProfileInput in;
  const auto* table = root.table("input");
  if (table == nullptr) return in;
  TomlTable f(*table, root.file(), "input.");
  in.form = f.choice("form", kInputFormNames).value_or(InputForm::mosb);
  in.id_base = static_cast<unsigned>(f.integer("id_base", 0, 1).value_or(0));
  in.integer_costs = f.boolean("integer_costs").value_or(false);
  if (const auto max = f.integer("max_arc_cost", 1, std::int64_t{1} << 53))
    in.max_arc_cost = static_cast<std::uint64_t>(*max);
  if (const auto max = f.integer("max_degree", 1, std::int64_t{1} << 32))
    in.max_degree = static_cast<std::uint64_t>(*max);
  in.parallel_arcs = f.choice("parallel_arcs", kParallelArcsNames).value_or(ParallelArcs::keep);
  in.append_dummy_arc = f.boolean("append_dummy_arc").value_or(false);
  in.pad_columns = static_cast<unsigned>(f.integer("pad_columns", 0, 64).value_or(0));
  in.queries_format = f.choice("queries", kQueriesFormatNames);
  if (const auto* range = f.array("objectives")) {
    if (range->size() != 2 || !(*range)[0].is_integer() || !(*range)[1].is_integer())
      f.fail(*range, "objectives", "expected [MIN, MAX] (MAX 0: no maximum)");
    const auto min = *(*range)[0].value<std::int64_t>(), max = *(*range)[1].value<std::int64_t>();
    if (min < 1 || max < 0 || max > 4096 || min > 4096 || (max != 0 && max < min))
      f.fail(*range, "objectives", "expected 1 <= MIN <= MAX (MAX 0: no maximum)");
    in.min_objectives = static_cast<unsigned>(min);
    in.max_objectives = static_cast<unsigned>(max);
  }
  if (in.pad_columns > 0 && in.form != InputForm::dimacs_multi_column)
    f.fail(*f.get("pad_columns"), "pad_columns", "only with form = \"dimacs-multi-column\"");
  f.refuse_unknown();
  return in;
}

ProfileTimeLimit parse_time_limit(TomlTable& root) {
  ProfileTimeLimit limit;
  const auto* table = root.table("time_limit");
  if (table == nullptr) return limit;
  TomlTable f(*table, root.file(), "time_limit.");
  limit.scale = f.number("scale", 1, 100).value_or(limit.scale);
  limit.add_seconds = f.number("add", 0, 1e6).value_or(limit.add_seconds);
  limit.integer = f.boolean("integer").value_or(false);
  limit.unlimited = f.number("unlimited", 1, 1e12).value_or(limit.unlimited);
  f.refuse_unknown();
  return limit;
}

std::vector<ProfileOption> parse_options(TomlTable& root) {
  std::vector<ProfileOption> options;
  const auto* table = root.table("options");
  if (table == nullptr) return options;
  TomlTable all(*table, root.file(), "options.");
  for (const auto& [key, node] : *table) {
    const std::string name(key.str());
    const auto* option_table = all.table(name);
    if (!is_name(name) ||
        std::find(kPlaceholders.begin(), kPlaceholders.end(), name) != kPlaceholders.end())
      all.fail(node, name, "an option's name is letters, digits, - and _, and no placeholder's");
    TomlTable f(*option_table, root.file(), "options." + name + ".");
    ProfileOption option;
    option.name = name;
    option.description = f.string("description").value_or("");
    option.default_value = f.required_string("default");
    option.values = f.strings("values");
    if (!option.values.empty() && std::find(option.values.begin(), option.values.end(),
                                            option.default_value) == option.values.end())
      f.fail(*f.get("default"), "default", "not one of the values");
    if (const auto* limits = f.table("max_objectives")) {
      TomlTable g(*limits, root.file(), "options." + name + ".max_objectives.");
      for (const auto& [value, limit] : *limits) {
        const std::string v(value.str());
        if (std::find(option.values.begin(), option.values.end(), v) == option.values.end())
          g.fail(limit, v, "not one of the option's values");
        option.max_objectives[v] = static_cast<unsigned>(*g.integer(v, 1, 4096));
      }
      g.refuse_unknown();
    }
    f.refuse_unknown();
    options.push_back(std::move(option));
  }
  all.refuse_unknown();
  return options;
}

OutputLine parse_output_line(const toml::node& node, const std::string& file,
                             const std::string& path, bool status) {
  if (!node.is_table()) {
    const auto at = position_of(node);
    throw Error(ErrorCode::invalid_argument,
                source_error(file, at.line, at.column, path, "expected a table"));
  }
  TomlTable f(*node.as_table(), file, path + ".");
  OutputLine line;
  line.file = f.choice("file", kOutputFileNames).value_or(OutputFile::front);
  line.text = status ? f.required_string("line") : f.required_string("prefix");
  if (line.text.empty()) f.fail(node, status ? "line" : "prefix", "empty");
  if (status) line.status = f.choice("status", kQueryStatusNames).value_or(QueryStatus::timeout);
  if (status && is_completed(line.status))
    f.fail(*f.get("status"), "status", "a status line states that the solver did not finish");
  if (const auto when = f.string("when")) {
    const auto eq = when->find('=');
    if (eq == std::string::npos || eq == 0) f.fail(*f.get("when"), "when", "expected OPTION=VALUE");
    line.when_option = when->substr(0, eq);
    line.when_value = when->substr(eq + 1);
  }
  f.refuse_unknown();
  return line;
}

std::vector<OutputLine> parse_output_lines(TomlTable& f, std::string_view key, bool status) {
  std::vector<OutputLine> lines;
  if (const auto* list = f.array(key))
    for (const auto& item : *list)
      lines.push_back(parse_output_line(item, f.file(), f.path(key), status));
  return lines;
}

// The keys of an output field (OutputField) in `f`.
OutputField parse_output_field(TomlTable& f) {
  OutputField field;
  field.file = f.choice("file", kOutputFileNames).value_or(OutputFile::stdout_file);
  field.prefix = f.required_string("prefix");
  field.field = static_cast<unsigned>(f.integer("field", 0, 1000).value_or(0));
  field.separator = f.string("separator").value_or("");
  if (field.field > 0 && field.separator.empty())
    f.fail(*f.get("field"), "field", "a field needs a separator");
  return field;
}

std::optional<OutputRuntime> parse_runtime(TomlTable& out) {
  const auto* table = out.table("runtime");
  if (table == nullptr) return std::nullopt;
  TomlTable f(*table, out.file(), "output.runtime.");
  OutputRuntime runtime;
  static_cast<OutputField&>(runtime) = parse_output_field(f);
  const auto unit = f.string("unit").value_or("s");
  if (unit != "s" && unit != "ms") f.fail(*f.get("unit"), "unit", "expected s or ms");
  runtime.unit_seconds = unit == "ms" ? 1e-3 : 1;
  f.refuse_unknown();
  return runtime;
}

std::optional<OutputField> parse_count(TomlTable& out) {
  const auto* table = out.table("count");
  if (table == nullptr) return std::nullopt;
  TomlTable f(*table, out.file(), "output.count.");
  auto count = parse_output_field(f);
  f.refuse_unknown();
  return count;
}

ProfileOutput parse_output(TomlTable& root) {
  ProfileOutput output;
  const auto* table = root.table("output");
  if (table == nullptr) return output;
  TomlTable f(*table, root.file(), "output.");
  output.format = f.string("format").value_or("protocol");
  // The registry's formats (mosb run --output-format) and the profile's own: vectors.
  const bool vectors = output.format == "vectors";
  if (!vectors && find_solver_output_format(output.format) == nullptr) {
    std::string expected = "expected";
    for (const auto& format : solver_output_formats())
      expected += " " + std::string(format.name) + ",";
    f.fail(*f.get("format"), "format", expected + " or vectors");
  }
  for (const char* key : {"file", "prefix", "group", "separator", "trailing_separator", "status",
                          "finished", "unfinished", "runtime", "count"})
    if (!vectors && f.get(key) != nullptr)
      f.fail(*f.get(key), key, "only with format = \"vectors\"");
  output.file = f.string("file").value_or("{front}");
  output.prefix = f.string("prefix").value_or("");
  output.group = static_cast<unsigned>(f.integer("group", 0, 16).value_or(0));
  output.separator = f.string("separator").value_or(" ");
  if (output.separator.empty()) f.fail(*f.get("separator"), "separator", "empty");
  output.trailing_separator = f.boolean("trailing_separator").value_or(false);
  output.status_lines = parse_output_lines(f, "status", true);
  output.finished = parse_output_lines(f, "finished", false);
  output.unfinished = f.choice("unfinished", kQueryStatusNames).value_or(QueryStatus::failed);
  if (is_completed(output.unfinished))
    f.fail(*f.get("unfinished"), "unfinished", "expected a status of a search that did not end");
  output.runtime = parse_runtime(f);
  output.runtime_clock = f.choice("runtime_clock", kRuntimeClockNames).value_or(RuntimeClock::wall);
  output.count = parse_count(f);
  f.refuse_unknown();
  return output;
}

// The command's placeholders are known, fit the input form, and {gr} is a word of its own.
void check_command(const SolverProfile& p, TomlTable& root) {
  std::vector<std::string> words;
  try {
    words = split_command(p.command);
  } catch (const Error& e) {
    root.fail(*root.get("command"), "command", e.what());
  }
  const auto refuse = [&](const std::string& what) {
    root.fail(*root.get("command"), "command", what);
  };
  if (words.front() != "{executable}")
    refuse("the first word is {executable} (the solver a run is given)");
  for (const auto& word : words) {
    const auto names = profile_internal::placeholder_names(word);
    if (!names) refuse("a lone brace in '" + word + "'");
    for (const auto& name : *names) {
      const bool option = std::any_of(p.options.begin(), p.options.end(),
                                      [&](const auto& o) { return o.name == name; });
      const bool gr = name == "gr" || name.rfind("gr:", 0) == 0;
      const bool known = option || gr ||
                         std::find(kPlaceholders.begin(), kPlaceholders.end() - 2, name) !=
                             kPlaceholders.end() - 2;
      if (!known) refuse("unknown placeholder {" + name + "}");
      if ((gr || name == "co") && p.input.form != InputForm::dimacs)
        refuse("{" + name + "} needs input.form = \"dimacs\"");
      if (name == "multi_gr" && p.input.form != InputForm::dimacs_multi_column)
        refuse("{multi_gr} needs input.form = \"dimacs-multi-column\"");
      if (name == "queries" && !p.input.queries_format)
        refuse(R"({queries} needs input.queries = "space" or "comma")");
      if (name == "gr" && word != "{gr}") refuse("{gr} is a word of its own (one word per file)");
    }
  }
}

}  // namespace

std::span<const std::string_view> profile_placeholders() {
  return kPlaceholders;
}

SolverProfile parse_profile(std::string_view text, const std::string& file) {
  const auto table = parse_toml(text, file);
  TomlTable root(table, file, "");
  SolverProfile p;
  p.file = file;
  p.text_digest = hex64(xxh3_64(text.data(), text.size()));
  p.name = root.required_string("name");
  if (!is_name(p.name)) root.fail(*root.get("name"), "name", "letters, digits, - and _ only");
  p.solver = root.string("solver").value_or("");  // empty: the executable's file name
  p.description = root.string("description").value_or("");
  p.repository = root.string("repository").value_or("");
  p.version = root.string("version").value_or("");
  p.command = root.required_string("command", true);
  if (const auto* codes = root.array("success_exit_codes")) {
    p.success_exit_codes.clear();
    for (const auto& code : *codes) {
      if (!code.is_integer() || *code.value<std::int64_t>() < 0 ||
          *code.value<std::int64_t>() > 255)
        root.fail(code, "success_exit_codes", "expected exit statuses 0 to 255");
      p.success_exit_codes.push_back(static_cast<int>(*code.value<std::int64_t>()));
    }
    if (p.success_exit_codes.empty())
      root.fail(*codes, "success_exit_codes", "at least one exit status");
  }
  p.input = parse_input(root);
  p.time_limit = parse_time_limit(root);
  p.options = parse_options(root);
  p.output = parse_output(root);
  check_command(p, root);
  root.refuse_unknown();
  return p;
}

SolverProfile load_profile(const std::string& name_or_path) {
  const bool path =
      name_or_path.find('/') != std::string::npos ||
      (name_or_path.size() > 5 && name_or_path.compare(name_or_path.size() - 5, 5, ".toml") == 0);
  if (!path) {
    for (const auto& shipped : shipped_profiles())
      if (shipped.name == name_or_path)
        return parse_profile(shipped.text, "(shipped) " + std::string(shipped.name) + ".toml");
    std::string names;
    for (const auto& shipped : shipped_profiles())
      names += (names.empty() ? "" : ", ") + std::string(shipped.name);
    throw Error(ErrorCode::invalid_argument,
                {setting("profile"), " " + name_or_path +
                                         ": no shipped profile of that name (shipped: " + names +
                                         "; a file's path has a / or ends in .toml)"});
  }
  return parse_profile(read_regular_file(name_or_path, std::uint64_t{1} << 20), name_or_path);
}

}  // namespace mosb::converters
