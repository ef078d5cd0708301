#include "mosb/converters/dimacs_export.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/number_text.hpp"
#include "mosb/version.hpp"

namespace mosb::converters {

namespace {

using format::ElementType;
using format::SectionKind;

// Buffered text over an AtomicFile: appears under its name at commit(), complete, or not at all.
class AtomicTextFile {
 public:
  explicit AtomicTextFile(const std::filesystem::path& path) : file_(path) {
    buffer_.reserve(kFlushAt + 256);
  }

  AtomicTextFile& operator<<(std::string_view text) {
    buffer_ += text;
    if (buffer_.size() >= kFlushAt) flush();
    return *this;
  }
  AtomicTextFile& operator<<(std::uint64_t value) {
    char digits[24];
    const auto r = std::to_chars(digits, digits + sizeof digits, value);
    return *this << std::string_view(digits, static_cast<std::size_t>(r.ptr - digits));
  }
  AtomicTextFile& operator<<(std::int64_t value) {
    char digits[24];
    const auto r = std::to_chars(digits, digits + sizeof digits, value);
    return *this << std::string_view(digits, static_cast<std::size_t>(r.ptr - digits));
  }

  void commit() {
    flush();
    file_.commit();
  }

 private:
  static constexpr std::size_t kFlushAt = 1 << 20;
  void flush() {
    file_.write(buffer_);
    buffer_.clear();
  }

  AtomicFile file_;
  std::string buffer_;
};

// Metadata text in a `c` line: control characters would end the line, so they become '?'.
std::string comment_safe(std::string_view text) {
  std::string out;
  for (char c : text) out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) ? '?' : c;
  return out;
}

std::string file_stem_for(const GraphReader& reader, const std::filesystem::path& instance) {
  auto name = reader.metadata().get("benchmark").value_or(instance.stem().string());
  bool usable = !name.empty() && name != "." && name != "..";
  for (char c : name) usable &= c != '/' && c != '\\' && static_cast<unsigned char>(c) >= 0x20;
  if (!usable)
    throw Error(reader.display_name() + ": benchmark name '" + comment_safe(name) +
                "' cannot name a file");
  return name;
}

unsigned export_id_base(const GraphReader& reader, const DimacsExportOptions& options) {
  if (options.id_base) {
    if (*options.id_base > 1)
      throw Error(ErrorCode::other, {"export dimacs: ", setting("id_base"), " must be 0 or 1"});
    return *options.id_base;
  }
  const auto stored = reader.metadata().get("id_base");
  if (!stored) return 1;
  if (*stored != "0" && *stored != "1")
    throw Error(reader.display_name() + ": metadata id_base '" + comment_safe(*stored) +
                "' is not 0 or 1");
  return *stored == "0" ? 0 : 1;
}

void write_header_comments(AtomicTextFile& out, const GraphReader& reader,
                           const std::string& benchmark) {
  out << "c written by mosb " << kVersion << " (export dimacs) from benchmark "
      << comment_safe(benchmark) << "\n";
  out << "c instance digest " << reader.digest() << "\n";
}

template <class T>
void write_coordinates(AtomicTextFile& out, const GraphReader& reader, const Section& coords,
                       unsigned id_base) {
  const auto xy = reader.values<T>(coords);
  for (std::uint64_t v = 0; v < reader.vertex_count(); ++v) {
    out << "v " << (v + id_base);
    for (std::size_t k = 0; k < 2; ++k) {
      if constexpr (std::is_floating_point_v<T>)
        out << " " << format_real_cost(static_cast<double>(xy[2 * v + k]));
      else if constexpr (std::is_signed_v<T>)
        out << " " << static_cast<std::int64_t>(xy[2 * v + k]);
      else
        out << " " << static_cast<std::uint64_t>(xy[2 * v + k]);
    }
    out << "\n";
  }
}

void export_coordinates(const std::filesystem::path& path, const GraphReader& reader,
                        const Section& coords, const std::string& benchmark, unsigned id_base) {
  if (coords.entry.row_width != 2)
    throw Error(reader.display_name() + ": vertex data 'coords' has width " +
                std::to_string(coords.entry.row_width) + ", a .co needs 2");
  AtomicTextFile out(path);
  write_header_comments(out, reader, benchmark);
  const auto& meta = reader.metadata();
  out << "c coordinate scale " << comment_safe(meta.get("coords.scale").value_or("1")) << " unit "
      << comment_safe(meta.get("coords.unit").value_or("")) << "\n";
  out << "p aux sp co " << reader.vertex_count() << "\n";
  format::visit_element_type(coords.type, [&](auto tag) {
    write_coordinates<typename decltype(tag)::type>(out, reader, coords, id_base);
  });
  out.commit();
}

// The costs of one objective as the text writes them: integers (stored integers, or float costs
// × scale rounded) or reals (the shortest round-trip text).
struct CostColumn {
  std::string name;
  bool real = false;
  std::vector<std::uint64_t> integers;
  std::vector<double> reals;

  long double value(std::uint64_t arc) const {
    return real ? static_cast<long double>(reals[arc]) : static_cast<long double>(integers[arc]);
  }
};

constexpr std::uint64_t kExactDoubleLimit = std::uint64_t{1} << 53;

CostColumn read_column(const GraphReader& reader, std::size_t j, const DimacsExportOptions& o,
                       unsigned id_base) {
  const auto& section = reader.objective(j);
  CostColumn column;
  column.name = section.name;
  const auto m = reader.arc_count();
  const bool real = format::is_float(section.type);
  const auto where = [&](std::uint64_t arc) {
    const auto offsets = reader.forward_offsets();
    const auto tail = static_cast<std::uint64_t>(
        std::upper_bound(offsets.begin(), offsets.end(), arc) - offsets.begin() - 1);
    return " (arc " + std::to_string(tail + id_base) + " -> " +
           std::to_string(std::uint64_t{reader.forward_targets()[arc]} + id_base) + ")";
  };
  if (real && o.integer_costs && !(o.scale > 0))
    throw Error(ErrorCode::other,
                {reader.display_name() + ": objective '" + section.name +
                     "' holds float costs and the solver reads integer costs only: give ",
                 setting("scale"),
                 " K (costs x K, rounded to integers; the solver's values are divided back)"});
  if (real && !(o.scale > 0)) {
    column.real = true;
    column.reals.resize(m);
    reader.read_cost_as(j, column.reals);
    return column;
  }
  column.integers.resize(m);
  if (real) {
    std::vector<double> reals(m);
    reader.read_cost_as(j, reals);
    for (std::uint64_t a = 0; a < m; ++a) {
      const double scaled = reals[a] * o.scale;
      if (!std::isfinite(scaled) || scaled < 0 || scaled >= static_cast<double>(kExactDoubleLimit))
        throw Error(reader.display_name() + ": objective '" + section.name + "': cost " +
                    format_real_cost(reals[a]) + " x " + format_real_cost(o.scale) +
                    " is not an integer in [0, 2^53)" + where(a));
      column.integers[a] = static_cast<std::uint64_t>(std::llround(scaled));
    }
  } else {
    reader.read_cost_as(j, column.integers);
  }
  if (o.max_arc_cost)
    for (std::uint64_t a = 0; a < m; ++a)
      if (column.integers[a] > *o.max_arc_cost)
        throw Error(reader.display_name() + ": objective '" + section.name + "': cost " +
                    std::to_string(column.integers[a]) + " is above " +
                    std::to_string(*o.max_arc_cost) + ", the largest the solver reads" + where(a));
  return column;
}

// One arc line of the text: its ends (0-based) and the instance arc whose costs it carries.
struct TextArc {
  std::uint64_t tail, head, arc;
};
constexpr std::uint64_t kZeroCost = ~std::uint64_t{0};  // a subdivision's second half, the dummy

// Whether arc `b`'s costs dominate or equal arc `a`'s over `columns`.
bool covers(const std::vector<CostColumn>& columns, std::uint64_t b, std::uint64_t a) {
  for (const auto& c : columns)
    if (c.value(b) > c.value(a)) return false;
  return true;
}

// The out-arcs of `v` with `collapse`: per head, the arcs no other of the pair covers (of equal
// ones the first), the first kept direct and each other one through a new vertex.
void plan_collapsed(const GraphReader& reader, const std::vector<CostColumn>& columns,
                    std::uint64_t v, std::vector<TextArc>& arcs, std::vector<TextArc>& halves,
                    std::uint64_t& next_vertex) {
  const auto offsets = reader.forward_offsets();
  const auto targets = reader.forward_targets();
  std::vector<std::uint64_t> out;
  for (auto a = offsets[v]; a < offsets[v + 1]; ++a) out.push_back(a);
  std::stable_sort(out.begin(), out.end(), [&](auto x, auto y) { return targets[x] < targets[y]; });
  for (std::size_t i = 0; i < out.size();) {
    std::size_t end = i;
    while (end < out.size() && targets[out[end]] == targets[out[i]]) ++end;
    bool direct = true;
    for (std::size_t k = i; k < end; ++k) {
      bool covered = false;
      for (std::size_t l = i; l < end && !covered; ++l)
        covered = l != k && covers(columns, out[l], out[k]) &&
                  (l < k || !covers(columns, out[k], out[l]));
      if (covered) continue;
      if (direct) {
        arcs.push_back({v, targets[out[k]], out[k]});
        direct = false;
      } else {
        arcs.push_back({v, next_vertex, out[k]});
        halves.push_back({next_vertex++, targets[out[k]], kZeroCost});
      }
    }
    i = end;
  }
}

// The arc lines of the text, in the order written, and its vertex count.
std::vector<TextArc> plan_arcs(const GraphReader& reader, const std::vector<CostColumn>& columns,
                               const DimacsExportOptions& o, std::uint64_t& vertex_count) {
  const auto offsets = reader.forward_offsets();
  const auto targets = reader.forward_targets();
  std::vector<TextArc> arcs, halves;
  arcs.reserve(reader.arc_count() + (o.append_dummy_arc ? 1 : 0));
  vertex_count = reader.vertex_count();
  for (std::uint64_t v = 0; v < reader.vertex_count(); ++v) {
    if (o.collapse_parallel_arcs) {
      plan_collapsed(reader, columns, v, arcs, halves, vertex_count);
      continue;
    }
    for (auto a = offsets[v]; a < offsets[v + 1]; ++a) arcs.push_back({v, targets[a], a});
  }
  arcs.insert(arcs.end(), halves.begin(), halves.end());
  if (o.append_dummy_arc) {
    arcs.push_back({vertex_count, vertex_count + 1, kZeroCost});
    vertex_count += 2;
  }
  return arcs;
}

void write_cost(AtomicTextFile& out, const CostColumn& column, std::uint64_t arc) {
  if (arc == kZeroCost)
    out << (column.real ? std::string_view("0.0") : std::string_view("0"));
  else if (column.real)
    out << format_real_cost(column.reals[arc]);
  else
    out << column.integers[arc];
}

// What the text holds: its arcs and the comments every .gr of it carries.
// What the text holds: its arcs and the comments every .gr of it carries.
struct TextGraph {
  std::vector<CostColumn> columns;
  std::vector<TextArc> arcs;
  std::uint64_t vertex_count = 0;
  unsigned id_base = 1;
  std::vector<std::string> comments;  // the same in every file, so line numbers agree
};

// Refuses a vertex of the text with more than `max_degree` arcs out or in.
void check_degrees(const GraphReader& reader, const TextGraph& g, std::uint64_t max_degree) {
  std::vector<std::uint64_t> out(g.vertex_count), in(g.vertex_count);
  for (const auto& arc : g.arcs) {
    for (auto* count : {&out[arc.tail], &in[arc.head]})
      if (++*count > max_degree)
        throw Error(reader.display_name() + ": vertex " +
                    std::to_string((count == &out[arc.tail] ? arc.tail : arc.head) + g.id_base) +
                    " has more than " + std::to_string(max_degree) + " arcs " +
                    (count == &out[arc.tail] ? "out" : "in") + ", the most the solver holds");
  }
}

// `columns` of the text's objectives into `path` (one per objective, or all in one file), with
// `padding` columns of 0 after them.
void write_gr(const std::filesystem::path& path, const GraphReader& reader, const TextGraph& g,
              const std::vector<std::size_t>& columns, unsigned padding,
              const std::string& benchmark) {
  AtomicTextFile out(path);
  write_header_comments(out, reader, benchmark);
  for (const auto& comment : g.comments) out << "c " << comment << "\n";
  out << "c objective" << (columns.size() > 1 ? "s" : "");
  for (const auto k : columns) {
    const auto& name = g.columns[k].name;
    const auto unit = reader.metadata().get("objective." + name + ".unit").value_or("");
    out << " " << name << (unit.empty() ? "" : " unit " + comment_safe(unit));
  }
  if (padding > 0) out << ", then " << std::uint64_t{padding} << " columns of 0";
  out << "\n";
  out << "p sp " << g.vertex_count << " " << std::uint64_t{g.arcs.size()} << "\n";
  for (const auto& arc : g.arcs) {
    out << "a " << (arc.tail + g.id_base) << " " << (arc.head + g.id_base);
    for (const auto k : columns) {
      out << " ";
      write_cost(out, g.columns[k], arc.arc);
    }
    for (unsigned p = 0; p < padding; ++p) out << " 0";
    out << "\n";
  }
  out.commit();
}

void export_queries(const std::filesystem::path& path, const GraphReader& reader,
                    const std::string& set, unsigned id_base, QueriesFormat format) {
  AtomicTextFile out(path);
  const std::string_view separator = format == QueriesFormat::comma ? "," : " ";
  for (const auto& q : reader.queries(set))
    out << (std::uint64_t{q.start} + id_base) << separator << (std::uint64_t{q.goal} + id_base)
        << "\n";
  out.commit();
}

// The comments that say how the text differs from the instance.
std::vector<std::string> text_comments(const GraphReader& reader, const DimacsExportOptions& o,
                                       const DimacsExportFiles& files) {
  std::vector<std::string> comments;
  if (!files.scaled_objectives.empty()) {
    std::string names;
    for (const auto& name : files.scaled_objectives) names += " " + name;
    comments.push_back("costs x " + format_real_cost(o.scale) + ", rounded to integers:" + names);
  }
  const auto own = reader.vertex_count();
  const auto dummy = o.append_dummy_arc ? 2 : 0;
  if (files.vertex_count > own + dummy)
    comments.push_back("vertices " + std::to_string(own + files.id_base) + " to " +
                       std::to_string(files.vertex_count - dummy - 1 + files.id_base) +
                       " subdivide parallel arcs");
  if (o.append_dummy_arc)
    comments.emplace_back("the last arc joins two vertices of no query (a reader's workaround)");
  return comments;
}

}  // namespace

std::string format_real_cost(double value) {
  std::string out = shortest_text(value);
  // Without '.' or an exponent `convert dimacs` would read an integer column.
  if (out.find_first_of(".eEn") == std::string::npos) out += ".0";
  return out;
}

DimacsExportFiles export_dimacs_files(const std::filesystem::path& instance,
                                      const DimacsExportOptions& options,
                                      const Progress& progress) {
  // The export walks the CSR and copies costs: only a file whose payload passes verify.
  const auto reader = GraphReader::open(instance, VerifyLevel::full);
  const auto benchmark = file_stem_for(reader, instance);
  DimacsExportFiles files;
  files.id_base = export_id_base(reader, options);

  std::vector<std::size_t> objectives;
  std::vector<std::string> query_sets;
  if (const auto view = select_view(reader, options.selection)) {
    objectives = view->objectives;
    if (!view->query_set.empty()) query_sets.push_back(view->query_set);
  } else {
    for (std::size_t j = 0; j < reader.objective_count(); ++j) objectives.push_back(j);
    for (const auto* s : reader.all(SectionKind::queries)) query_sets.push_back(s->name);
  }
  if (options.multi_column && options.pad_columns > 0 && objectives.size() > options.pad_columns)
    throw Error(reader.display_name() + ": " + std::to_string(objectives.size()) +
                " objectives, and the text has " + std::to_string(options.pad_columns) +
                " cost columns");

  TextGraph g;
  g.id_base = files.id_base;
  for (const auto j : objectives) {
    g.columns.push_back(read_column(reader, j, options, files.id_base));
    if (options.scale > 0 && format::is_float(reader.objective(j).type))
      files.scaled_objectives.push_back(g.columns.back().name);
  }
  if (options.scale > 0 && files.scaled_objectives.empty())
    throw Error(ErrorCode::other, {reader.display_name() + ": ", setting("scale"),
                                   ": no objective of the selection holds float costs (integer "
                                   "costs are written as they are)"});
  g.arcs = plan_arcs(reader, g.columns, options, g.vertex_count);
  if (options.max_degree) check_degrees(reader, g, *options.max_degree);
  files.vertex_count = g.vertex_count;
  files.arc_count = g.arcs.size();
  g.comments = text_comments(reader, options, files);

  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) throw Error(options.out_dir.string() + ": cannot create the directory: " + ec.message());
  const auto* coords =
      options.coordinates ? reader.find(SectionKind::vertex_data, "coords") : nullptr;
  const std::uint64_t file_count =
      (options.multi_column ? 1 : objectives.size()) + (coords ? 1 : 0) + query_sets.size();
  const auto add = [&](const std::filesystem::path& path) {
    check_output_is_not_input(path, {instance});
    files.written.push_back(path);
  };
  const auto done = [&] { report(progress, "export", files.written.size(), file_count); };
  done();
  if (options.multi_column) {
    add(options.out_dir / (benchmark + ".gr"));
    std::vector<std::size_t> all(g.columns.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
    const auto columns = static_cast<unsigned>(all.size());
    write_gr(files.written.back(), reader, g, all,
             options.pad_columns > columns ? options.pad_columns - columns : 0, benchmark);
    files.multi_column = files.written.back();
    done();
  } else {
    for (std::size_t k = 0; k < g.columns.size(); ++k) {
      add(options.out_dir / (benchmark + "-" + g.columns[k].name + ".gr"));
      write_gr(files.written.back(), reader, g, {k}, 0, benchmark);
      files.objectives.push_back(files.written.back());
      done();
    }
  }
  if (coords) {
    add(options.out_dir / (benchmark + ".co"));
    export_coordinates(files.written.back(), reader, *coords, benchmark, files.id_base);
    files.coordinates = files.written.back();
    done();
  }
  for (const auto& set : query_sets) {
    add(options.out_dir / (benchmark + "-" + set + ".queries"));
    export_queries(files.written.back(), reader, set, files.id_base, options.queries_format);
    files.queries.emplace_back(set, files.written.back());
    done();
  }
  return files;
}

std::vector<std::filesystem::path> export_dimacs(const std::filesystem::path& instance,
                                                 const DimacsExportOptions& options,
                                                 const Progress& progress) {
  return export_dimacs_files(instance, options, progress).written;
}

}  // namespace mosb::converters
