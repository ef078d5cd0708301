// Tables of numbers for a results section: one model, written as CSV (RFC 4180, every digit kept),
// a LaTeX booktabs tabular (three significant digits, for a paper) or aligned text (a terminal).
// `mosb eval --csv|--latex` and `mosb report` build theirs here. The writers take text as given
// (a solver's name as its file says it) and escape it for their language, each in one place:
// CSV in write_csv, LaTeX in latex_escape, HTML in plots::Svg::escape; the terminal's escaping
// (escape_for_terminal) is the program's and never reaches a file.
#pragma once

#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/solver_comparison.hpp"

namespace mosb::tables {

struct Cell {
  enum class Kind { absent, text, count, real } kind = Kind::absent;
  std::string text;
  std::uint64_t count = 0;
  double real = 0;  // may be +infinity

  static Cell of(std::string t) { return {Kind::text, std::move(t), 0, 0}; }
  static Cell of(std::uint64_t n) { return {Kind::count, {}, n, 0}; }
  static Cell of(double x) { return {Kind::real, {}, 0, x}; }
};

struct Column {
  std::string key;        // CSV header and text heading: [a-z0-9_@.]
  std::string latex;      // LaTeX heading (math allowed; any text in it through latex_escape)
  std::string html = {};  // HTML heading (plain text, escaped on writing); the key when empty
};

// A head over `count` columns from `first` (a solver's columns in a paper's comparison table):
// LaTeX \multicolumn with a \cmidrule under it, an HTML heading row of its own (colspan). CSV and
// text have no such row; the grouped columns' keys carry the group themselves.
struct ColumnGroup {
  std::size_t first = 0, count = 0;
  std::string title;  // plain text, escaped on writing
};

struct Table {
  std::vector<Column> columns;
  std::vector<std::vector<Cell>> rows;  // each as long as `columns`
  std::string caption;                  // LaTeX comment line and text heading; may be empty
  std::vector<ColumnGroup> groups;      // in column order, not overlapping; may be empty
};

// `text` as LaTeX shows it in text mode, a cell's or a heading's: \ { } $ & # % _ ~ ^ [ ] < > |
// escaped (so no name can end a tabular, start a command or be read as the optional argument
// of the previous row's \\), and each C0 control character and DEL as \textbackslash{}xNN (it
// would otherwise break the table or the run). Other bytes, UTF-8 included, are kept.
std::string latex_escape(std::string_view text);

// What a query counts as at one ε in an ε-coverage column.
enum class Coverage { covered, not_covered, dominated };
// The column of that count at ε = `label` (the ε's decimal text), the one heading every table
// gives it: key "covered@LABEL" ("not_covered@", "dominated@"), LaTeX "cov. $\varepsilon{=}LABEL$"
// ("not cov.", "dom."), HTML "covered at ε = LABEL" ("not covered", "dominated").
Column coverage_column(Coverage what, std::string_view label);

// Numbers: CSV the shortest text that reads back the same ("inf" for infinity), an empty field
// when absent; LaTeX %.3g, $\infty$, "--" when absent, text escaped; text %.4g, "-" when absent.
// CSV (RFC 4180) quotes a field holding a comma, a quote, CR or LF, doubling its quotes; a text
// field starting with = + - @ TAB or CR, which a spreadsheet would run as a formula, is written
// with a ' before it, quoted (OWASP, "CSV Injection"); any other C0 control character, and DEL,
// becomes U+FFFD, as in HTML. Numbers are written as numbers: a negative one (a ρ of the instance
// space) is a value to a spreadsheet, not a formula, and keeps its sign.
void write_csv(std::ostream& out, const Table& table);
void write_latex(std::ostream& out, const Table& table);
void write_text(std::ostream& out, const Table& table);
// The table as one compact JSON object and a newline: {"caption": ..., "rows": [{KEY: value, ...},
// ...]}, keys in column order, an absent cell and a non-finite number null (`mosb eval --json`).
void write_json(std::ostream& out, const Table& table);
// An HTML <table class="sortable"> with the caption, a header row and one row per table row:
// numbers as text writes them, each cell also carrying its exact value in data-v (what a sorting
// script compares; empty when absent), text escaped. Readable without any script.
void write_html(std::ostream& out, const Table& table, const std::string& id);

// One row per solver: statuses, per ε covered, not covered and failed for dominated vectors
// (QueryOutcome::dominated), achieved ε (median, max), |S|/|R|
// (median, mean), runtime over the common queries (count, median, mean, max, shifted geometric
// mean). `epsilon_labels` names the ε in order, as the user gave them. `for_paper` keeps the
// columns a paper's comparison table has (solved, timeout, memory-limit, failed, covered per ε,
// ε median and max, |S|/|R| median, runtime median, max and shifted geometric mean).
Table comparison_summary(const SolverComparison& comparison,
                         std::span<const std::string> epsilon_labels, bool for_paper = false);
// One row per solver and query: statuses, sizes, achieved ε, coverage per ε, the runtime the
// comparison summarises (mosb's wall clock `runtime_seconds`, else the solver's own figure under
// its statistic's name), failed.
Table comparison_per_query(const SolverComparison& comparison,
                           std::span<const std::string> epsilon_labels,
                           std::span<const SolutionReader> solutions);

}  // namespace mosb::tables
