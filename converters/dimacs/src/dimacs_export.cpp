#include "mosb/converters/dimacs_export.hpp"

#include <charconv>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
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
    if (*options.id_base > 1) throw Error("export dimacs: --id-base must be 0 or 1");
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

void export_objective(const std::filesystem::path& path, const GraphReader& reader, std::size_t j,
                      const std::string& benchmark, unsigned id_base) {
  const auto& section = reader.objective(j);
  const auto m = reader.arc_count();
  AtomicTextFile out(path);
  write_header_comments(out, reader, benchmark);
  const auto unit = reader.metadata().get("objective." + section.name + ".unit").value_or("");
  out << "c objective " << section.name << (unit.empty() ? "" : " unit " + comment_safe(unit))
      << "\n";
  out << "p sp " << reader.vertex_count() << " " << m << "\n";
  const auto offsets = reader.forward_offsets();
  const auto targets = reader.forward_targets();
  const bool real = format::is_float(section.type);
  std::vector<std::uint64_t> integers(real ? 0 : m);
  std::vector<double> reals(real ? m : 0);
  if (real)
    reader.read_cost_as(j, reals);
  else
    reader.read_cost_as(j, integers);
  for (std::uint64_t v = 0; v < reader.vertex_count(); ++v)
    for (auto a = offsets[v]; a < offsets[v + 1]; ++a) {
      out << "a " << (v + id_base) << " " << (std::uint64_t{targets[a]} + id_base) << " ";
      if (real)
        out << format_real_cost(reals[a]);
      else
        out << integers[a];
      out << "\n";
    }
  out.commit();
}

void export_queries(const std::filesystem::path& path, const GraphReader& reader,
                    const std::string& set, unsigned id_base) {
  AtomicTextFile out(path);
  for (const auto& q : reader.queries(set))
    out << (std::uint64_t{q.start} + id_base) << " " << (std::uint64_t{q.goal} + id_base) << "\n";
  out.commit();
}

}  // namespace

std::string format_real_cost(double value) {
  char text[64];
  const auto r = std::to_chars(text, text + sizeof text, value);
  std::string out(text, r.ptr);
  // Without '.' or an exponent `convert dimacs` would read an integer column.
  if (out.find_first_of(".eEn") == std::string::npos) out += ".0";
  return out;
}

std::vector<std::filesystem::path> export_dimacs(const std::filesystem::path& instance,
                                                 const DimacsExportOptions& options,
                                                 const Progress& progress) {
  // The export walks the CSR and copies costs: only a file whose payload passes verify.
  const auto reader = GraphReader::open(instance, VerifyLevel::full);
  const auto benchmark = file_stem_for(reader, instance);
  const auto id_base = export_id_base(reader, options);

  std::vector<std::size_t> objectives;
  std::vector<std::string> query_sets;
  if (const auto view = select_view(reader, options.selection)) {
    objectives = view->objectives;
    if (!view->query_set.empty()) query_sets.push_back(view->query_set);
  } else {
    for (std::size_t j = 0; j < reader.objective_count(); ++j) objectives.push_back(j);
    for (const auto* s : reader.all(SectionKind::queries)) query_sets.push_back(s->name);
  }

  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) throw Error(options.out_dir.string() + ": cannot create the directory: " + ec.message());
  std::vector<std::filesystem::path> written;
  const auto* coords = reader.find(SectionKind::vertex_data, "coords");
  const std::uint64_t file_count = objectives.size() + (coords ? 1 : 0) + query_sets.size();
  report(progress, "export", 0, file_count);
  for (auto j : objectives) {
    written.push_back(options.out_dir / (benchmark + "-" + reader.objective(j).name + ".gr"));
    check_output_is_not_input(written.back(), {instance});
    export_objective(written.back(), reader, j, benchmark, id_base);
    report(progress, "export", written.size(), file_count);
  }
  if (coords) {
    written.push_back(options.out_dir / (benchmark + ".co"));
    check_output_is_not_input(written.back(), {instance});
    export_coordinates(written.back(), reader, *coords, benchmark, id_base);
    report(progress, "export", written.size(), file_count);
  }
  for (const auto& set : query_sets) {
    written.push_back(options.out_dir / (benchmark + "-" + set + ".queries"));
    check_output_is_not_input(written.back(), {instance});
    export_queries(written.back(), reader, set, id_base);
    report(progress, "export", written.size(), file_count);
  }
  return written;
}

}  // namespace mosb::converters
