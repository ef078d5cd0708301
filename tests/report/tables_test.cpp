#include "mosb/report/tables.hpp"

#include <doctest/doctest.h>

#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace mosb;
using namespace mosb::tables;

namespace {

// Two solvers as compare_solvers would summarise them, at ε = 0 and 0.1.
SolverComparison two_solvers() {
  SolverComparison c;
  SolverSummary fast;
  fast.name = "fast_1";
  fast.own.statuses[QueryStatus::solved] = 2;
  fast.own.statuses[QueryStatus::disconnected] = 1;
  fast.per_epsilon = {{1, 1}, {2, 0}};
  fast.achieved_epsilon = Distribution{2, 0.05, 0.05, 0.1, 0};
  fast.size_ratio = Distribution{2, 1, 1, 1, 0};
  fast.runtime = Distribution{2, 0.75, 0.75, 1, 0.7};
  SolverSummary slow;
  slow.name = "slow & co";
  slow.own.statuses[QueryStatus::solved] = 1;
  slow.own.statuses[QueryStatus::timeout] = 1;
  slow.own.statuses[QueryStatus::disconnected] = 1;
  slow.not_solved = 1;
  slow.per_epsilon = {{0, 1}, {0, 1}};
  slow.achieved_epsilon = Distribution{1, std::numeric_limits<double>::infinity(), 0, 0.125, 0};
  c.solvers = {fast, slow};
  return c;
}

const std::vector<std::string> kLabels{"0", "0.1"};

}  // namespace

TEST_CASE("write_csv: a header of keys, every digit, empty fields for absent values, CRLF") {
  std::ostringstream out;
  write_csv(out, comparison_summary(two_solvers(), kLabels));
  const auto csv = out.str();
  CHECK(csv.starts_with(
      "solver,solved,timeout,memory_limit,disconnected,not_run,failed,not_solved,"
      "covered@0,not_covered@0,dominated@0,covered@0.1,not_covered@0.1,dominated@0.1,"
      "eps_median,eps_max,"
      "size_ratio_median,size_ratio_mean,runtime_queries,runtime_median,"
      "runtime_mean,runtime_max,runtime_sgm\r\n"));
  CHECK(csv.find("\r\nfast_1,2,0,0,1,0,0,0,1,1,0,2,0,0,0.05,0.1,1,1,2,0.75,0.75,1,0.7\r\n") !=
        std::string::npos);
  // No runtime: empty fields; an infinite median: "inf".
  CHECK(csv.find("\r\nslow & co,1,1,0,1,0,0,1,0,1,0,0,1,0,inf,0.125,,,0,,,,\r\n") !=
        std::string::npos);
}

TEST_CASE("write_csv: a field with a comma, a quote or a line break is quoted") {
  Table t;
  t.columns = {{"name", "Name"}};
  t.rows = {{Cell::of(std::string("a,b"))}, {Cell::of(std::string("say \"x\""))}};
  std::ostringstream out;
  write_csv(out, t);
  CHECK(out.str() == "name\r\n\"a,b\"\r\n\"say \"\"x\"\"\"\r\n");
}

TEST_CASE("write_json: keys in column order, numbers as numbers, absent and infinite null") {
  Table t;
  t.caption = "a \"caption\"";
  t.columns = {{"name", "Name"}, {"n", "N"}, {"x", "X"}, {"gap", "Gap"}};
  t.rows = {{Cell::of(std::string("s\n1")), Cell::of(std::uint64_t{3}), Cell::of(0.125), Cell{}},
            {Cell::of(std::string("t")), Cell{}, Cell::of(std::numeric_limits<double>::infinity()),
             Cell::of(std::uint64_t{0})}};
  std::ostringstream out;
  write_json(out, t);
  CHECK(out.str() ==
        "{\"caption\":\"a \\\"caption\\\"\",\"rows\":[{\"name\":\"s\\n1\",\"n\":3,\"x\":0.125,"
        "\"gap\":null},{\"name\":\"t\",\"n\":null,\"x\":null,\"gap\":0}]}\n");
}

// Issue 36 §4: a spreadsheet runs a field starting with = + - @ TAB or CR as a formula.
TEST_CASE(
    "write_csv: text that a spreadsheet would run is quoted after a ', numbers stay numbers") {
  Table t;
  t.columns = {{"name", "Name"}, {"rho", "$\\rho$"}};
  for (const char* name : {"=cmd|' /C calc'!A0", "+1", "-2+3", "@SUM(A1)", "\tx", "\rx", "a\\b",
                           "a\x1b[2Jb", "ok-name"})
    t.rows.push_back({Cell::of(std::string(name)), Cell::of(-0.44)});
  std::ostringstream out;
  write_csv(out, t);
  CHECK(out.str() ==
        "name,rho\r\n"
        "\"'=cmd|' /C calc'!A0\",-0.44\r\n"
        "\"'+1\",-0.44\r\n"
        "\"'-2+3\",-0.44\r\n"
        "\"'@SUM(A1)\",-0.44\r\n"
        "\"'\tx\",-0.44\r\n"
        "\"'\rx\",-0.44\r\n"
        "a\\b,-0.44\r\n"               // a backslash is data, not terminal escaping
        "a\xEF\xBF\xBD[2Jb,-0.44\r\n"  // no control character reaches the file
        "ok-name,-0.44\r\n");
}

// Issue 36 §3: every string a LaTeX table shows goes through latex_escape, headings included.
TEST_CASE("latex_escape: no name can end the tabular, run a command or take an argument") {
  CHECK(latex_escape("\\end{tabular}\\input{/etc/passwd}") ==
        "\\textbackslash{}end\\{tabular\\}\\textbackslash{}input\\{/etc/passwd\\}");
  CHECK(latex_escape("$ _ # % & ~ ^ { }") ==
        "\\$ \\_ \\# \\% \\& \\textasciitilde{} \\textasciicircum{} \\{ \\}");
  CHECK(latex_escape("[1cm]<a|b>") == "{[}1cm{]}\\textless{}a\\textbar{}b\\textgreater{}");
  CHECK(latex_escape("a\nb\x7f") == "a\\textbackslash{}x0Ab\\textbackslash{}x7F");
  // Beyond ASCII, what pdflatex typesets: Latin-1 letters kept, Greek and dashes as commands,
  // any other code point and any byte of no UTF-8 sequence spelled out.
  CHECK(latex_escape("ε-solver") == "\\ensuremath{\\varepsilon}-solver");
  CHECK(latex_escape("Müller – ρ") == "Müller -- \\ensuremath{\\rho}");
  CHECK(latex_escape("\xe2\x9c\x93 ok") == "\\textbackslash{}u2713 ok");
  CHECK(latex_escape("a\xff\xc3") == "a\\textbackslash{}xFF\\textbackslash{}xC3");
  CHECK(latex_escape("\xc0\x80") == "\\textbackslash{}xC0\\textbackslash{}x80");  // overlong NUL
  // The comparison's headings carry each ε through it as well.
  std::ostringstream out;
  auto c = two_solvers();
  c.solvers[0].name = "\\end{tabular}";
  write_latex(out, comparison_summary(c, kLabels, true));
  CHECK(out.str().find("\n\\textbackslash{}end\\{tabular\\} & 2 & ") != std::string::npos);
  CHECK(out.str().find("\\end{tabular}") == out.str().rfind("\\end{tabular}"));  // the table's
}

TEST_CASE("write_latex: a booktabs tabular of the paper's columns, escaped, three digits") {
  std::ostringstream out;
  auto table = comparison_summary(two_solvers(), kLabels, true);
  table.caption = "mosb eval";
  write_latex(out, table);
  const auto tex = out.str();
  CHECK(
      tex.starts_with("% mosb eval\n\\begin{tabular}{lrrrrrrrrrrrr}\n\\toprule\nSolver & solved & "
                      "timeout & memory-limit & failed & cov.\\ $\\varepsilon{=}0$ & "));
  CHECK(tex.find("\\midrule\nfast\\_1 & 2 & 0 & 0 & 0 & 1 & 2 & 0.05 & 0.1 & 1 & 0.75 & 1 & 0.7 "
                 "\\\\\n") != std::string::npos);
  CHECK(tex.find("slow \\& co & 1 & 1 & 0 & 0 & 0 & 0 & $\\infty$ & 0.125 & -- & -- & -- & -- "
                 "\\\\\n") != std::string::npos);
  CHECK(tex.ends_with("\\bottomrule\n\\end{tabular}\n"));
}

TEST_CASE("write_latex and write_text: large numbers whole, never with an exponent") {
  Table table;
  table.columns = {{"count", "count"}, {"size", "size"}, {"small", "small"}};
  table.rows = {{Cell::of(std::uint64_t{1160000}), Cell::of(6400.5), Cell::of(0.000173)},
                {Cell::of(std::uint64_t{999}), Cell::of(999.6), Cell::of(12.345)},
                {Cell::of(std::uint64_t{0}), Cell::of(-12345.0), Cell::of(0.0)}};
  std::ostringstream latex;
  write_latex(latex, table);
  CHECK(latex.str().find("1{,}160{,}000 & 6{,}401 & 0.000173 \\\\\n") != std::string::npos);
  CHECK(latex.str().find("999 & 1{,}000 & 12.3 \\\\\n") != std::string::npos);
  CHECK(latex.str().find("0 & -12{,}345 & 0 \\\\\n") != std::string::npos);
  CHECK(latex.str().find("e+") == std::string::npos);
  std::ostringstream text;
  write_text(text, table);
  CHECK(text.str().find("6401") != std::string::npos);
  CHECK(text.str().find("e+") == std::string::npos);
}

TEST_CASE("write_text: names left-aligned, numbers right-aligned under their headings") {
  std::ostringstream out;
  write_text(out, comparison_summary(two_solvers(), kLabels));
  std::istringstream lines(out.str());
  std::string header, line;
  std::getline(lines, header);
  CHECK(header.starts_with("solver     solved"));
  std::vector<std::string> rows;
  while (std::getline(lines, line)) rows.push_back(line);
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].starts_with("fast_1          2"));
  CHECK(rows[1].starts_with("slow & co       1"));
  // The last column is right-aligned: every row ends where the header does, or earlier only by
  // the absent values' dashes, which are right-aligned too.
  CHECK(rows[0].size() == header.size());
  CHECK(rows[1].size() == header.size());
}

TEST_CASE("write_html: a sortable table, headings, exact values in data-v, text escaped") {
  Table t;
  t.caption = "a <caption>";
  t.columns = {{"name", "Name", "solver name"}, {"n", "$n$"}, {"t", "$t$"}};
  t.rows = {{Cell::of(std::string("a&b")), Cell::of(std::uint64_t{12}), Cell::of(0.125)},
            {Cell::of(std::string("c")), Cell{}, Cell::of(1.0 / 3)}};
  std::ostringstream out;
  write_html(out, t, "tab");
  const auto html = out.str();
  CHECK(html.find(R"(<table class="sortable" id="tab">)") != std::string::npos);
  CHECK(html.find("<caption>a &lt;caption&gt;</caption>") != std::string::npos);
  CHECK(html.find(R"(<th scope="col" data-key="name">solver name</th>)") != std::string::npos);
  CHECK(html.find(R"(<th scope="col" data-key="n">n</th>)") != std::string::npos);
  CHECK(html.find("<td>a&amp;b</td>") != std::string::npos);
  CHECK(html.find(R"(<td class="n" data-v="12">12</td>)") != std::string::npos);
  CHECK(html.find(R"(<td class="n" data-v="">-</td>)") != std::string::npos);
  CHECK(html.find(R"(data-v="0.3333333333333333">0.3333</td>)") != std::string::npos);
}

TEST_CASE("column groups: a \\multicolumn head with its \\cmidrule, an HTML colgroup heading") {
  Table t;
  t.columns = {{"a@x", "A"}, {"b@x", "B"}, {"c", "C"}, {"d@y", "D"}};
  t.rows = {
      {Cell::of(std::uint64_t{1}), Cell::of(std::uint64_t{2}), Cell::of(std::uint64_t{3}), Cell{}}};
  t.groups = {{0, 2, "x & co"}, {3, 1, "y"}};
  std::ostringstream latex;
  write_latex(latex, t);
  CHECK(latex.str() ==
        "\\begin{tabular}{lrrr}\n\\toprule\n"
        "\\multicolumn{2}{c}{x \\& co} &  & \\multicolumn{1}{c}{y} \\\\\n"
        "\\cmidrule(lr){1-2}\\cmidrule(lr){4-4}\n"
        "A & B & C & D \\\\\n\\midrule\n1 & 2 & 3 & -- \\\\\n\\bottomrule\n\\end{tabular}\n");
  std::ostringstream html;
  write_html(html, t, "t");
  CHECK(html.str().find("<thead><tr><th scope=\"colgroup\" colspan=\"2\">x &amp; co</th><th></th>"
                        "<th scope=\"colgroup\" colspan=\"1\">y</th></tr>\n<tr><th") !=
        std::string::npos);
  std::ostringstream csv;
  write_csv(csv, t);
  CHECK(csv.str().substr(0, 13) == "a@x,b@x,c,d@y");  // the keys carry the groups
}
