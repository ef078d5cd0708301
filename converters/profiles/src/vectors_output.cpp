// The `vectors` output of a solver profile (spec/RUN.md §10.4): a per-query file (or stdout) whose
// lines hold the front's cost vectors in the solver's own notation, with lines that state a
// status, a line whose absence means the search did not finish, and a runtime line.
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "mosb/converters/profile_run.hpp"
#include "mosb/converters/solver_output.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/error.hpp"
#include "placeholders.hpp"

namespace mosb::converters {

namespace {

constexpr std::uint64_t kExactLimit = std::uint64_t{1} << 53;

// A solver's output files, each read once when a rule needs it.
class OutputTexts {
 public:
  OutputTexts(const SolverOutputFiles& files, std::string front_path)
      : files_(files), front_path_(std::move(front_path)) {}

  const std::string& path(OutputFile file) const {
    switch (file) {
      case OutputFile::front:
        return front_path_;
      case OutputFile::stdout_file:
        return files_.stdout_path;
      case OutputFile::stderr_file:
        break;
    }
    return files_.stderr_path;
  }
  const std::string& text(OutputFile file) {
    auto& slot = texts_[static_cast<std::size_t>(file)];
    if (!slot) slot = read_text_input(path(file), files_.output_bytes).text;
    return *slot;
  }

 private:
  const SolverOutputFiles& files_;
  std::string front_path_;
  std::array<std::optional<std::string>, 3> texts_;
};

// Calls `line(text, number)` for each line of `text`, without its `\r\n` or `\n`.
template <class Line>
void for_each_line(const std::string& text, Line&& line) {
  std::size_t start = 0, number = 1;
  while (start < text.size()) {
    auto end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view view(text.data() + start, end - start);
    if (!view.empty() && view.back() == '\r') view.remove_suffix(1);
    line(view, number++);
    start = end + 1;
  }
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

bool applies(const OutputLine& rule, const VectorsContext& context) {
  if (rule.when_option.empty()) return true;
  const auto value = context.options.find(rule.when_option);
  return value != context.options.end() && value->second == rule.when_value;
}

// An integer written as digits, optionally with a fraction of zeros (`59.000000`): exact.
std::optional<std::uint64_t> exact_integer(std::string_view text) {
  const auto dot = text.find('.');
  const auto digits = text.substr(0, dot);
  if (dot != std::string_view::npos)
    for (const char c : text.substr(dot + 1))
      if (c != '0') return std::nullopt;
  std::uint64_t value = 0;
  const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || r.ec != std::errc() || r.ptr != digits.data() + digits.size() ||
      value > kExactLimit)
    return std::nullopt;
  return value;
}

// The values of one vector line: the text after the prefix, or its `group`-th [...].
std::string_view vector_text(std::string_view line, const ProfileOutput& out,
                             const std::string& where) {
  if (out.group == 0) return line.substr(out.prefix.size());  // the prefix only picks the line
  std::size_t at = 0;
  for (unsigned g = 1;; ++g) {
    const auto open = line.find('[', at);
    const auto close = open == std::string_view::npos ? open : line.find(']', open);
    if (close == std::string_view::npos)
      throw Error(where + ": no bracketed group " + std::to_string(out.group));
    if (g == out.group) return line.substr(open + 1, close - open - 1);
    at = close + 1;
  }
}

void read_vector(std::string_view line, const ProfileOutput& out, const VectorsContext& context,
                 const SolverOutputFiles& files, const std::string& where,
                 std::vector<double>& costs) {
  auto text = vector_text(line, out, where);
  std::vector<std::string_view> values;
  for (std::size_t start = 0;;) {
    const auto end = text.find(out.separator, start);
    values.push_back(
        trimmed(text.substr(start, end == std::string_view::npos ? end : end - start)));
    if (end == std::string_view::npos) break;
    start = end + out.separator.size();
  }
  if (out.separator == " ")  // blanks: runs of them are one separator
    std::erase_if(values, [](std::string_view v) { return v.empty(); });
  else if (out.trailing_separator && values.size() > 1 && values.back().empty())
    values.pop_back();
  const std::size_t columns = std::max<std::size_t>(context.objectives, context.padded_columns);
  if (values.size() != columns)
    throw Error(where + ": " + std::to_string(values.size()) + " values, expected " +
                std::to_string(columns));
  for (std::size_t k = 0; k < columns; ++k) {
    const auto v = values[k];
    const auto name = "value " + std::to_string(k + 1) + " '" + std::string(v) + "'";
    if (k >= context.objectives) {  // a padding column the text had as 0
      if (exact_integer(v) != 0u)
        throw Error(where + ": " + name + " of a padding column is not 0");
      continue;
    }
    const bool integer =
        context.scaled[k] || (k < files.integer_objectives.size() && files.integer_objectives[k]);
    if (integer) {
      const auto value = exact_integer(v);
      if (!value) throw Error(where + ": " + name + " is not an integer in [0, 2^53]");
      costs.push_back(context.scaled[k] ? static_cast<double>(*value) / context.scale
                                        : static_cast<double>(*value));
      continue;
    }
    double value = 0;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), value);
    if (v.empty() || r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(value))
      throw Error(where + ": " + name + " is not a finite number");
    costs.push_back(value);
  }
}

// The text of `rule`'s field on the first line that has its prefix, trimmed, and where it is
// ("PATH:LINE"); nullopt when no line has the prefix.
std::optional<std::pair<std::string, std::string>> read_field(const OutputField& rule,
                                                              OutputTexts& texts) {
  std::optional<std::pair<std::string, std::string>> found;
  const auto& path = texts.path(rule.file);
  for_each_line(texts.text(rule.file), [&](std::string_view line, std::size_t number) {
    if (found || line.substr(0, rule.prefix.size()) != rule.prefix) return;
    const auto where = path + ":" + std::to_string(number);
    auto value = line.substr(rule.prefix.size());
    if (rule.field > 0) {
      for (unsigned f = 1; f < rule.field; ++f) {
        const auto at = line.find(rule.separator);
        if (at == std::string_view::npos)
          throw Error(where + ": no field " + std::to_string(rule.field) + " in the line");
        line.remove_prefix(at + rule.separator.size());
      }
      value = line.substr(0, line.find(rule.separator));
    }
    found.emplace(std::string(trimmed(value)), where);
  });
  return found;
}

std::optional<double> read_runtime(const OutputRuntime& rule, OutputTexts& texts) {
  const auto field = read_field(rule, texts);
  if (!field) return std::nullopt;
  const auto& [value, where] = *field;
  double x = 0;
  const auto r = std::from_chars(value.data(), value.data() + value.size(), x);
  if (value.empty() || r.ec != std::errc() || r.ptr != value.data() + value.size() ||
      !std::isfinite(x) || x < 0)
    throw Error(where + ": runtime '" + value + "' is not a number of seconds");
  return x * rule.unit_seconds;
}

// The solver's own count of its front against the vectors read: a query whose output holds
// another number of vectors (none, from a T-MDA built without its front printing) fails.
void check_count(const OutputField& rule, OutputTexts& texts, std::uint64_t vectors) {
  const auto field = read_field(rule, texts);
  if (!field) return;  // no such line: `finished` says whether the search ended
  const auto& [value, where] = *field;
  std::uint64_t count = 0;
  const auto r = std::from_chars(value.data(), value.data() + value.size(), count);
  if (value.empty() || r.ec != std::errc() || r.ptr != value.data() + value.size())
    throw Error(where + ": the count of solutions '" + value + "' is not a whole number");
  if (count != vectors)
    throw Error(where + ": the solver says it found " + value + " solutions, its output holds " +
                std::to_string(vectors) + " vectors");
}

}  // namespace

ParsedOutput read_vectors_output(const SolverOutputFiles& files, const ProfileOutput& output,
                                 const VectorsContext& context) {
  const auto fill = [&](const std::string& name) -> std::optional<std::string> {
    if (name == "front") return files.front_path;
    if (name == "fronts") return files.fronts_dir;
    if (name == "source") return std::to_string(std::uint64_t{files.query.start} + context.id_base);
    if (name == "target") return std::to_string(std::uint64_t{files.query.goal} + context.id_base);
    return std::nullopt;
  };
  const std::string front_path = output.file == "stdout" ? files.stdout_path
                                                         : profile_internal::expand_placeholders(
                                                               output.file, fill, "output.file");
  OutputTexts texts(files, front_path);
  for (const auto& rule : output.status_lines) {
    if (!applies(rule, context)) continue;
    bool found = false;
    for_each_line(texts.text(rule.file),
                  [&](std::string_view line, std::size_t) { found |= trimmed(line) == rule.text; });
    if (found)
      return stated_output(rule.status, texts.path(rule.file) + " says '" + rule.text + "'");
  }
  for (const auto& rule : output.finished) {
    if (!applies(rule, context)) continue;
    bool found = false;
    for_each_line(texts.text(rule.file), [&](std::string_view line, std::size_t) {
      found |= line.substr(0, rule.text.size()) == rule.text;
    });
    if (!found)
      return stated_output(output.unfinished, texts.path(rule.file) +
                                                  " has no line starting with '" + rule.text +
                                                  "': the search did not finish");
  }
  ParsedOutput out;
  for_each_line(texts.text(OutputFile::front), [&](std::string_view line, std::size_t number) {
    if (line.substr(0, output.prefix.size()) != output.prefix || trimmed(line).empty()) return;
    read_vector(line, output, context, files, front_path + ":" + std::to_string(number), out.costs);
    if (out.costs.size() > files.output_bytes / 8)
      throw Error(front_path + ": a front of more than " + std::to_string(files.output_bytes / 8) +
                  " values");
  });
  out.vectors = context.objectives == 0 ? 0 : out.costs.size() / context.objectives;
  if (output.runtime) out.statistics.runtime_seconds = read_runtime(*output.runtime, texts);
  if (output.count) check_count(*output.count, texts, out.vectors);
  return out;
}

}  // namespace mosb::converters
