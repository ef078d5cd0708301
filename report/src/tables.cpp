#include "mosb/report/tables.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "mosb/internal/number_text.hpp"
#include "mosb/report/svg.hpp"

namespace mosb::tables {
namespace {

std::string shortest(double x) {
  if (std::isinf(x)) return "inf";
  return shortest_text(x);
}

// `digits` significant digits, never an exponent for a number of `digits` or more digits before
// the point: those are written whole (rounded to an integer; a front size is never 6.4e+03), the
// thousands separated by `separator` from 1,000 on when it is not empty.
std::string significant(double x, int digits, std::string_view separator = {}) {
  if (std::isfinite(x) && std::abs(x) >= std::pow(10.0, digits - 1) && std::abs(x) < 1e18) {
    const auto whole = std::to_string(std::llabs(std::llround(x)));
    std::string out = x < 0 ? "-" : "";
    for (std::size_t i = 0; i < whole.size(); ++i) {
      if (i > 0 && (whole.size() - i) % 3 == 0) out += separator;
      out += whole[i];
    }
    return out;
  }
  std::array<char, 48> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "%.*g", digits, x);
  return buffer.data();
}

// A count as LaTeX shows it: thousands separated by {,} (a comma that adds no space in math).
std::string latex_count(std::uint64_t n) {
  return significant(static_cast<double>(n), 1, "{,}");
}

// The one CSV field writer (RFC 4180, and OWASP's guard against formulas: tables.hpp).
std::string csv_field(std::string_view s) {
  const bool formula = !s.empty() && std::string_view("=+-@\t\r").find(s.front()) != s.npos;
  const bool quoted = formula || s.find_first_of(",\"\r\n") != std::string_view::npos;
  std::string out = formula ? "\"'" : quoted ? "\"" : "";
  for (const char c : s) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\t' && c != '\r' && c != '\n') || byte == 0x7f) {
      out += "\xEF\xBF\xBD";  // U+FFFD: no control character reaches a file or a terminal
      continue;
    }
    if (c == '"') out += '"';
    out += c;
  }
  return quoted ? out + '"' : out;
}

std::string csv_cell(const Cell& c) {
  switch (c.kind) {
    case Cell::Kind::text:
      return csv_field(c.text);
    case Cell::Kind::count:
      return std::to_string(c.count);
    case Cell::Kind::real:
      return shortest(c.real);
    case Cell::Kind::absent:
      break;
  }
  return {};
}

std::string latex_cell(const Cell& c) {
  switch (c.kind) {
    case Cell::Kind::text:
      return latex_escape(c.text);
    case Cell::Kind::count:
      return c.count < (std::uint64_t{1} << 53) ? latex_count(c.count) : std::to_string(c.count);
    case Cell::Kind::real:
      return std::isinf(c.real) ? "$\\infty$" : significant(c.real, 3, "{,}");
    case Cell::Kind::absent:
      break;
  }
  return "--";
}

std::string text_cell(const Cell& c) {
  switch (c.kind) {
    case Cell::Kind::text:
      return c.text;
    case Cell::Kind::count:
      return std::to_string(c.count);
    case Cell::Kind::real:
      return std::isinf(c.real) ? "inf" : significant(c.real, 4);
    case Cell::Kind::absent:
      break;
  }
  return "-";
}

Cell optional_real(const std::optional<Distribution>& d, double Distribution::*field) {
  return d ? Cell::of((*d).*field) : Cell{};
}

std::string status_key(QueryStatus s) {
  std::string key(to_string(s));
  std::replace(key.begin(), key.end(), '-', '_');
  return key;
}

}  // namespace

namespace {

// The code point of the UTF-8 sequence at text[at] and its length; nullopt for a byte that starts
// no valid sequence (a stray continuation, an overlong or truncated one).
std::optional<std::pair<char32_t, std::size_t>> utf8_at(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[at + k]); };
  const unsigned char lead = byte(0);
  const std::size_t length = lead >= 0xF0 && lead < 0xF5   ? 4
                             : lead >= 0xE0                ? 3
                             : lead >= 0xC2 && lead < 0xE0 ? 2
                                                           : 0;
  if (length == 0 || at + length > text.size()) return std::nullopt;
  char32_t cp = lead & (0x7F >> length);
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(k) & 0xC0) != 0x80) return std::nullopt;
    cp = (cp << 6) | (byte(k) & 0x3F);
  }
  const char32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < smallest[length] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return std::nullopt;
  return std::pair{cp, length};
}

// A code point beyond ASCII as pdflatex (utf8 input, the default encodings) typesets it: Latin-1
// letters as they are; Greek letters, dashes, × and … as their commands (a profile's default
// name says "ε=0.05"); anything else as \textbackslash{}uXXXX, so that no table fails to compile.
std::string latex_code_point(char32_t cp, std::string_view bytes) {
  static constexpr const char* kGreek[] = {
      "alpha", "beta",   "gamma",   "delta", "varepsilon", "zeta", "eta",  "theta", "iota",
      "kappa", "lambda", "mu",      "nu",    "xi",         "o",    "pi",   "rho",   "varsigma",
      "sigma", "tau",    "upsilon", "phi",   "chi",        "psi",  "omega"};
  if (cp >= 0xA0 && cp <= 0xFF && cp != 0xD7 && cp != 0xF7) return std::string(bytes);
  if (cp >= 0x3B1 && cp <= 0x3C9 && cp != 0x3BF)
    return std::string("\\ensuremath{\\") + kGreek[cp - 0x3B1] + "}";
  switch (cp) {
    case 0xD7:
      return "\\ensuremath{\\times}";
    case 0xF7:
      return "\\ensuremath{\\div}";
    case 0x3BF:
      return "o";
    case 0x2013:
      return "--";
    case 0x2014:
      return "---";
    case 0x2026:
      return "\\ldots{}";
    case 0x2212:
      return "\\ensuremath{-}";
    default:
      break;
  }
  char hex[16];
  std::snprintf(hex, sizeof hex, "u%04X", static_cast<unsigned>(cp));
  return std::string("\\textbackslash{}") + hex;
}

}  // namespace

std::string latex_escape(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x80) {
      if (const auto decoded = utf8_at(text, i)) {
        out += latex_code_point(decoded->first, text.substr(i, decoded->second));
        i += decoded->second - 1;
        continue;
      }
    }
    if (byte < 0x20 || byte >= 0x7f) {  // a control character, or a byte of no UTF-8 sequence
      std::array<char, 8> hex{};
      std::snprintf(hex.data(), hex.size(), "x%02X", byte);
      out += std::string("\\textbackslash{}") + hex.data();
      continue;
    }
    switch (c) {
      case '\\':
        out += "\\textbackslash{}";
        break;
      case '~':
        out += "\\textasciitilde{}";
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      case '<':
        out += "\\textless{}";
        break;
      case '>':
        out += "\\textgreater{}";
        break;
      case '|':
        out += "\\textbar{}";
        break;
      case '[':  // braced: never the optional argument of the row's \\ before it
      case ']':
        out += std::string("{") + c + "}";
        break;
      case '&':
      case '%':
      case '$':
      case '#':
      case '_':
      case '{':
      case '}':
        out += '\\';
        out += c;
        break;
      default:
        out += c;
    }
  }
  return out;
}

Column coverage_column(Coverage what, std::string_view label) {
  static constexpr std::string_view kKey[] = {"covered", "not_covered", "dominated"};
  static constexpr std::string_view kLatex[] = {"cov.", "not cov.", "dom."};
  static constexpr std::string_view kHtml[] = {"covered", "not covered", "dominated"};
  const auto i = static_cast<std::size_t>(what);
  const std::string e(label);
  return {std::string(kKey[i]) + "@" + e,
          std::string(kLatex[i]) + "\\ $\\varepsilon{=}" + latex_escape(e) + "$",
          std::string(kHtml[i]) + " at ε = " + e};
}

void write_csv(std::ostream& out, const Table& table) {
  for (std::size_t i = 0; i < table.columns.size(); ++i)
    out << (i ? "," : "") << csv_field(table.columns[i].key);
  out << "\r\n";
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << csv_cell(row[i]);
    out << "\r\n";
  }
}

void write_latex(std::ostream& out, const Table& table) {
  if (!table.caption.empty()) out << "% " << latex_escape(table.caption) << '\n';
  // Text columns (names, ranges) left, numbers right.
  std::string align;
  for (std::size_t i = 0; i < table.columns.size(); ++i) {
    const bool text =
        i == 0 || std::any_of(table.rows.begin(), table.rows.end(),
                              [&](const auto& r) { return r.at(i).kind == Cell::Kind::text; });
    align += text ? 'l' : 'r';
  }
  out << "\\begin{tabular}{" << align << "}\n\\toprule\n";
  if (!table.groups.empty()) {
    std::size_t column = 0;
    std::string rules;
    for (const auto& g : table.groups) {
      for (; column < g.first; ++column) out << (column ? " & " : "");
      out << (column ? " & " : "") << "\\multicolumn{" << g.count << "}{c}{"
          << latex_escape(g.title) << "}";
      rules += "\\cmidrule(lr){" + std::to_string(g.first + 1) + "-" +
               std::to_string(g.first + g.count) + "}";
      column = g.first + g.count;
    }
    for (; column < table.columns.size(); ++column) out << " & ";
    out << " \\\\\n" << rules << "\n";
  }
  for (std::size_t i = 0; i < table.columns.size(); ++i)
    out << (i ? " & " : "") << table.columns[i].latex;
  out << " \\\\\n\\midrule\n";
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? " & " : "") << latex_cell(row[i]);
    out << " \\\\\n";
  }
  out << "\\bottomrule\n\\end{tabular}\n";
}

void write_json(std::ostream& out, const Table& table) {
  auto rows = nlohmann::ordered_json::array();
  for (const auto& row : table.rows) {
    auto& object = rows.emplace_back(nlohmann::ordered_json::object());
    for (std::size_t k = 0; k < table.columns.size(); ++k) {
      const auto& cell = row.at(k);
      auto& value = object[table.columns[k].key];  // null unless set below
      if (cell.kind == Cell::Kind::text) value = cell.text;
      if (cell.kind == Cell::Kind::count) value = cell.count;
      if (cell.kind == Cell::Kind::real && std::isfinite(cell.real)) value = cell.real;
    }
  }
  nlohmann::ordered_json document;
  document["caption"] = table.caption;
  document["rows"] = std::move(rows);
  out << document.dump() << '\n';
}

void write_text(std::ostream& out, const Table& table) {
  std::vector<std::vector<std::string>> cells{{}};
  for (const auto& c : table.columns) cells[0].push_back(c.key);
  for (const auto& row : table.rows) {
    cells.emplace_back();
    for (const auto& c : row) cells.back().push_back(text_cell(c));
  }
  std::vector<std::size_t> width(table.columns.size(), 0);
  for (const auto& row : cells)
    for (std::size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
  if (!table.caption.empty()) out << table.caption << '\n';
  for (const auto& row : cells) {
    std::string line;
    for (std::size_t i = 0; i < row.size(); ++i) {
      // The first column (a name) is left-aligned, numbers right-aligned.
      const std::string pad(width[i] - row[i].size(), ' ');
      line += (i ? "  " : "") + (i ? pad + row[i] : row[i] + pad);
    }
    line.erase(line.find_last_not_of(' ') + 1);
    out << line << '\n';
  }
}

void write_html(std::ostream& out, const Table& table, const std::string& id) {
  out << R"(<table class="sortable" id=")" << plots::Svg::escape(id) << "\">\n";
  if (!table.caption.empty())
    out << "<caption>" << plots::Svg::escape(table.caption) << "</caption>\n";
  out << "<thead>";
  if (!table.groups.empty()) {  // the groups' heads, over empty cells where there is none
    out << "<tr>";
    std::size_t column = 0;
    for (const auto& g : table.groups) {
      for (; column < g.first; ++column) out << "<th></th>";
      out << R"(<th scope="colgroup" colspan=")" << g.count << "\">" << plots::Svg::escape(g.title)
          << "</th>";
      column = g.first + g.count;
    }
    for (; column < table.columns.size(); ++column) out << "<th></th>";
    out << "</tr>\n";
  }
  out << "<tr>";
  for (const auto& c : table.columns)
    out << R"(<th scope="col" data-key=")" << plots::Svg::escape(c.key) << "\">"
        << plots::Svg::escape(c.html.empty() ? c.key : c.html) << "</th>";
  out << "</tr></thead>\n<tbody>\n";
  for (const auto& row : table.rows) {
    out << "<tr>";
    for (const auto& c : row) {
      if (c.kind == Cell::Kind::text) {
        out << "<td>" << plots::Svg::escape(c.text) << "</td>";
        continue;
      }
      const std::string exact = c.kind == Cell::Kind::absent ? std::string() : csv_cell(c);
      out << R"(<td class="n" data-v=")" << exact << "\">" << plots::Svg::escape(text_cell(c))
          << "</td>";
    }
    out << "</tr>\n";
  }
  out << "</tbody>\n</table>\n";
}

Table comparison_summary(const SolverComparison& comparison,
                         std::span<const std::string> epsilon_labels, bool for_paper) {
  // A paper's table keeps what the paper's comparison table shows: outcomes, coverage, runtimes.
  const auto shown = [for_paper](QueryStatus s) {
    return !for_paper || (s != QueryStatus::disconnected && s != QueryStatus::not_run);
  };
  Table t;
  t.columns = {{"solver", "Solver"}};
  for (const auto status : kQueryStatuses) {
    if (shown(status)) t.columns.push_back({status_key(status), latex_escape(to_string(status))});
  }
  if (!for_paper) t.columns.push_back({"not_solved", "not solved"});
  for (const auto& e : epsilon_labels) {
    t.columns.push_back(coverage_column(Coverage::covered, e));
    if (!for_paper) {
      t.columns.push_back(coverage_column(Coverage::not_covered, e));
      t.columns.push_back(coverage_column(Coverage::dominated, e));
    }
  }
  t.columns.insert(t.columns.end(), {{"eps_median", "$\\tilde\\varepsilon$"},
                                     {"eps_max", "$\\varepsilon_{\\max}$"},
                                     {"size_ratio_median", "$|S|/|R|$"}});
  if (!for_paper)
    t.columns.insert(t.columns.end(),
                     {{"size_ratio_mean", "$|S|/|R|$ mean"}, {"runtime_queries", "$n_t$"}});
  t.columns.push_back({"runtime_median", "$\\tilde t$ [s]"});
  if (!for_paper) t.columns.push_back({"runtime_mean", "$\\bar t$ [s]"});
  t.columns.insert(t.columns.end(),
                   {{"runtime_max", "$t_{\\max}$ [s]"}, {"runtime_sgm", "SGM [s]"}});
  for (const auto& s : comparison.solvers) {
    std::vector<Cell> row{Cell::of(s.name)};
    for (const auto status : kQueryStatuses)
      if (shown(status)) row.push_back(Cell::of(s.own.statuses[status]));
    if (!for_paper) row.push_back(Cell::of(s.not_solved));
    for (const auto& e : s.per_epsilon) {
      row.push_back(Cell::of(e.covered));
      if (!for_paper) {
        row.push_back(Cell::of(e.not_covered));
        row.push_back(Cell::of(e.dominated));
      }
    }
    row.push_back(optional_real(s.achieved_epsilon, &Distribution::median));
    row.push_back(optional_real(s.achieved_epsilon, &Distribution::max));
    row.push_back(optional_real(s.size_ratio, &Distribution::median));
    if (!for_paper) {
      row.push_back(optional_real(s.size_ratio, &Distribution::mean));
      row.push_back(Cell::of(std::uint64_t{s.runtime ? s.runtime->count : 0}));
    }
    row.push_back(optional_real(s.runtime, &Distribution::median));
    if (!for_paper) row.push_back(optional_real(s.runtime, &Distribution::mean));
    row.push_back(optional_real(s.runtime, &Distribution::max));
    row.push_back(optional_real(s.runtime, &Distribution::shifted_geometric_mean));
    t.rows.push_back(std::move(row));
  }
  return t;
}

Table comparison_per_query(const SolverComparison& comparison,
                           std::span<const std::string> epsilon_labels,
                           std::span<const SolutionReader> solutions) {
  Table t;
  t.columns = {{"solver", "Solver"},
               {"query", "query"},
               {"reference_status", "reference"},
               {"status", "status"},
               {"solution_size", "$|S|$"},
               {"reference_size", "$|R|$"},
               {"achieved_eps", "$\\varepsilon$"}};
  for (const auto& e : epsilon_labels) t.columns.push_back(coverage_column(Coverage::covered, e));
  // The runtime the comparison summarises: mosb's wall clock, else the solver's own figure.
  const auto statistic = runtime_statistic(comparison.runtime);
  t.columns.push_back(comparison.runtime == RuntimeSource::wall
                          ? Column{"runtime_seconds", "$t$ [s]"}
                          : Column{std::string(to_string(statistic)), "$t_{\\mathrm{rep}}$ [s]"});
  t.columns.push_back({"failed", "failed"});
  for (std::size_t i = 0; i < comparison.solvers.size(); ++i) {
    const auto& s = comparison.solvers[i];
    for (const auto& q : s.evaluation.queries) {
      std::vector<Cell> row{Cell::of(s.name), Cell::of(q.query),
                            Cell::of(std::string(to_string(q.reference_status))),
                            Cell::of(std::string(to_string(q.solution_status)))};
      if (q.front) {
        row.push_back(Cell::of(std::uint64_t{q.front->solution_size}));
        row.push_back(Cell::of(std::uint64_t{q.front->reference_size}));
        row.push_back(Cell::of(q.front->achieved_value));
        for (const auto& c : q.front->coverage) row.push_back(Cell::of(std::uint64_t{c.covered}));
      } else {
        row.resize(row.size() + 3 + epsilon_labels.size());
      }
      const auto runtime = solutions[i].statistic_as_double(statistic, q.query);
      row.push_back(runtime ? Cell::of(*runtime) : Cell{});
      row.push_back(Cell::of(std::uint64_t{q.failed}));
      t.rows.push_back(std::move(row));
    }
  }
  return t;
}

}  // namespace mosb::tables
