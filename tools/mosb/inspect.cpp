#include <CLI/CLI.hpp>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/stats.hpp"

namespace mosb::cli {

namespace {

std::string kind_name(const Section& s) {
  return s.kind ? std::string(format::to_string(*s.kind))
                : "unknown(" + std::to_string(s.entry.kind) + ")";
}

// Metadata values are file content: escaped so they cannot move the cursor or fake a line.
std::string shown(const std::optional<std::string>& value) {
  return escape_for_terminal(value.value_or(""));
}

// What inspect checked: nothing past the header, the section table and the metadata unless
// --verify LEVEL was given.
struct Inspection {
  GraphReader reader;
  std::optional<VerifyLevel> verified;
};

// The counts walk the CSR: only on a reader verified in full (nullopt otherwise, and
// for a packed file, which cannot be verified in place and is shown from its table alone).
std::optional<ArcMultiplicity> loops_and_parallel_arcs(const Inspection& i) {
  if (format::is_packed(i.reader.header()) || !i.verified ||
      !covers(*i.verified, VerifyLevel::full))
    return std::nullopt;
  return count_loops_and_parallel_arcs(i.reader);
}

std::string verified_text(const Inspection& i) {
  if (!i.verified)
    return "no (the header, the section table and the metadata only; --verify LEVEL or mosb "
           "verify checks the rest)";
  return std::string(kVerifyLevelNames.name(*i.verified));
}

std::string version(const GraphReader& r) {
  return std::to_string(r.header().version_major) + "." + std::to_string(r.header().version_minor);
}

void print_text(const Inspection& inspection) {
  const auto& r = inspection.reader;
  const auto& metadata = r.metadata();
  std::cout << "file        " << r.display_name() << '\n'
            << "format      " << version(r) << "\n"
            << "digest      " << r.digest() << '\n'
            << "benchmark   " << shown(metadata.get("benchmark")) << '\n'
            << "family      " << shown(metadata.get("family")) << '\n'
            << "vertices    " << r.vertex_count() << '\n'
            << "arcs        " << r.arc_count() << '\n'
            << "verified    " << verified_text(inspection) << '\n';
  const bool packed = format::is_packed(r.header());
  if (const auto multiplicity = loops_and_parallel_arcs(inspection))
    std::cout << "self-loops  " << multiplicity->self_loops << '\n'
              << "parallel    " << multiplicity->parallel_arcs << " (extra copies of an arc)\n";
  else
    std::cout << "self-loops  n/a (" << (packed ? "packed file" : "--verify full counts them")
              << ")\n"
              << "parallel    n/a (" << (packed ? "packed file" : "--verify full counts them")
              << ")\n";
  std::cout << "objectives  " << r.objective_count() << '\n';
  for (std::size_t i = 0; i < r.objective_count(); ++i) {
    const auto& s = r.objective(i);
    std::cout << "  " << i << "  " << std::left << std::setw(24) << s.name << std::setw(5)
              << format::to_string(s.type) << "unit '"
              << shown(metadata.get("objective." + s.name + ".unit")) << "'\n";
  }
  std::cout << "query sets\n";
  for (const auto* s : r.all(format::SectionKind::queries)) {
    std::cout << "  " << std::left << std::setw(24) << s->name << s->entry.row_count << " queries";
    if (r.find(format::SectionKind::query_reference, s->name)) {
      const std::string key = "queries." + s->name + ".reference.";
      std::cout << ", references for '" << shown(metadata.get(key + "objective")) << "' ("
                << shown(metadata.get(key + "source")) << ")";
    }
    std::cout << '\n';
  }
  std::cout << "sections\n"
            << "  " << std::left << std::setw(16) << "kind" << std::setw(25) << "name"
            << std::setw(5) << "type" << std::right << std::setw(6) << "width" << std::setw(12)
            << "rows" << std::setw(13) << "bytes" << std::setw(13) << "offset"
            << "  checksum\n";
  for (const auto& s : r.sections())
    std::cout << "  " << std::left << std::setw(16) << kind_name(s) << std::setw(25) << s.name
              << std::setw(5) << format::to_string(s.type) << std::right << std::setw(6)
              << s.entry.row_width << std::setw(12) << s.entry.row_count << std::setw(13)
              << s.entry.stored_length << std::setw(13) << s.entry.offset << "  "
              << hex64(s.entry.checksum)
              << (s.is_packed() ? " (" +
                                      std::string(format::to_string(
                                          static_cast<format::Encoding>(s.entry.encoding))) +
                                      ")"
                                : "")
              << '\n';
  std::cout << "metadata\n";
  for (const auto& [key, value] : metadata.entries())
    std::cout << "  " << key << " = " << escape_for_terminal(value) << '\n';
}

void print_json(const Inspection& inspection) {
  const auto& r = inspection.reader;
  const auto& metadata = r.metadata();
  JsonWriter json(std::cout);
  json.begin_object();
  json.key("file").value(r.display_name());
  json.key("format").value(version(r));
  json.key("digest").value(r.digest());
  json.key("vertices").value(r.vertex_count());
  json.key("arcs").value(r.arc_count());
  if (inspection.verified)
    json.key("verified").value(std::string(kVerifyLevelNames.name(*inspection.verified)));
  else
    json.key("verified").null();
  if (const auto multiplicity = loops_and_parallel_arcs(inspection)) {
    json.key("self_loops").value(multiplicity->self_loops);
    json.key("parallel_arcs").value(multiplicity->parallel_arcs);
  } else {
    json.key("self_loops").null();
    json.key("parallel_arcs").null();
  }
  json.key("objectives").begin_array();
  for (std::size_t i = 0; i < r.objective_count(); ++i) {
    const auto& s = r.objective(i);
    json.begin_object();
    json.key("name").value(s.name);
    json.key("type").value(format::to_string(s.type));
    json.key("unit").value(metadata.get("objective." + s.name + ".unit").value_or(""));
    json.end_object();
  }
  json.end_array();
  json.key("query_sets").begin_array();
  for (const auto* s : r.all(format::SectionKind::queries)) {
    json.begin_object();
    json.key("name").value(s->name);
    json.key("queries").value(s->entry.row_count);
    if (r.find(format::SectionKind::query_reference, s->name)) {  // only sets that carry one
      const std::string key = "queries." + s->name + ".reference.";
      json.key("reference").begin_object();
      json.key("objective").value(metadata.get(key + "objective").value_or(""));
      json.key("source").value(metadata.get(key + "source").value_or(""));
      json.end_object();
    }
    json.end_object();
  }
  json.end_array();
  json.key("sections").begin_array();
  for (const auto& s : r.sections()) {
    json.begin_object();
    json.key("kind").value(kind_name(s));
    json.key("name").value(s.name);
    json.key("type").value(format::to_string(s.type));
    json.key("width").value(std::uint64_t{s.entry.row_width});
    json.key("rows").value(s.entry.row_count);
    json.key("offset").value(s.entry.offset);
    json.key("bytes").value(s.entry.stored_length);
    json.key("checksum").value(hex64(s.entry.checksum));
    json.key("packed").value(s.is_packed());
    json.key("encoding").value(format::to_string(static_cast<format::Encoding>(s.entry.encoding)));
    json.end_object();
  }
  json.end_array();
  json.key("metadata").begin_object();
  for (const auto& [key, value] : metadata.entries()) json.key(key).value(value);
  json.end_object();
  json.end_object();
}

}  // namespace

Command add_inspect(CLI::App& app) {
  auto* sub = app.add_subcommand("inspect", "Show a file's version, digest, sections and metadata");
  auto file = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  auto level = std::make_shared<std::string>();
  sub->add_option("INSTANCE", *file, "a .mosb instance")->required();
  sub->add_option("--verify", *level,
                  "verify the file to LEVEL (" + kVerifyLevelNames.choices_text() +
                      ") before showing it; full also counts self-loops and "
                      "parallel arcs. Without it, nothing past the header, the section table and "
                      "the metadata is read")
      ->check(CLI::IsMember(kVerifyLevelNames.names()));
  add_json_flag(sub, *as_json);
  return {sub, [file, as_json, level] {
            Inspection inspection{GraphReader::open(*file), std::nullopt};
            if (!level->empty()) {
              inspection.verified = kVerifyLevelNames.parse(*level);
              inspection.reader = GraphReader::open(*file, *inspection.verified);
            }
            if (*as_json)
              print_json(inspection);
            else
              print_text(inspection);
            return 0;
          }};
}

}  // namespace mosb::cli
