#include "mosb/converters/solution_import.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/solution_verify.hpp"

namespace mosb::converters {

namespace {

using text::fail;
using text::quoted;

bool is_value_separator(char c) {
  return c == ' ' || c == '\t' || c == ',' || c == ';';
}

constexpr std::uint64_t kMaxExactInteger = std::uint64_t{1} << 53;

// Why a cost written with a point or an exponent is not read exactly, or empty. Text that rounds
// to 2^53 (9007199254740993.0, 9.007199254740993e15) passes every later check of an integer cost
// (at most 2^53) as another integer than the solver wrote, so it is refused; one that rounds above
// is refused for an integer objective by the solution writer, and is a float objective's value.
std::string inexact_problem(double value, std::string_view text) {
  if (value != static_cast<double>(kMaxExactInteger)) return {};
  return "the cost " + std::string(text) +
         " is read as 2^53, to which a point or an exponent may have rounded it: write an "
         "integer cost as digits alone";
}

// Why `token` is no cost, or empty when it is one (stored in `value`). An integer of digits alone
// is read exactly: one above 2^53 would be rounded to another (…993 to …992), so it is refused.
std::string cost_problem(std::string_view token, double& value) {
  if (!token.empty() && token.find_first_not_of("0123456789") == std::string_view::npos) {
    std::uint64_t n = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), n);
    if (ec != std::errc() || n > kMaxExactInteger)
      return "the integer " + quoted(token) + " is above 2^53, the largest exact integer cost";
    value = static_cast<double>(n);
    return {};
  }
  const auto parsed = text::to_real(token);
  if (!parsed) {
    std::string lower(token);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower.find("inf") != std::string::npos || lower.find("nan") != std::string::npos)
      return "non-finite cost " + quoted(token);
    return "expected a cost, found " + quoted(token);
  }
  if (!std::isfinite(*parsed)) return "non-finite cost " + quoted(token);
  if (*parsed < 0) return "negative cost " + quoted(token);
  if (auto problem = inexact_problem(*parsed, quoted(token)); !problem.empty()) return problem;
  value = *parsed;
  return {};
}

// Why a vector of `count` values cannot give the view's d values, or empty.
Message width_problem(std::size_t count, const SolutionImportOptions& o) {
  if (o.columns.empty()) {
    if (count == o.objective_count) return {};
    return {text::plural(count, "value") + ", the view has " +
                text::plural(o.objective_count, "objective") + " (",
            setting("columns"), " picks values)"};
  }
  for (auto c : o.columns)
    if (c >= count)
      return {text::plural(count, "value") + ", ", setting("columns"),
              " needs value " + std::to_string(c)};
  return {};
}

// Appends the view's values of `row` to `costs` (width already checked).
void append_picked(const std::vector<double>& row, const SolutionImportOptions& o,
                   std::vector<double>& costs) {
  if (o.columns.empty()) {
    costs.insert(costs.end(), row.begin(), row.end());
    return;
  }
  for (auto c : o.columns) costs.push_back(row[c]);
}

std::string queries_text(std::size_t count) {
  return std::to_string(count) + (count == 1 ? " query" : " queries");
}

// A query id as written in the input, 0-based in the set, or why not.
std::string query_problem(std::string_view token, const SolutionImportOptions& o,
                          std::uint64_t& query) {
  const auto id = text::to_u64(token);
  const auto count = o.queries.size();
  if (!id) return "expected a query id, found " + quoted(token);
  if (*id < o.id_base || *id - o.id_base >= count)
    return "query id " + std::string(token) + " outside " + std::to_string(o.id_base) + ".." +
           std::to_string(count - 1 + o.id_base) + " (the set has " + queries_text(count) + ")";
  query = *id - o.id_base;
  return {};
}

void check_options(const SolutionImportOptions& o) {
  if (o.objective_count == 0) throw Error(ErrorCode::invalid_argument, "no objectives");
  if (o.id_base > 1)
    throw Error(ErrorCode::invalid_argument, {setting("id_base"), " must be 0 or 1"});
  if (!o.columns.empty() && o.columns.size() != o.objective_count)
    throw Error(
        ErrorCode::invalid_argument,
        {setting("columns"), " picks " + text::plural(o.columns.size(), "value") +
                                 ", the view has " + text::plural(o.objective_count, "objective")});
}

// Sorts by query and refuses two results for one query.
std::vector<ImportedResult> by_query(std::vector<ImportedResult> results,
                                     std::vector<std::string> where) {
  std::vector<std::size_t> order(results.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](auto a, auto b) { return results[a].query < results[b].query; });
  std::vector<ImportedResult> sorted;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && results[order[k]].query == results[order[k - 1]].query)
      throw Error(ErrorCode::invalid_argument, where[order[k]] + ": a second result for query " +
                                                   std::to_string(results[order[k]].query) +
                                                   " (the first: " + where[order[k - 1]] + ")");
    sorted.push_back(std::move(results[order[k]]));
  }
  return sorted;
}

// Applies a stated status to `result`, whose vectors (if any) are already read, or why not.
std::string stated_front_problem(const ImportedResult& result) {
  if (result.status != QueryStatus::solved && !result.costs.empty())
    return "status " + std::string(to_string(result.status)) +
           " with vectors (only a solved query has a front)";
  if (result.statistics.exit_status && result.status != QueryStatus::failed)
    return "an exit status for a " + std::string(to_string(result.status)) +
           " query (only failed ones carry it)";
  return {};
}

// An exit status as an input writes it: the code, or 128 + N for signal N.
std::string exit_status_problem(std::string_view token, std::optional<std::uint64_t>& out) {
  const auto code = text::to_u64(token, kAbsentCount - 1);
  if (!code) return "expected an exit status (0 .. 2^64-2), found " + quoted(token);
  out = *code;
  return {};
}

// A table row's `status` and `exit_status` fields (either column may be absent): the first row of
// a query sets its status, later rows must agree, and only a solved query has more than one row.
void table_row_status(const std::string& name, std::uint64_t line,
                      const std::vector<text::Token>& fields, std::size_t status_column,
                      std::size_t exit_column, bool first_row, ImportedResult& result) {
  QueryStatus status = QueryStatus::solved;
  if (status_column != SIZE_MAX && !fields[status_column].text.empty())
    if (auto problem = stated_status_problem(fields[status_column].text, status))
      fail(name, line, fields[status_column].column, *problem);
  if (first_row) {
    result.status = status;
    result.status_stated = status_column != SIZE_MAX;
  } else if (status != result.status || status != QueryStatus::solved) {
    fail(name, line, status_column == SIZE_MAX ? 1 : fields[status_column].column,
         "a second row for query " + std::to_string(result.query) + " with status " +
             std::string(to_string(status)) + " (an earlier row says " +
             std::string(to_string(result.status)) + "; only a solved query has several rows)");
  }
  if (exit_column != SIZE_MAX && !fields[exit_column].text.empty()) {
    if (auto problem = exit_status_problem(fields[exit_column].text, result.statistics.exit_status);
        !problem.empty())
      fail(name, line, fields[exit_column].column, problem);
    if (status != QueryStatus::failed)
      fail(name, line, fields[exit_column].column,
           "an exit status for a " + std::string(to_string(status)) +
               " query (only failed ones carry it)");
  }
}

// A JSON record's optional "status" and "exit_status" into `result`.
template <class Json, class At>
void json_record_status(const Json& record, const std::string& record_at, const At& at,
                        ImportedResult& result) {
  if (const auto status = record.find("status"); status != record.end()) {
    if (!status->is_string())
      throw at(record_at + "/status", "expected a status word, found " + status->dump());
    if (auto problem = stated_status_problem(status->template get<std::string>(), result.status))
      throw at(record_at + "/status", *problem);
    result.status_stated = true;
  }
  if (const auto code = record.find("exit_status"); code != record.end()) {
    if (!code->is_number_unsigned() || code->template get<std::uint64_t>() == kAbsentCount)
      throw at(record_at + "/exit_status", "expected an exit status, found " + code->dump());
    result.statistics.exit_status = code->template get<std::uint64_t>();
  }
}

// A JSON record's finish_info.solutions[].cost_until_now into `result` (its status already read:
// a record stating a status without a front needs no finish_info).
template <class Json, class At>
void json_record_front(const Json& record, const std::string& record_at, const std::string& name,
                       const SolutionImportOptions& o, const At& at, ImportedResult& result) {
  const auto info = record.find("finish_info");
  const bool has_info = info != record.end() && info->is_object();
  // A solver that says its search did not succeed (A*pex's own time-out is "Failed") did not
  // finish: its solutions are a partial front, never kept, whatever else the record says (a
  // "status": "solved" beside it is a contradiction, and the failure wins).
  if (has_info && (!result.status_stated || result.status == QueryStatus::solved))
    if (const auto status = info->find("status"); status != info->end()) {
      if (!status->is_string())
        throw at(record_at + "/finish_info/status", "expected a word, found " + status->dump());
      if (status->template get<std::string>() != "Success") {
        result.statement = "finish_info.status " + status->dump() +
                           (result.status_stated ? " (beside status \"solved\")" : "");
        result.status = QueryStatus::failed;
        result.status_stated = true;
        return;
      }
    }
  const Json* solutions = nullptr;
  if (has_info)
    if (const auto found = info->find("solutions"); found != info->end() && found->is_array())
      solutions = &*found;
  // A record stating a status without a front needs no finish_info.
  if (!result.status_stated || result.status == QueryStatus::solved) {
    if (!has_info) throw at(record_at, "no 'finish_info' object");
    if (!solutions) throw at(record_at + "/finish_info", "no 'solutions' array");
  }
  const std::size_t solution_count = solutions ? solutions->size() : 0;
  std::vector<double> row;
  for (std::size_t k = 0; k < solution_count; ++k) {
    const std::string solution_at = record_at + "/finish_info/solutions/" + std::to_string(k);
    const Json& solution = (*solutions)[k];
    const auto cost = solution.is_object() ? solution.find("cost_until_now") : solution.end();
    if (!solution.is_object() || cost == solution.end() || !cost->is_array())
      throw at(solution_at, "no 'cost_until_now' array");
    row.clear();
    for (std::size_t i = 0; i < cost->size(); ++i) {
      const Json& value = (*cost)[i];
      const std::string value_at = solution_at + "/cost_until_now/" + std::to_string(i);
      if (!value.is_number()) throw at(value_at, "expected a cost, found " + value.dump());
      if (value.is_number_unsigned() && value.template get<std::uint64_t>() > kMaxExactInteger)
        throw at(value_at,
                 "the integer " + value.dump() + " is above 2^53, the largest exact integer cost");
      const double v = value.template get<double>();
      if (!std::isfinite(v)) throw at(value_at, "non-finite cost " + value.dump());
      if (v < 0) throw at(value_at, "negative cost " + value.dump());
      if (value.is_number_float())
        if (auto problem = inexact_problem(v, value.dump()); !problem.empty())
          throw at(value_at, problem);
      row.push_back(v);
    }
    if (const auto problem = width_problem(row.size(), o); !problem.empty())
      throw at(solution_at + "/cost_until_now", problem);
    append_picked(row, o, result.costs);
    result.vector_sources.push_back(name + ": " + solution_at + "/cost_until_now");
  }
}

}  // namespace

std::optional<std::string> stated_status_problem(std::string_view word, QueryStatus& status) {
  const auto parsed = parse_query_status(word);
  if (!parsed || *parsed == QueryStatus::not_run)
    return "unknown status " + quoted(word) +
           " (solved, timeout, memory-limit, disconnected, failed)";
  status = *parsed;
  return std::nullopt;
}

ImportedResult parse_front_text(std::string_view text, const std::string& name, std::uint64_t query,
                                const SolutionImportOptions& o) {
  check_options(o);
  ImportedResult result;
  result.query = query;
  result.source = name;
  text::LineScanner lines(text);
  std::string_view line;
  std::vector<double> row;
  std::vector<text::Token> words;
  while (lines.next(line)) {
    std::size_t begin = 0, end = line.size();
    while (begin < end && (line[begin] == ' ' || line[begin] == '\t')) ++begin;
    if (begin == end || line[begin] == '#') continue;
    if (line.substr(begin).starts_with("status") || line.substr(begin).starts_with("exit_status")) {
      text::tokenize(line, words);
      if (words.size() != 2 || (words[0].text != "status" && words[0].text != "exit_status"))
        fail(name, lines.number(), begin + 1,
             "expected 'status WORD' or 'exit_status N', found " + quoted(line));
      std::string problem;
      if (words[0].text == "status") {
        if (result.status_stated) fail(name, lines.number(), begin + 1, "a second status line");
        if (auto p = stated_status_problem(words[1].text, result.status)) problem = *p;
        result.status_stated = true;
      } else {
        problem = exit_status_problem(words[1].text, result.statistics.exit_status);
      }
      if (!problem.empty()) fail(name, lines.number(), words[1].column, problem);
      continue;
    }
    if (line[begin] == '[') {
      if (line[end - 1] != ']') fail(name, lines.number(), end + 1, "'[' without a closing ']'");
      ++begin;
      --end;
    }
    row.clear();
    std::size_t i = begin;
    while (true) {
      while (i < end && is_value_separator(line[i])) ++i;
      if (i >= end) break;
      const std::size_t start = i;
      while (i < end && !is_value_separator(line[i])) ++i;
      double value = 0;
      const auto problem = cost_problem(line.substr(start, i - start), value);
      if (!problem.empty()) fail(name, lines.number(), start + 1, problem);
      row.push_back(value);
    }
    if (const auto problem = width_problem(row.size(), o); !problem.empty())
      fail(name, lines.number(), begin + 1, problem);
    append_picked(row, o, result.costs);
    result.vector_sources.push_back(name + ":" + std::to_string(lines.number()));
  }
  if (!result.status_stated && result.costs.empty()) result.status = o.status_for_empty;
  if (const auto problem = stated_front_problem(result); !problem.empty())
    throw Error(ErrorCode::invalid_argument, name + ": " + problem);
  return result;
}

std::vector<ImportedResult> import_front_directory(const std::filesystem::path& directory,
                                                   const SolutionImportOptions& o) {
  check_options(o);
  std::error_code error;
  std::filesystem::directory_iterator it(directory, error);
  if (error)
    throw Error(ErrorCode::io,
                directory.string() + ": cannot list the directory: " + error.message());
  std::vector<std::filesystem::path> files;
  for (const auto& entry : it)
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());  // messages in a stable order
  std::vector<ImportedResult> results;
  std::vector<std::string> where;
  for (const auto& file : files) {
    const std::string stem = file.filename().string().substr(0, file.filename().string().find('.'));
    std::size_t last = stem.size();
    while (last > 0 && (stem[last - 1] < '0' || stem[last - 1] > '9')) --last;
    std::size_t first = last;
    while (first > 0 && stem[first - 1] >= '0' && stem[first - 1] <= '9') --first;
    if (first == last)
      throw Error(ErrorCode::invalid_argument,
                  file.string() + ": no query id in the file name (e.g. 17.txt)");
    std::uint64_t query = 0;
    if (const auto problem =
            query_problem(std::string_view(stem).substr(first, last - first), o, query);
        !problem.empty())
      throw Error(ErrorCode::invalid_argument, file.string() + ": " + problem);
    const auto input = read_text_input(file);
    results.push_back(parse_front_text(input.text, file.string(), query, o));
    where.push_back(file.string());
  }
  return by_query(std::move(results), std::move(where));
}

void apply_example_run_log(std::string_view text, const std::string& name,
                           const SolutionImportOptions& o, std::vector<ImportedResult>& results) {
  check_options(o);
  text::LineScanner lines(text);
  std::string_view line;
  std::vector<text::Token> fields;
  std::size_t next = 0;  // results[next] is the query the next line must describe
  std::uint64_t query = 0;
  for (; lines.next(line); ++query) {
    text::tokenize(line, fields);
    if (fields.size() != 5)
      fail(name, lines.number(), 1,
           "expected 'start goal front_size seconds expansions', found " +
               text::plural(fields.size(), "field"));
    if (query >= o.queries.size())
      fail(name, lines.number(), 1,
           "a line for query " + std::to_string(query) + ", the set has " +
               queries_text(o.queries.size()));
    const auto& q = o.queries[query];
    const std::uint64_t endpoints[2] = {q.start, q.goal};
    for (int i = 0; i < 2; ++i) {
      const auto id = text::to_u64(fields[i].text);
      if (!id || *id != endpoints[i])
        fail(name, lines.number(), fields[i].column,
             "query " + std::to_string(query) + " goes from " + std::to_string(q.start) + " to " +
                 std::to_string(q.goal) + ", the line says " + quoted(fields[0].text) + " " +
                 quoted(fields[1].text));
    }
    if (next >= results.size() || results[next].query != query)
      fail(name, lines.number(), 1,
           "query " + std::to_string(query) + " has a line here but no front file (" +
               std::to_string(query + o.id_base) + ".txt)");
    auto& result = results[next++];
    const auto size = text::to_u64(fields[2].text);
    // The solver finished the query and reported an empty front: the proof the file alone lacks.
    if (!result.status_stated && result.costs.empty() && size == 0u)
      result.status = QueryStatus::disconnected;
    const auto vectors = result.costs.size() / o.objective_count;
    if (!size || *size != vectors)
      fail(name, lines.number(), fields[2].column,
           "front size " + quoted(fields[2].text) + ", but query " + std::to_string(query) +
               "'s front file holds " + text::plural(vectors, "vector"));
    const auto seconds = text::to_real(fields[3].text);
    if (!seconds || !std::isfinite(*seconds) || *seconds < 0)
      fail(name, lines.number(), fields[3].column,
           "expected seconds (finite, >= 0), found " + quoted(fields[3].text));
    const auto expansions = text::to_u64(fields[4].text);
    if (!expansions)
      fail(name, lines.number(), fields[4].column,
           "expected an expansion count, found " + quoted(fields[4].text));
    if (is_completed(result.status)) {
      result.statistics.runtime_seconds = *seconds;
      result.statistics.expanded = *expansions;
    }
  }
  if (next < results.size())
    throw Error(ErrorCode::invalid_argument,
                name + ": no line for query " + std::to_string(results[next].query) +
                    ", which has a front file (" + text::plural(query, "line") + " read)");
}

std::vector<ImportedResult> parse_solution_table(std::string_view text, const std::string& name,
                                                 std::span<const std::string> names,
                                                 const SolutionImportOptions& o) {
  check_options(o);
  text::LineScanner lines(text);
  std::string_view line;
  // Fields of a line with their 1-based columns.
  char separator = ',';
  auto split = [&](std::string_view l) {
    std::vector<text::Token> fields;
    std::size_t start = 0;
    while (true) {
      auto stop = l.find(separator, start);
      if (stop == std::string_view::npos) stop = l.size();
      auto field = l.substr(start, stop - start);
      std::size_t lead = 0;
      while (lead < field.size() && (field[lead] == ' ' || field[lead] == '\t')) ++lead;
      field.remove_prefix(lead);
      while (!field.empty() && (field.back() == ' ' || field.back() == '\t'))
        field.remove_suffix(1);
      fields.push_back({field, start + lead + 1});
      if (stop == l.size()) break;
      start = stop + 1;
    }
    return fields;
  };
  bool have_header = false;
  while (lines.next(line))
    if (!line.empty()) {
      have_header = true;
      break;
    }
  if (!have_header) throw Error(ErrorCode::invalid_argument, name + ": no header line");
  if (line.find('\t') != std::string_view::npos) separator = '\t';
  const auto header = split(line);
  const std::uint64_t header_line = lines.number();
  std::size_t query_column = SIZE_MAX, status_column = SIZE_MAX, exit_column = SIZE_MAX;
  for (std::size_t k = 0; k < header.size(); ++k) {
    if (header[k].text == "query") query_column = k;
    if (header[k].text == "status") status_column = k;
    if (header[k].text == "exit_status") exit_column = k;
  }
  if (query_column == SIZE_MAX) fail(name, header_line, 1, "no 'query' column in the header");
  std::vector<std::size_t> cost_columns;
  if (!o.columns.empty()) {
    for (auto c : o.columns) {
      if (c >= header.size())
        fail(name, header_line, 1,
             {text::plural(header.size(), "column") + ", ", setting("columns"),
              " needs column " + std::to_string(c)});
      cost_columns.push_back(c);
    }
  } else {
    for (std::size_t i = 0; i < o.objective_count; ++i) {
      const std::string wanted = i < names.size() ? names[i] : std::string();
      auto found = std::find_if(header.begin(), header.end(),
                                [&](const text::Token& t) { return t.text == wanted; });
      if (found == header.end())
        fail(name, header_line, 1,
             {"no column " + quoted(wanted) + " (an objective of the view; ", setting("columns"),
              " picks columns by position)"});
      cost_columns.push_back(static_cast<std::size_t>(found - header.begin()));
    }
  }
  std::map<std::uint64_t, ImportedResult> results;
  while (lines.next(line)) {
    if (line.empty()) continue;
    const auto fields = split(line);
    if (fields.size() != header.size())
      fail(name, lines.number(), line.size() + 1,
           text::plural(fields.size(), "field") + ", the header has " +
               std::to_string(header.size()));
    std::uint64_t query = 0;
    const auto& qf = fields[query_column];
    if (const auto problem = query_problem(qf.text, o, query); !problem.empty())
      fail(name, lines.number(), qf.column, problem);
    const bool first_row = !results.contains(query);
    auto& result = results[query];
    result.query = query;
    result.source = name + ":" + std::to_string(lines.number());
    table_row_status(name, lines.number(), fields, status_column, exit_column, first_row, result);
    if (result.status != QueryStatus::solved) {
      for (auto c : cost_columns)
        if (!fields[c].text.empty())
          fail(name, lines.number(), fields[c].column,
               "a cost for a " + std::string(to_string(result.status)) +
                   " query (only a solved query has a front; leave the field empty)");
      continue;
    }
    for (auto c : cost_columns) {
      double value = 0;
      if (const auto problem = cost_problem(fields[c].text, value); !problem.empty())
        fail(name, lines.number(), fields[c].column, problem);
      result.costs.push_back(value);
    }
    result.vector_sources.push_back(name + ":" + std::to_string(lines.number()));
  }
  std::vector<ImportedResult> sorted;
  sorted.reserve(results.size());
  for (auto& [query, result] : results) sorted.push_back(std::move(result));
  return sorted;
}

namespace {

// A 0-based byte offset of the text as FILE:LINE:COLUMN.
[[noreturn]] void fail_at_offset(std::string_view text, const std::string& name, std::size_t at,
                                 const std::string& message) {
  at = std::min(at, text.size());
  const auto before = text.substr(0, at);
  const std::uint64_t line = 1 + std::count(before.begin(), before.end(), '\n');
  const auto line_start = before.rfind('\n');
  const std::uint64_t column = at - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
  fail(name, line, column, message);
}

// A text that must be an array of records and is not.
struct NotAnArray {};

// A key given twice in one object: nlohmann keeps the last silently, so `"status": "failed",
// "status": "solved"` would read as solved. Thrown by the parser callback below.
struct DuplicateKey {
  std::string key;
  std::size_t occurrence = 0;  // of the quoted key in the whole text, 1-based
};

// A JSON value built from nlohmann's SAX events, refusing a key given twice in one object; with
// `element`, the value must be an array whose elements are handed over one by one as each is
// read, then dropped. (nlohmann's callback parser, which could drop them too, scans an object's
// parent at the end of each object: quadratic in a front of object vectors, a minute for a 57 MB
// log; its DOM of the whole log took ~14 times the text.)
class JsonBuilder {
 public:
  using Json = nlohmann::json;
  using Element = std::function<void(const Json&, std::size_t)>;
  explicit JsonBuilder(const Element& element) : element_(element) {}
  Json& root() { return root_; }

  bool null() { return add(Json(nullptr)); }
  bool boolean(bool value) { return add(Json(value)); }
  bool number_integer(Json::number_integer_t value) { return add(Json(value)); }
  bool number_unsigned(Json::number_unsigned_t value) { return add(Json(value)); }
  bool number_float(Json::number_float_t value, const Json::string_t&) { return add(Json(value)); }
  bool string(Json::string_t& value) { return add(Json(std::move(value))); }
  bool binary(Json::binary_t& value) { return add(Json::binary(std::move(value))); }
  bool start_object(std::size_t) {
    if (element_ && stack_.empty()) throw NotAnArray{};
    keys_.emplace_back();
    return open(Json::object());
  }
  bool key(Json::string_t& key) {
    const auto occurrence = ++seen_[key];
    if (!keys_.back().insert(key).second) throw DuplicateKey{key, occurrence};
    key_ = std::move(key);
    return true;
  }
  bool end_object() {
    keys_.pop_back();
    return close();
  }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool end_array() { return close(); }
  template <class Exception>
  bool parse_error(std::size_t, const std::string&, const Exception& error) {
    throw error;
  }

 private:
  // Places a value where the containers being read put it; returns where it went.
  Json* place(Json&& value) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    auto& parent = *stack_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return &parent.back();
    }
    auto& slot = parent[key_];
    slot = std::move(value);
    return &slot;
  }
  bool add(Json&& value) {
    place(std::move(value));
    hand_over();
    return true;
  }
  bool open(Json&& container) {
    stack_.push_back(place(std::move(container)));
    return true;
  }
  bool close() {
    stack_.pop_back();
    hand_over();
    return true;
  }
  // A whole element of the top-level array, to `element_`, then dropped.
  void hand_over() {
    if (!element_ || stack_.size() != 1) return;
    auto& array = *stack_.front();
    element_(array.back(), elements_++);
    array.erase(array.size() - 1);
  }

  const Element& element_;
  Json root_;
  std::vector<Json*> stack_;                 // the containers being read, outermost first
  std::string key_;                          // of the next value of the innermost object
  std::vector<std::set<std::string>> keys_;  // of each object being read, outermost first
  std::map<std::string, std::size_t> seen_;  // times each key appeared anywhere
  std::size_t elements_ = 0;
};

// The JSON text parsed; a syntax error is FILE:LINE:COLUMN: invalid JSON: REASON, and so is a key
// given twice in one object. With `element`, the text must be an array, each of whose elements is
// handed to `element` (with its index) as soon as it is read, then dropped (JsonBuilder): a log is
// read in the memory of its text and one record. The value returned is then the empty array.
nlohmann::json parse_json_text(std::string_view text, const std::string& name,
                               const JsonBuilder::Element& element = {}) {
  using Json = nlohmann::json;
  try {
    JsonBuilder builder(element);
    Json::sax_parse(text.begin(), text.end(), &builder);
    if (element && !builder.root().is_array()) throw NotAnArray{};
    return std::move(builder.root());
  } catch (const DuplicateKey& d) {
    // The key's position: its occurrence-th appearance as a quoted string (an escaped key, rare,
    // is located at the text's start).
    const auto quoted = Json(d.key).dump();
    std::size_t at = std::string_view::npos;
    for (std::size_t n = 0, from = 0; n < d.occurrence; ++n, from = at + 1)
      if ((at = text.find(quoted, from)) == std::string_view::npos) break;
    fail_at_offset(text, name, at == std::string_view::npos ? 0 : at,
                   "invalid JSON: the key " + quoted + " twice in one object");
  } catch (const Json::parse_error& e) {
    std::string what = e.what();
    // nlohmann's message: "[json.exception.parse_error.101] parse error at ...: REASON"
    if (const auto reason = what.rfind(": "); reason != std::string::npos)
      what = what.substr(reason + 2);
    // e.byte is 1-based, at the offending character.
    fail_at_offset(text, name, e.byte == 0 ? 0 : e.byte - 1, "invalid JSON: " + what);
  } catch (const Json::out_of_range& e) {
    // A number too large for any JSON number type: "... number overflow parsing 'DIGITS'". The
    // error carries no position, so the number's first occurrence locates it.
    std::string what = e.what();
    if (const auto tag = what.find("] "); tag != std::string::npos) what = what.substr(tag + 2);
    const auto quote = what.find('\'');
    const auto number = quote == std::string::npos
                            ? std::string()
                            : what.substr(quote + 1, what.rfind('\'') - quote - 1);
    const auto found = number.empty() ? std::string_view::npos : text.find(number);
    fail_at_offset(text, name, found == std::string_view::npos ? 0 : found,
                   "invalid JSON: " + what);
  }
}

using Endpoints = std::multimap<std::pair<std::uint64_t, std::uint64_t>, std::uint64_t>;

// The query record `r` answers: by position, or by its endpoints (`by_endpoints`, each query
// taken once, repeated endpoints in order).
template <class Json, class At>
std::uint64_t json_record_query(const Json& record, std::size_t r, const std::string& record_at,
                                const SolutionImportOptions& o, Endpoints& by_endpoints,
                                const At& at) {
  auto endpoint = [&](const char* key) -> std::uint64_t {
    const auto field = record.find(key);
    if (field == record.end()) throw at(record_at, std::string("no '") + key + "'");
    if (!field->is_number_unsigned())
      throw at(record_at + "/" + key, "expected a vertex id, found " + field->dump());
    const auto id = field->template get<std::uint64_t>();
    if (id < o.id_base || id - o.id_base >= o.vertex_count)
      throw at(record_at + "/" + key, "vertex id " + std::to_string(id) + " outside " +
                                          std::to_string(o.id_base) + ".." +
                                          std::to_string(o.vertex_count - 1 + o.id_base));
    return id - o.id_base;
  };
  const auto source = endpoint("source"), target = endpoint("target");
  if (o.match == RecordMatch::position) {
    if (r >= o.queries.size())
      throw at(record_at, "record " + std::to_string(r) + ", but the set has " +
                              queries_text(o.queries.size()));
    if (o.queries[r].start != source || o.queries[r].goal != target)
      throw at(record_at, "source " + std::to_string(source + o.id_base) + " and target " +
                              std::to_string(target + o.id_base) + ", but query " +
                              std::to_string(r) + " runs from " +
                              std::to_string(o.queries[r].start + o.id_base) + " to " +
                              std::to_string(o.queries[r].goal + o.id_base));
    return r;
  }
  auto [first, last] = by_endpoints.equal_range({source, target});
  if (first == last)
    throw at(record_at, "source " + std::to_string(source + o.id_base) + " and target " +
                            std::to_string(target + o.id_base) +
                            " are no query of the set (or every such query has a record)");
  const auto query = first->second;
  by_endpoints.erase(first);
  return query;
}

// `total_runtime(ms)`, kept only for a finished query: an interrupted or failed run carries no
// runtime (SOLUTIONS.md §4), so the log's is dropped.
template <class Json, class At>
void json_record_runtime(const Json& record, const std::string& record_at, const At& at,
                         ImportedResult& result) {
  const bool keeps_runtime = is_completed(result.status);
  const auto runtime = record.find("total_runtime(ms)");
  if (!keeps_runtime || runtime == record.end()) return;
  const std::string runtime_at = record_at + "/total_runtime(ms)";
  if (!runtime->is_number())
    throw at(runtime_at, "expected milliseconds, found " + runtime->dump());
  const double ms = runtime->template get<double>();
  if (!std::isfinite(ms) || ms < 0) throw at(runtime_at, "invalid runtime " + runtime->dump());
  result.statistics.runtime_seconds = ms / 1000.0;
}

}  // namespace

std::vector<ImportedResult> parse_solver_json_log(std::string_view text, const std::string& name,
                                                  const SolutionImportOptions& o) {
  check_options(o);
  // `message`: a std::string, or parts that name settings.
  auto at = [&](const std::string& pointer, const auto& message) -> Error {
    return Error(ErrorCode::invalid_argument, message).with_context(name + ": " + pointer + ": ");
  };
  Endpoints by_endpoints;
  if (o.match == RecordMatch::endpoints)
    for (std::uint64_t q = 0; q < o.queries.size(); ++q)
      by_endpoints.emplace(
          std::pair<std::uint64_t, std::uint64_t>(o.queries[q].start, o.queries[q].goal), q);
  std::vector<ImportedResult> results;
  std::vector<std::string> where;
  const auto read_record = [&](const nlohmann::json& record, std::size_t r) {
    const std::string record_at = "/" + std::to_string(r);
    if (!record.is_object()) throw at(record_at, "expected an object");
    ImportedResult result;
    result.query = json_record_query(record, r, record_at, o, by_endpoints, at);
    result.source = name + ": " + record_at;
    json_record_status(record, record_at, at, result);
    json_record_front(record, record_at, name, o, at, result);
    if (!result.status_stated && result.costs.empty()) result.status = QueryStatus::disconnected;
    if (const auto problem = stated_front_problem(result); !problem.empty())
      throw at(record_at, problem);
    json_record_runtime(record, record_at, at, result);
    results.push_back(std::move(result));
    where.push_back(name + ": " + record_at);
  };
  try {
    parse_json_text(text, name, read_record);
  } catch (const NotAnArray&) {
    throw at("/", "expected an array of records");
  }
  return by_query(std::move(results), std::move(where));
}

namespace {

// The vectors of `r` to keep: all of them, or (keep_optimal) its non-dominated subset. Throws for
// a dominated or repeated vector under `refuse`, naming both and where they came from.
std::vector<double> kept_costs(const ImportedResult& r, std::size_t d, DominatedVectors policy,
                               std::uint64_t& dropped) {
  const auto drop = dominated_rows(r.costs, d);
  if (drop.empty()) return r.costs;
  if (policy == DominatedVectors::refuse) {
    const auto pair = *first_dominated_row(r.costs, d);
    const auto source = [&](std::size_t row) {
      return row < r.vector_sources.size() ? r.vector_sources[row] : r.source;
    };
    throw Error(ErrorCode::invalid_argument,
                {source(pair.dominated) + ": query " + std::to_string(r.query) + ": " +
                     dominated_row_text(r.costs, d, pair) + " (at " + source(pair.by) + "); give ",
                 setting("dominated"), " to keep each front's non-dominated vectors"});
  }
  std::vector<double> kept;
  kept.reserve(r.costs.size() - drop.size() * d);
  for (std::size_t row = 0, next = 0; row < r.costs.size() / d; ++row) {
    if (next < drop.size() && drop[next] == row) {
      ++next;
      continue;
    }
    kept.insert(kept.end(), r.costs.begin() + static_cast<std::ptrdiff_t>(row * d),
                r.costs.begin() + static_cast<std::ptrdiff_t>((row + 1) * d));
  }
  dropped += drop.size();
  return kept;
}

}  // namespace

DroppedVectors set_imported_results(SolutionWriter& writer, std::span<const ImportedResult> results,
                                    DominatedVectors dominated) {
  const std::size_t d = writer.objective_count();
  DroppedVectors drops;
  for (const auto& r : results) {
    for (std::size_t k = 0; k < r.costs.size(); ++k)
      if (const auto problem = writer.cost_problem(k % d, r.costs[k]))
        throw Error(ErrorCode::invalid_argument,
                    (k / d < r.vector_sources.size() ? r.vector_sources[k / d] : r.source) +
                        ": query " + std::to_string(r.query) + ", objective '" +
                        writer.objective_names()[k % d] + "': " + *problem);
    const std::uint64_t before = drops.vectors;
    const auto costs = r.costs.size() % d == 0 ? kept_costs(r, d, dominated, drops.vectors)
                                               : r.costs;  // the writer refuses it below
    if (drops.vectors != before) ++drops.queries;
    try {
      writer.set_query(r.query, r.status, costs, r.statistics);
    } catch (const Error& e) {
      if (r.source.empty()) throw;
      throw e.with_context(r.source + ": ");
    }
  }
  if (dominated == DominatedVectors::keep_optimal) writer.set_dropped_vectors(drops);
  return drops;
}

}  // namespace mosb::converters
