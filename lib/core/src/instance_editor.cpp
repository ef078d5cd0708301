#include "mosb/instance_editor.hpp"

#include <string>

#include "mosb/error.hpp"
#include "mosb/file_writer.hpp"
#include "mosb/internal/xxh3.hpp"

namespace mosb {

using format::SectionKind;

namespace {

void check_query_sets(const GraphReader& source, const std::vector<QuerySet>& query_sets) {
  const std::uint64_t n = source.vertex_count();
  for (std::size_t i = 0; i < query_sets.size(); ++i) {
    const auto& set = query_sets[i];
    if (!format::is_valid_section_name(set.name))
      throw Error(source.display_name() + ": query set name '" + set.name + "' must be " +
                  std::string(format::kSectionNameRule));
    for (std::size_t j = 0; j < i; ++j)
      if (query_sets[j].name == set.name)
        throw Error(source.display_name() + ": query set '" + set.name + "' given twice");
    for (std::size_t q = 0; q < set.pairs.size(); ++q)
      if (set.pairs[q].start >= n || set.pairs[q].goal >= n)
        throw Error(source.display_name() + ": query set '" + set.name + "', query " +
                    std::to_string(q) + ": an endpoint is not below the vertex count " +
                    std::to_string(n));
  }
}

// A `queries` section replaced by a new set, or the `query_reference` section of such a set (the
// new set writes its own reference, or none, right after its pairs).
const QuerySet* replacement_for(const Section& s, const std::vector<QuerySet>& query_sets) {
  if (s.kind != SectionKind::queries && s.kind != SectionKind::query_reference) return nullptr;
  for (const auto& set : query_sets)
    if (set.name == s.name) return &set;
  return nullptr;
}

}  // namespace

void rewrite_instance(const GraphReader& source, const Metadata& metadata_in,
                      const std::vector<QuerySet>& query_sets,
                      const std::filesystem::path& output) {
  const std::string& file = source.display_name();
  for (const auto& s : source.sections())
    if (s.is_packed())
      throw Error(file + ": section '" + s.name +
                  "' is packed (zstd); unpack the file before editing its query sets");
  check_query_sets(source, query_sets);

  std::vector<std::string> objective_names, query_names;
  for (const auto* s : source.all(SectionKind::cost)) objective_names.push_back(s->name);
  for (const auto* s : source.all(SectionKind::queries)) query_names.push_back(s->name);
  for (const auto& set : query_sets)
    if (!source.find(SectionKind::queries, set.name)) query_names.push_back(set.name);
  if (auto problem = find_view_problem(metadata_in, objective_names, query_names))
    throw Error(file + ": " + *problem);
  Metadata metadata = metadata_in;
  for (const auto& set : query_sets)
    add_reference_metadata(metadata, set, objective_names, file + ": ");

  // Copying re-hashes the bytes: a section damaged on disk would come out with a fresh, matching
  // checksum and the damage would be laundered, so each copied section is checked first.
  for (const auto& s : source.sections()) {
    if (s.kind == SectionKind::metadata || replacement_for(s, query_sets)) continue;
    if (XXH3_64bits(s.stored.data(), s.stored.size()) != s.entry.checksum)
      throw Error(file + ": section '" + s.name +
                  "': checksum mismatch, the file is damaged (see mosb verify); not rewritten");
  }

  // Rewriting the source itself is an edit in place (keep mode, symlink and hard links, refuse a
  // read-only file); any other output is a new file.
  std::error_code ec;
  const bool in_place = std::filesystem::equivalent(output, source.display_name(), ec) && !ec;
  FileWriter writer(
      output, in_place ? AtomicFile::Existing::rewrite_in_place : AtomicFile::Existing::replace);
  for (const auto& s : source.sections()) {
    if (s.kind == SectionKind::metadata) {
      const std::string text = metadata.serialize();
      writer.add_section(
          SectionKind::metadata, s.name, 1,
          std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    } else if (const auto* set = replacement_for(s, query_sets)) {
      if (s.kind == SectionKind::queries) write_query_set(writer, *set);
    } else {
      writer.begin_section(static_cast<SectionKind>(s.entry.kind), s.name, s.type,
                           s.entry.row_width);
      writer.append(s.stored);
      writer.end_section();
    }
  }
  for (const auto& set : query_sets)
    if (!source.find(SectionKind::queries, set.name)) write_query_set(writer, set);
  writer.commit(source.vertex_count(), source.arc_count());
}

}  // namespace mosb
