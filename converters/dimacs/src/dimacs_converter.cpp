#include "mosb/converters/dimacs_converter.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <charconv>
#include <exception>
#include <limits>
#include <memory>
#include <string>

#include "mosb/converters/narrow_column.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/internal/parallel.hpp"
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

// One pass over a .gr text: `p sp n m` once, then `a u v c1 .. cd` lines (all with the same d),
// comments anywhere. With a reference (the first file of a per-objective pair), every arc must be
// the reference's arc at the same index.
class GrParser {
 public:
  GrParser(std::uint64_t size_hint, const std::string& display_name, unsigned id_base,
           const DimacsReference* reference, bool record_arc_lines)
      : size_hint_(size_hint),
        file_(display_name),
        id_base_(id_base),
        reference_(reference),
        record_arc_lines_(record_arc_lines) {
    if (id_base > 1) throw Error(display_name + ": id base must be 0 or 1");
  }

  DimacsGraph parse(LineScanner& lines) {
    std::string_view line;
    while (lines.next(line)) {
      const auto ln = lines.number();
      if (fast_integer_arc(line, ln)) continue;
      tokenize(line, t_);
      if (t_.empty() || t_[0].text == "c") continue;
      const auto end_column = line.size() + 1;
      if (t_[0].text == "a")
        arc_line(ln, end_column);
      else if (t_[0].text == "p")
        problem_line(ln, end_column);
      else
        fail(file_, ln, t_[0].column, "unknown line type " + quoted(t_[0].text));
    }
    return finish(lines.number());
  }

 private:
  // The common case without tokenizing: all columns integers so far, an arc the reference agrees
  // with. Anything else takes the general path, which reports the precise error.
  bool fast_integer_arc(std::string_view line, std::uint64_t ln) {
    if (integer_columns_.empty() || line.size() <= 1 || line[0] != 'a') return false;
    std::uint32_t u = 0, v = 0;
    if (!scan_integer_arc(line, cost_count_, id_base_, g_.vertex_count, u, v, fast_costs_.data()))
      return false;
    const auto k = g_.tails.size();
    const bool matches_reference =
        !reference_ || (k < reference_->graph->tails.size() && reference_->graph->tails[k] == u &&
                        reference_->graph->heads[k] == v);
    if (!matches_reference || k >= kMaxCount) return false;
    for (std::size_t j = 0; j < cost_count_; ++j) integer_columns_[j]->push_back(fast_costs_[j]);
    g_.tails.push_back(u);
    g_.heads.push_back(v);
    if (record_arc_lines_) g_.arc_lines.push_back(ln);
    return true;
  }

  void arc_line(std::uint64_t ln, std::size_t end_column) {
    if (p_line_ == 0) fail(file_, ln, t_[0].column, "arc line before the 'p sp' line");
    if (t_.size() < 4) {
      if (t_.size() >= 2) parse_id(file_, ln, t_[1], id_base_, g_.vertex_count);
      if (t_.size() >= 3) parse_id(file_, ln, t_[2], id_base_, g_.vertex_count);
      fail(file_, ln, end_column, "missing field: an arc line is 'a u v cost...'");
    }
    check_cost_count(ln, end_column);
    const auto u = parse_id(file_, ln, t_[1], id_base_, g_.vertex_count);
    const auto v = parse_id(file_, ln, t_[2], id_base_, g_.vertex_count);
    for (std::size_t j = 0; j < cost_count_; ++j) add_cost(file_, ln, t_[3 + j], g_.columns[j]);
    if (g_.tails.size() >= kMaxCount)
      fail(file_, ln, t_[0].column, "more than " + std::to_string(kMaxCount) + " arcs");
    if (reference_) check_reference_arc(ln, u, v);
    g_.tails.push_back(u);
    g_.heads.push_back(v);
    if (record_arc_lines_) g_.arc_lines.push_back(ln);
    // The fast path applies again once every column is (still) integer.
    integer_columns_.clear();
    for (auto& c : g_.columns)
      if (auto* ints = std::get_if<std::vector<std::uint64_t>>(&c))
        integer_columns_.push_back(ints);
    if (integer_columns_.size() != cost_count_ || cost_count_ == 0) integer_columns_.clear();
    fast_costs_.resize(cost_count_);
  }

  // The first arc line fixes the number of cost columns; every later one must have as many.
  void check_cost_count(std::uint64_t ln, std::size_t end_column) {
    if (first_arc_line_ == 0) {
      first_arc_line_ = ln;
      cost_count_ = t_.size() - 3;
      g_.columns.assign(cost_count_, Column{});
      for (auto& c : g_.columns) {
        auto& values = std::get<std::vector<std::uint64_t>>(c);
        values.reserve(g_.tails.capacity());
        advise_huge_pages(values);
      }
      return;
    }
    if (t_.size() - 3 == cost_count_) return;
    const std::string expected = "expected " + plural(cost_count_, "cost") + " as on line " +
                                 std::to_string(first_arc_line_);
    if (t_.size() - 3 < cost_count_) fail(file_, ln, end_column, "missing field: " + expected);
    fail(file_, ln, t_[3 + cost_count_].column,
         "extra field " + quoted(t_[3 + cost_count_].text) + ": " + expected);
  }

  void check_reference_arc(std::uint64_t ln, std::uint32_t u, std::uint32_t v) const {
    const auto& ref = *reference_->graph;
    const auto k = g_.tails.size();
    if (k >= ref.tails.size())
      fail(
          file_, ln, t_[1].column,
          "arc beyond the " + plural(ref.tails.size(), "arc") + " of " + *reference_->display_name);
    if (ref.tails[k] != u || ref.heads[k] != v)
      fail(file_, ln, t_[1].column,
           "arc " + std::to_string(u + id_base_) + " " + std::to_string(v + id_base_) +
               " differs from arc " + std::to_string(ref.tails[k] + id_base_) + " " +
               std::to_string(ref.heads[k] + id_base_) + " at " + *reference_->display_name + ":" +
               std::to_string(ref.arc_lines[k]) +
               " (per-objective files must list the same arcs in the same order)");
  }

  void problem_line(std::uint64_t ln, std::size_t end_column) {
    if (p_line_ != 0)
      fail(file_, ln, t_[0].column,
           "second 'p' line (the first is line " + std::to_string(p_line_) + ")");
    if (t_.size() < 2) fail(file_, ln, end_column, "missing field: the header is 'p sp n m'");
    if (t_[1].text != "sp")
      fail(file_, ln, t_[1].column, "expected 'sp' after 'p', found " + quoted(t_[1].text));
    if (t_.size() < 4) fail(file_, ln, end_column, "missing field: the header is 'p sp n m'");
    if (t_.size() > 4)
      fail(file_, ln, t_[4].column,
           "extra field " + quoted(t_[4].text) + ": the header is 'p sp n m'");
    g_.vertex_count = parse_count(file_, ln, t_[2], "vertex count");
    declared_arcs_ = parse_count(file_, ln, t_[3], "arc count");
    check_declared_vertices(file_, ln, t_[2].column, g_.vertex_count);
    p_line_ = ln;
    m_column_ = t_[3].column;
    if (reference_) {
      const auto& ref = *reference_->graph;
      if (g_.vertex_count != ref.vertex_count)
        fail(file_, ln, t_[2].column,
             "declares " + plural(g_.vertex_count, "vertex") + ", " + *reference_->display_name +
                 " has " + std::to_string(ref.vertex_count));
      if (declared_arcs_ != ref.tails.size())
        fail(file_, ln, t_[3].column,
             "declares " + plural(declared_arcs_, "arc") + ", " + *reference_->display_name +
                 " has " + std::to_string(ref.tails.size()));
    }
    // The header is untrusted: reserve no more than the text could hold (a line is >= 8 bytes).
    const auto reserve = std::min<std::uint64_t>(declared_arcs_, size_hint_ / 8 + 1);
    g_.tails.reserve(reserve);
    g_.heads.reserve(reserve);
    if (record_arc_lines_) g_.arc_lines.reserve(reserve);
    advise_huge_pages(g_.tails);
    advise_huge_pages(g_.heads);
  }

  DimacsGraph finish(std::uint64_t last_line) {
    if (p_line_ == 0) fail(file_, std::max<std::uint64_t>(last_line, 1), 1, "no 'p sp n m' line");
    if (g_.tails.size() != declared_arcs_)
      fail(file_, p_line_, m_column_,
           "the header declares " + plural(declared_arcs_, "arc") + ", found " +
               std::to_string(g_.tails.size()));
    if (first_arc_line_ == 0)  // no arcs at all: as many (zero) columns as the reference, or one
      g_.columns.assign(reference_ ? reference_->graph->columns.size() : 1, Column{});
    return std::move(g_);
  }

  const std::uint64_t size_hint_;
  const std::string& file_;
  const unsigned id_base_;
  const DimacsReference* const reference_;
  const bool record_arc_lines_;
  DimacsGraph g_;
  std::vector<Token> t_;
  std::uint64_t p_line_ = 0, m_column_ = 0, declared_arcs_ = 0, first_arc_line_ = 0;
  std::size_t cost_count_ = 0;
  std::vector<std::vector<std::uint64_t>*> integer_columns_;  // all columns, while all are integers
  std::vector<std::uint64_t> fast_costs_;
};

DimacsGraph parse_gr(LineScanner& lines, std::uint64_t size_hint, const std::string& display_name,
                     unsigned id_base, const DimacsReference* reference, bool record_arc_lines) {
  return GrParser(size_hint, display_name, id_base, reference, record_arc_lines).parse(lines);
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
  parallel_for(paths.size(), thread_count(0),
               [&](std::size_t i) { parsed[i] = parse_gr_file(paths[i], id_base, read); });
  return parsed;
}

bool same_arcs(const DimacsGraph& a, const DimacsGraph& b) {
  return a.vertex_count == b.vertex_count && a.tails == b.tails && a.heads == b.heads;
}

}  // namespace

GraphInput convert_dimacs(const DimacsOptions& options) {
  if (options.gr_files.empty()) throw Error("convert dimacs: no .gr file given");
  if (options.id_base > 1)
    throw Error(ErrorCode::other, {"convert dimacs: ", setting("id_base"), " must be 0 or 1"});
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
