#include "mosb/converters/dimacs_converter.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <thread>

#include "mosb/converters/narrow_column.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "vertex_values.hpp"

namespace mosb::converters {

namespace {

using format::kMaxCount;

using namespace text;  // the shared primitives of text_scan.hpp

std::string id_range(unsigned id_base, std::uint64_t n) {
  if (n == 0) return "(none: the graph has no vertices)";
  return std::to_string(id_base) + ".." + std::to_string(n - 1 + id_base);
}

// A count field of a header line (n or m).
std::uint64_t parse_count(const std::string& file, std::uint64_t line, const Token& t,
                          const char* what) {
  if (!is_digits(t.text))
    fail(file, line, t.column, std::string("expected the ") + what + ", found " + quoted(t.text));
  const auto value = to_u64(t.text);
  if (!value || *value > kMaxCount)
    fail(file, line, t.column,
         std::string("the ") + what + " " + quoted(t.text) + " exceeds " +
             std::to_string(kMaxCount));
  return *value;
}

std::uint32_t parse_id(const std::string& file, std::uint64_t line, const Token& t,
                       unsigned id_base, std::uint64_t n) {
  if (!is_digits(t.text))
    fail(file, line, t.column, "expected a vertex id, found " + quoted(t.text));
  const auto value = to_u64(t.text);
  if (!value || *value < id_base || *value - id_base >= n)
    fail(file, line, t.column, "vertex id " + quoted(t.text) + " outside " + id_range(id_base, n));
  return static_cast<std::uint32_t>(*value - id_base);
}

using Column = std::variant<std::vector<std::uint64_t>, std::vector<double>>;

// Asks for transparent huge pages on a reserved array: filling FLA-size arrays otherwise costs one
// page fault per 4 KiB, a fifth of the conversion's time. Advice only; ignored where unsupported.
template <class T>
void advise_huge_pages(const std::vector<T>& v) {
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(v.data());
  const auto end = begin + v.capacity() * sizeof(T);
  const auto first = (begin + kHuge - 1) & ~(kHuge - 1), last = end & ~(kHuge - 1);
  if (last >
      first)  // NOLINTNEXTLINE(performance-no-int-to-ptr): madvise takes page-aligned addresses
    ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

void add_cost(const std::string& file, std::uint64_t line, const Token& t, Column& column) {
  const auto s = t.text;
  if (!s.empty() && s[0] == '-') fail(file, line, t.column, "negative cost " + quoted(s));
  const bool real = s.find_first_of(".eE") != std::string_view::npos;
  if (!real) {
    if (!is_digits(s)) fail(file, line, t.column, "expected a cost, found " + quoted(s));
    const auto value = to_u64(s);
    if (!value)
      fail(file, line, t.column, "cost " + quoted(s) + " exceeds " + std::to_string(UINT64_MAX));
    if (auto* ints = std::get_if<std::vector<std::uint64_t>>(&column))
      ints->push_back(*value);
    else
      std::get<std::vector<double>>(column).push_back(static_cast<double>(*value));
    return;
  }
  // Digits, at most one '.', then an optional exponent: what from_chars accepts without
  // inf/nan/hex.
  for (char c : s)
    if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-'))
      fail(file, line, t.column, "expected a cost, found " + quoted(s));
  if (s[0] == '+' || s[0] == 'e' || s[0] == 'E')
    fail(file, line, t.column, "expected a cost, found " + quoted(s));
  double value = 0;
  const auto [ptr, ec] =
      std::from_chars(s.data(), s.data() + s.size(), value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range)
    fail(file, line, t.column, "cost " + quoted(s) + " out of range");
  if (ec != std::errc() || ptr != s.data() + s.size())
    fail(file, line, t.column, "expected a cost, found " + quoted(s));
  if (auto* ints = std::get_if<std::vector<std::uint64_t>>(&column)) {
    std::vector<double> reals(ints->begin(), ints->end());
    reals.reserve(ints->capacity());
    column = std::move(reals);
  }
  std::get<std::vector<double>>(column).push_back(value);
}

// The common case in one pass: `a u v c1 .. cd` with plain integers and valid ids. Anything else
// (reals, signs, bad ids, wrong field counts) returns false and takes the general path, which
// reports the precise error.
bool scan_integer_arc(std::string_view line, std::size_t cost_count, unsigned id_base,
                      std::uint64_t n, std::uint32_t& u, std::uint32_t& v, std::uint64_t* costs) {
  const char* p = line.data() + 1;
  const char* const end = line.data() + line.size();
  auto field = [&](std::uint64_t& out) {
    if (p == end || (*p != ' ' && *p != '\t')) return false;
    while (p != end && (*p == ' ' || *p == '\t')) ++p;
    const char* const start = p;
    std::uint64_t x = 0;
    while (p != end && static_cast<unsigned>(*p - '0') < 10)
      x = x * 10 + static_cast<unsigned>(*p++ - '0');
    out = x;
    return p != start && p - start <= 19;  // 19 digits cannot overflow
  };
  std::uint64_t a = 0, b = 0;
  if (!field(a) || !field(b) || a < id_base || b < id_base || a - id_base >= n || b - id_base >= n)
    return false;
  for (std::size_t j = 0; j < cost_count; ++j)
    if (!field(costs[j])) return false;
  if (p != end) return false;
  u = static_cast<std::uint32_t>(a - id_base);
  v = static_cast<std::uint32_t>(b - id_base);
  return true;
}

DimacsGraph parse_gr(LineScanner& lines, std::uint64_t size_hint, const std::string& display_name,
                     unsigned id_base, const DimacsReference* reference, bool record_arc_lines) {
  if (id_base > 1) throw Error(display_name + ": id base must be 0 or 1");
  DimacsGraph g;
  std::string_view line;
  std::vector<Token> t;
  std::uint64_t p_line = 0, m_column = 0, declared_arcs = 0, first_arc_line = 0;
  std::size_t cost_count = 0;
  std::vector<std::vector<std::uint64_t>*> integer_columns;  // all columns, while all are integers
  std::vector<std::uint64_t> fast_costs;
  while (lines.next(line)) {
    const auto ln = lines.number();
    std::uint32_t fast_u = 0, fast_v = 0;
    if (!integer_columns.empty() && line.size() > 1 && line[0] == 'a' &&
        scan_integer_arc(line, cost_count, id_base, g.vertex_count, fast_u, fast_v,
                         fast_costs.data())) {
      const auto k = g.tails.size();
      const bool matches_reference = !reference || (k < reference->graph->tails.size() &&
                                                    reference->graph->tails[k] == fast_u &&
                                                    reference->graph->heads[k] == fast_v);
      if (matches_reference && k < kMaxCount) {
        for (std::size_t j = 0; j < cost_count; ++j) integer_columns[j]->push_back(fast_costs[j]);
        g.tails.push_back(fast_u);
        g.heads.push_back(fast_v);
        if (record_arc_lines) g.arc_lines.push_back(ln);
        continue;
      }
    }
    tokenize(line, t);
    if (t.empty() || t[0].text == "c") continue;
    const auto end_column = line.size() + 1;
    if (t[0].text == "a") {
      if (p_line == 0) fail(display_name, ln, t[0].column, "arc line before the 'p sp' line");
      if (t.size() < 4) {
        if (t.size() >= 2) parse_id(display_name, ln, t[1], id_base, g.vertex_count);
        if (t.size() >= 3) parse_id(display_name, ln, t[2], id_base, g.vertex_count);
        fail(display_name, ln, end_column, "missing field: an arc line is 'a u v cost...'");
      }
      if (first_arc_line == 0) {
        first_arc_line = ln;
        cost_count = t.size() - 3;
        g.columns.assign(cost_count, Column{});
        for (auto& c : g.columns) {
          auto& values = std::get<std::vector<std::uint64_t>>(c);
          values.reserve(g.tails.capacity());
          advise_huge_pages(values);
        }
      } else if (t.size() - 3 != cost_count) {
        const std::string expected = "expected " + plural(cost_count, "cost") + " as on line " +
                                     std::to_string(first_arc_line);
        if (t.size() - 3 < cost_count)
          fail(display_name, ln, end_column, "missing field: " + expected);
        fail(display_name, ln, t[3 + cost_count].column,
             "extra field " + quoted(t[3 + cost_count].text) + ": " + expected);
      }
      const auto u = parse_id(display_name, ln, t[1], id_base, g.vertex_count);
      const auto v = parse_id(display_name, ln, t[2], id_base, g.vertex_count);
      for (std::size_t j = 0; j < cost_count; ++j)
        add_cost(display_name, ln, t[3 + j], g.columns[j]);
      const auto k = g.tails.size();
      if (k >= kMaxCount)
        fail(display_name, ln, t[0].column, "more than " + std::to_string(kMaxCount) + " arcs");
      if (reference) {
        const auto& ref = *reference->graph;
        if (k >= ref.tails.size())
          fail(display_name, ln, t[1].column,
               "arc beyond the " + plural(ref.tails.size(), "arc") + " of " +
                   *reference->display_name);
        if (ref.tails[k] != u || ref.heads[k] != v)
          fail(display_name, ln, t[1].column,
               "arc " + std::to_string(u + id_base) + " " + std::to_string(v + id_base) +
                   " differs from arc " + std::to_string(ref.tails[k] + id_base) + " " +
                   std::to_string(ref.heads[k] + id_base) + " at " + *reference->display_name +
                   ":" + std::to_string(ref.arc_lines[k]) +
                   " (per-objective files must list the same arcs in the same order)");
      }
      g.tails.push_back(u);
      g.heads.push_back(v);
      if (record_arc_lines) g.arc_lines.push_back(ln);
      integer_columns.clear();
      for (auto& c : g.columns)
        if (auto* ints = std::get_if<std::vector<std::uint64_t>>(&c))
          integer_columns.push_back(ints);
      if (integer_columns.size() != cost_count || cost_count == 0) integer_columns.clear();
      fast_costs.resize(cost_count);
    } else if (t[0].text == "p") {
      if (p_line != 0)
        fail(display_name, ln, t[0].column,
             "second 'p' line (the first is line " + std::to_string(p_line) + ")");
      if (t.size() < 2)
        fail(display_name, ln, end_column, "missing field: the header is 'p sp n m'");
      if (t[1].text != "sp")
        fail(display_name, ln, t[1].column, "expected 'sp' after 'p', found " + quoted(t[1].text));
      if (t.size() < 4)
        fail(display_name, ln, end_column, "missing field: the header is 'p sp n m'");
      if (t.size() > 4)
        fail(display_name, ln, t[4].column,
             "extra field " + quoted(t[4].text) + ": the header is 'p sp n m'");
      g.vertex_count = parse_count(display_name, ln, t[2], "vertex count");
      declared_arcs = parse_count(display_name, ln, t[3], "arc count");
      check_declared_vertices(display_name, ln, t[2].column, g.vertex_count);
      p_line = ln;
      m_column = t[3].column;
      if (reference) {
        const auto& ref = *reference->graph;
        if (g.vertex_count != ref.vertex_count)
          fail(display_name, ln, t[2].column,
               "declares " + plural(g.vertex_count, "vertex") + ", " + *reference->display_name +
                   " has " + std::to_string(ref.vertex_count));
        if (declared_arcs != ref.tails.size())
          fail(display_name, ln, t[3].column,
               "declares " + plural(declared_arcs, "arc") + ", " + *reference->display_name +
                   " has " + std::to_string(ref.tails.size()));
      }
      // The header is untrusted: reserve no more than the text could hold (a line is >= 8 bytes).
      const auto reserve = std::min<std::uint64_t>(declared_arcs, size_hint / 8 + 1);
      g.tails.reserve(reserve);
      g.heads.reserve(reserve);
      if (record_arc_lines) g.arc_lines.reserve(reserve);
      advise_huge_pages(g.tails);
      advise_huge_pages(g.heads);
    } else {
      fail(display_name, ln, t[0].column, "unknown line type " + quoted(t[0].text));
    }
  }
  if (p_line == 0)
    fail(display_name, std::max<std::uint64_t>(lines.number(), 1), 1, "no 'p sp n m' line");
  if (g.tails.size() != declared_arcs)
    fail(display_name, p_line, m_column,
         "the header declares " + plural(declared_arcs, "arc") + ", found " +
             std::to_string(g.tails.size()));
  if (first_arc_line == 0 && reference)  // no arcs at all: as many (zero) columns as the reference
    g.columns.assign(reference->graph->columns.size(), Column{});
  if (first_arc_line == 0 && !reference) g.columns.assign(1, Column{});
  return g;
}

}  // namespace

DimacsGraph parse_dimacs_gr(std::string_view text, const std::string& display_name,
                            unsigned id_base, const DimacsReference* reference) {
  LineScanner lines(text);
  return parse_gr(lines, text.size(), display_name, id_base, reference, true);
}

DimacsGraph parse_dimacs_gr(TextSource& source, std::uint64_t size_hint,
                            const std::string& display_name, unsigned id_base,
                            const DimacsReference* reference, bool record_arc_lines) {
  LineScanner lines(source);
  return parse_gr(lines, size_hint, display_name, id_base, reference, record_arc_lines);
}

std::vector<std::uint64_t> dimacs_arc_lines(TextSource& source) {
  LineScanner lines(source);
  std::string_view line;
  std::vector<std::uint64_t> numbers;
  while (lines.next(line)) {
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string_view::npos && line[first] == 'a' &&
        (first + 1 == line.size() || line[first + 1] == ' ' || line[first + 1] == '\t'))
      numbers.push_back(lines.number());
  }
  return numbers;
}

std::vector<std::int64_t> parse_vertex_values(LineScanner& lines, const std::string& display_name,
                                              unsigned id_base, std::uint64_t vertex_count,
                                              const VertexValueFile& file) {
  const std::string header = std::string("'p aux sp ") + file.tag + " n'";
  const std::size_t fields = 2 + file.values;  // v id value...
  std::string_view line;
  std::vector<Token> t;
  std::uint64_t p_line = 0, n = 0;
  std::vector<std::int64_t> values;
  std::vector<bool> seen;
  while (lines.next(line)) {
    tokenize(line, t);
    const auto ln = lines.number();
    if (t.empty() || t[0].text == "c") continue;
    const auto end_column = line.size() + 1;
    if (t[0].text == "v") {
      if (p_line == 0)
        fail(display_name, ln, t[0].column,
             std::string("'v' line before the ") + file.header_cited_by_v + " line");
      if (t.size() < fields)
        fail(display_name, ln, end_column, std::string("missing field: ") + file.line_rule);
      if (t.size() > fields)
        fail(display_name, ln, t[fields].column,
             "extra field " + quoted(t[fields].text) + ": " + file.line_rule);
      if (file.precise_field_errors && !is_digits(t[1].text))
        fail(display_name, ln, t[1].column, "expected a vertex id, found " + quoted(t[1].text));
      const auto number = to_u64(t[1].text);
      if (!number || *number < id_base || *number - id_base >= n)
        fail(display_name, ln, t[1].column,
             "vertex id " + quoted(t[1].text) + " outside " + id_range(id_base, n));
      const auto id = *number - id_base;
      if (seen[id])
        fail(display_name, ln, t[1].column,
             "second 'v' line for vertex " + std::to_string(*number));
      seen[id] = true;
      for (std::size_t k = 0; k < file.values; ++k) {
        const auto value = to_i64(t[2 + k].text);
        if (!value)
          fail(display_name, ln, t[2 + k].column,
               std::string("expected an integer ") + file.value_name + ", found " +
                   quoted(t[2 + k].text));
        values[file.values * id + k] = *value;
      }
    } else if (t[0].text == "p") {
      if (p_line != 0)
        fail(display_name, ln, t[0].column,
             "second 'p' line (the first is line " + std::to_string(p_line) + ")");
      if (t.size() < 5)
        fail(display_name, ln, end_column, "missing field: the header is " + header);
      if (t[1].text != "aux" || t[2].text != "sp" || t[3].text != file.tag)
        fail(display_name, ln, t[1].column, "expected " + header);
      if (t.size() > 5)
        fail(display_name, ln, t[5].column,
             "extra field " + quoted(t[5].text) + ": the header is " + header);
      if (file.precise_field_errors) {
        n = parse_count(display_name, ln, t[4], "vertex count");
      } else {
        const auto count = to_u64(t[4].text, kMaxCount);
        if (!count)
          fail(display_name, ln, t[4].column,
               "expected the vertex count, found " + quoted(t[4].text));
        n = *count;
      }
      if (n != vertex_count)
        fail(display_name, ln, t[4].column,
             "declares " +
                 (file.precise_field_errors ? plural(n, "vertex")
                                            : std::to_string(n) + " vertices") +
                 ", the graph has " + std::to_string(vertex_count));
      p_line = ln;
      values.assign(file.values * n, 0);  // n equals the graph's vertex count, already in memory
      seen.assign(n, false);
    } else {
      fail(display_name, ln, t[0].column, "unknown line type " + quoted(t[0].text));
    }
  }
  if (p_line == 0)
    fail(display_name, std::max<std::uint64_t>(lines.number(), 1), 1, "no " + header + " line");
  for (std::uint64_t id = 0; id < n; ++id)
    if (!seen[id])
      fail(display_name, p_line, 1, "no 'v' line for vertex " + std::to_string(id + id_base));
  return values;
}

std::vector<std::int64_t> parse_dimacs_co(std::string_view text, const std::string& display_name,
                                          unsigned id_base, std::uint64_t vertex_count) {
  LineScanner lines(text);
  return parse_vertex_values(lines, display_name, id_base, vertex_count, kCoordinateFile);
}

std::vector<std::int64_t> parse_dimacs_co(TextSource& source, const std::string& display_name,
                                          unsigned id_base, std::uint64_t vertex_count) {
  LineScanner lines(source);
  return parse_vertex_values(lines, display_name, id_base, vertex_count, kCoordinateFile);
}

namespace {

// One .gr file opened and parsed on its own (no reference, no arc lines), or how that failed.
struct ParsedGr {
  std::optional<InputFacts> facts;
  DimacsGraph graph;
  std::exception_ptr error;
};

ParsedGr parse_gr_file(const std::string& path, unsigned id_base, ReadProgress& read) {
  ParsedGr out;
  try {
    InputFile file(path);  // unmapped again as soon as it is parsed
    file.count_into(&read);
    out.facts = file.facts();
    out.graph = naming_input_on_out_of_memory(file.display_name(), [&] {
      return parse_dimacs_gr(file, file.size_hint(), file.display_name(), id_base, nullptr, false);
    });
  } catch (...) {
    out.error = std::current_exception();
  }
  return out;
}

// Every file parsed, on up to hardware_concurrency threads.
std::vector<ParsedGr> parse_gr_files(const std::vector<std::string>& paths, unsigned id_base,
                                     ReadProgress& read) {
  std::vector<ParsedGr> parsed(paths.size());
  const std::size_t threads =
      std::min<std::size_t>(paths.size(), std::max(1u, std::thread::hardware_concurrency()));
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i = next++; i < paths.size(); i = next++)
      parsed[i] = parse_gr_file(paths[i], id_base, read);
  };
  std::vector<std::thread> pool;
  for (std::size_t k = 1; k < threads; ++k) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  return parsed;
}

bool same_arcs(const DimacsGraph& a, const DimacsGraph& b) {
  return a.vertex_count == b.vertex_count && a.tails == b.tails && a.heads == b.heads;
}

}  // namespace

GraphInput convert_dimacs(const DimacsOptions& options) {
  if (options.gr_files.empty()) throw Error("convert dimacs: no .gr file given");
  if (options.id_base > 1) throw Error("convert dimacs: --id-base must be 0 or 1");
  GraphInput out;
  // Each file is parsed on its own, in parallel. A later file that fails or disagrees with the
  // first is parsed again against it, sequentially, which gives the message (and the first of
  // several errors) a file-by-file parse gives; the first file's arc lines, which that message
  // cites, are found by scanning it again.
  auto read_files = options.gr_files;
  if (options.co_file) read_files.push_back(*options.co_file);
  ReadProgress read(options.progress, read_files);
  auto parsed = parse_gr_files(options.gr_files, options.id_base, read);
  DimacsGraph first;
  std::vector<Column> columns;
  for (std::size_t i = 0; i < parsed.size(); ++i) {
    auto& p = parsed[i];
    if (i == 0) {
      if (p.error) std::rethrow_exception(p.error);
      first = std::move(p.graph);
    } else if (p.error || !same_arcs(first, p.graph)) {
      const std::string& first_name = parsed[0].facts->display_name;
      naming_input_on_out_of_memory(options.gr_files[i], [&] {
        InputFile reference_file(options.gr_files[0]);
        first.arc_lines = dimacs_arc_lines(reference_file);
        InputFile file(options.gr_files[i]);
        const DimacsReference ref{&first_name, &first};
        (void)parse_dimacs_gr(file, file.size_hint(), file.display_name(), options.id_base, &ref,
                              false);
      });
      if (p.error) std::rethrow_exception(p.error);
      throw Error(p.facts->display_name + ": internal error: the arcs differ from " + first_name +
                  " but no line says where");
    }
    record_input(out.metadata, i, *p.facts);
    auto& g = i == 0 ? first : p.graph;
    // A later file without arcs adds no column (as many as the first file's, which are moved out).
    if (i > 0 && g.tails.empty()) g.columns.clear();
    for (auto& c : g.columns) columns.push_back(std::move(c));
    g.columns.clear();
    if (i > 0) p.graph = DimacsGraph{};
  }
  if (!options.objectives.empty() && options.objectives.size() != columns.size())
    throw Error("convert dimacs: " + plural(options.objectives.size(), "objective name") +
                " given, the input has " + plural(columns.size(), "cost column"));
  out.vertex_count = first.vertex_count;
  out.tails = std::move(first.tails);
  out.heads = std::move(first.heads);
  for (std::size_t j = 0; j < columns.size(); ++j) {
    CostColumn c;
    if (options.objectives.empty()) {
      c.name = "c" + std::to_string(j + 1);
    } else {
      c.name = options.objectives[j].name;
      c.unit = options.objectives[j].unit;
    }
    c.values = std::move(columns[j]);
    c.forced_type = options.cost_type;
    out.costs.push_back(std::move(c));
  }
  auto& m = out.metadata;
  if (options.co_file) {
    InputFile input(*options.co_file);
    input.count_into(&read);
    record_input(m, options.gr_files.size(), input.facts());
    const auto xy = naming_input_on_out_of_memory(input.display_name(), [&] {
      return parse_dimacs_co(input, input.display_name(), options.id_base, out.vertex_count);
    });
    out.vertex_data.push_back(narrowest_column<std::int32_t, std::int64_t>("coords", 2, xy));
    m.set("coords.scale", "1e-6");
    m.set("coords.unit", "degree");
  }
  m.set("benchmark",
        options.name
            ? *options.name
            : benchmark_name_from(std::filesystem::path(options.gr_files[0]).filename().string(),
                                  {".gr"}));
  m.set("family", "road");
  m.set("id_base", std::to_string(options.id_base));
  m.set("source.command", "convert dimacs");
  m.set("source.param.id_base", std::to_string(options.id_base));
  if (options.name) m.set("source.param.name", *options.name);
  if (!options.objectives.empty())
    m.set("source.param.objectives", objective_list(options.objectives));
  if (options.cost_type) m.set("source.param.cost_type", format::to_string(*options.cost_type));
  return out;
}

}  // namespace mosb::converters
