#include "mosb/manifest.hpp"

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>
#include <type_traits>
#include <utility>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/metadata.hpp"
#include "mosb/sha256.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_summary.hpp"

namespace mosb {

namespace {

using Json = nlohmann::json;

bool is_lower_hex(std::string_view text, std::size_t digits) {
  return text.size() == digits && std::all_of(text.begin(), text.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

Json to_json(const ManifestEntry& e) {
  Json sources = Json::array();
  for (const auto& s : e.sources)
    sources.push_back(Json{{"name", s.name}, {"size", s.size}, {"xxh3", s.xxh3}});
  Json out{{"file", e.file},
           {"size", e.size},
           {"sha256", e.sha256},
           {"digest", e.digest},
           {"format_version", e.format_version},
           {"packed", e.packed},
           {"benchmark", e.benchmark},
           {"views", e.views},
           {"query_sets", e.query_sets},
           {"sources", sources}};
  if (const auto& s = e.solutions) {
    out["kind"] = "solutions";
    out["instance"] = s->instance;
    out["epsilon"] = s->epsilon;
    out["solver"] = s->solver;
    out["solvers"] = s->solvers;
    out["statuses"] = s->statuses;
    out["vectors"] = s->vectors;
    out["statistics"] = s->statistics;
  }
  return out;
}

struct LineError {
  std::string message;
};

template <class T>
T field(const Json& object, const char* key, bool required, T fallback = {}) {
  const auto it = object.find(key);
  if (it == object.end()) {
    if (required) throw LineError{std::string("missing key '") + key + "'"};
    return fallback;
  }
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    // nlohmann converts any number to T, a float out of T's range with undefined behaviour: take
    // only integers that T holds.
    if (it->is_number_unsigned()) {
      if (const auto v = it->get<std::uint64_t>(); std::in_range<T>(v)) return static_cast<T>(v);
    } else if (it->is_number_integer()) {
      if (const auto v = it->get<std::int64_t>(); std::in_range<T>(v)) return static_cast<T>(v);
    }
    throw LineError{std::string("key '") + key + "' is not an integer in range"};
  } else {
    try {
      return it->get<T>();
    } catch (const Json::exception&) {
      throw LineError{std::string("key '") + key + "' has the wrong type"};
    }
  }
}

// The keys of a solution file's entry (`kind` "solutions").
SolutionsEntry solutions_from_json(const Json& object) {
  SolutionsEntry s;
  s.instance = field<std::string>(object, "instance", true);
  if (!is_lower_hex(s.instance, 32)) throw LineError{"instance is not 32 lowercase hex digits"};
  s.epsilon = field<std::string>(object, "epsilon", true);
  if (s.epsilon.empty() || s.epsilon.find_first_not_of("0123456789.eE+-") != std::string::npos)
    throw LineError{"epsilon '" + s.epsilon + "' is not a decimal number"};
  s.solver = field<std::string>(object, "solver", false);
  s.solvers = field<std::vector<std::string>>(object, "solvers", false);
  const auto statuses = object.find("statuses");
  if (statuses != object.end()) {
    if (!statuses->is_object()) throw LineError{"key 'statuses' has the wrong type"};
    for (const auto& [name, count] : statuses->items()) {
      if (!parse_query_status(name)) throw LineError{"statuses: '" + name + "' is no status"};
      s.statuses[name] = field<std::uint64_t>(*statuses, name.c_str(), true);
    }
  }
  s.vectors = field<std::uint64_t>(object, "vectors", false);
  s.statistics = field<std::vector<std::string>>(object, "statistics", false);
  return s;
}

ManifestEntry entry_from_json(const Json& object) {
  if (!object.is_object()) throw LineError{"not a JSON object"};
  ManifestEntry e;
  e.file = field<std::string>(object, "file", true);
  if (!is_valid_manifest_file_name(e.file))
    throw LineError{"invalid file name '" + e.file + "' (" + std::string(kManifestFileNameRule) +
                    ")"};
  e.size = field<std::uint64_t>(object, "size", true);
  e.sha256 = field<std::string>(object, "sha256", true);
  if (!is_lower_hex(e.sha256, 64)) throw LineError{"sha256 is not 64 lowercase hex digits"};
  e.digest = field<std::string>(object, "digest", true);
  if (!is_lower_hex(e.digest, 32)) throw LineError{"digest is not 32 lowercase hex digits"};
  e.format_version = field<std::string>(object, "format_version", false);
  e.packed = field<bool>(object, "packed", false);
  e.benchmark = field<std::string>(object, "benchmark", false);
  e.views = field<std::vector<std::string>>(object, "views", false);
  e.query_sets = field<std::vector<std::string>>(object, "query_sets", false);
  const auto sources = object.find("sources");
  if (sources != object.end()) {
    if (!sources->is_array()) throw LineError{"key 'sources' has the wrong type"};
    for (const auto& s : *sources) {
      if (!s.is_object()) throw LineError{"a 'sources' element is not an object"};
      e.sources.push_back({field<std::string>(s, "name", true),
                           field<std::uint64_t>(s, "size", true),
                           field<std::string>(s, "xxh3", true)});
    }
  }
  // An unknown kind is a later version's file, never an instance.
  const auto kind = field<std::string>(object, "kind", false, "instance");
  if (kind == "solutions")
    e.solutions = solutions_from_json(object);
  else if (kind != "instance")
    throw LineError{"kind '" + kind + R"(' is neither "instance" nor "solutions")"};
  return e;
}

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const auto end = text.find('\n');
    lines.push_back(text.substr(0, end));
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

// The older suite MANIFEST: `name<TAB>file<TAB>size<TAB>digest` per line (spec/GENERATORS.md).
Manifest parse_legacy(const std::vector<std::string_view>& lines, const std::string& name) {
  Manifest manifest;
  manifest.legacy = true;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto where = name + ":" + std::to_string(i + 1) + ": ";
    std::vector<std::string> fields;
    std::string_view rest = lines[i];
    for (;;) {
      const auto tab = rest.find('\t');
      fields.emplace_back(rest.substr(0, tab));
      if (tab == std::string_view::npos) break;
      rest.remove_prefix(tab + 1);
    }
    if (fields.size() != 4)
      throw Error(where + "neither a JSON Lines manifest nor a TSV MANIFEST line of 4 fields");
    ManifestEntry e;
    e.benchmark = fields[0];
    e.file = fields[1];
    if (!is_valid_manifest_file_name(e.file))
      throw Error(where + "invalid file name '" + e.file + "' (" +
                  std::string(kManifestFileNameRule) + ")");
    const auto& size = fields[2];
    if (size.empty() || size.size() > 19 ||
        !std::all_of(size.begin(), size.end(), [](char c) { return c >= '0' && c <= '9'; }))
      throw Error(where + "size '" + size + "' is not a number");
    e.size = std::stoull(size);
    e.digest = fields[3];
    if (!is_lower_hex(e.digest, 32)) throw Error(where + "digest is not 32 lowercase hex digits");
    manifest.entries.push_back(std::move(e));
  }
  return manifest;
}

void sort_and_check_unique(Manifest& manifest, const std::string& name) {
  std::sort(manifest.entries.begin(), manifest.entries.end(),
            [](const auto& a, const auto& b) { return a.file < b.file; });
  for (std::size_t i = 1; i < manifest.entries.size(); ++i)
    if (manifest.entries[i].file == manifest.entries[i - 1].file)
      throw Error(name + ": file '" + manifest.entries[i].file + "' listed twice");
}

}  // namespace

const ManifestEntry* Manifest::find(std::string_view file) const {
  const auto it =
      std::lower_bound(entries.begin(), entries.end(), file,
                       [](const ManifestEntry& e, std::string_view f) { return e.file < f; });
  return it != entries.end() && it->file == file ? &*it : nullptr;
}

bool is_valid_manifest_file_name(std::string_view name) {
  if (name.empty() || name == "." || name == ".." || name == kManifestName) return false;
  for (std::size_t i = 0; i < name.size();) {
    const auto c = static_cast<unsigned char>(name[i]);
    // Not UTF-8 (a lone byte 0x80-0x9F is itself a C1 control to an 8-bit terminal, and JSON
    // cannot hold it): refused too.
    const std::size_t length = utf8_sequence_length(name, i);
    if (length == 0 || c == '/' || c < 0x20 || c == 0x7F) return false;
    if (length > 1 && is_hidden_code_point(utf8_code_point(name, i, length))) return false;
    i += length;
  }
  return true;
}

Manifest parse_manifest(std::string_view text, const std::string& display_name) {
  auto lines = split_lines(text);
  if (lines.empty()) throw Error(display_name + ": empty manifest (no header record)");
  if (lines.front().empty() || lines.front().front() != '{') {
    auto manifest = parse_legacy(lines, display_name);
    sort_and_check_unique(manifest, display_name);
    return manifest;
  }
  Manifest manifest;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto where = display_name + ":" + std::to_string(i + 1) + ": ";
    Json record;
    try {
      record = Json::parse(lines[i]);
    } catch (const Json::parse_error& e) {
      throw Error(where + "not JSON (byte " + std::to_string(e.byte) + ")");
    } catch (const Json::exception& e) {
      // Valid syntax nlohmann cannot hold, e.g. a number beyond every JSON number type.
      std::string what = e.what();
      if (const auto tag = what.find("] "); tag != std::string::npos) what = what.substr(tag + 2);
      throw Error(where + "not JSON: " + what);
    }
    try {
      if (i == 0) {
        if (!record.is_object() || field<std::string>(record, "format", true) != kManifestFormat)
          throw LineError{"the header record does not name format \"mosb-manifest\""};
        const auto version = field<int>(record, "version", true);
        if (version < 1 || version > kManifestVersion)
          throw LineError{"manifest version " + std::to_string(version) +
                          ", this mosb reads 1 to " + std::to_string(kManifestVersion)};
        continue;
      }
      manifest.entries.push_back(entry_from_json(record));
    } catch (const LineError& e) {
      throw Error(where + e.message);
    }
  }
  sort_and_check_unique(manifest, display_name);
  return manifest;
}

Manifest read_manifest(const std::filesystem::path& path) {
  return parse_manifest(read_whole_file(path), path.string());
}

std::string serialize_manifest(const Manifest& manifest) {
  auto entries = manifest.entries;
  Manifest sorted{std::move(entries), false};
  sort_and_check_unique(sorted, std::string(kManifestName));
  const bool lists_solutions = std::any_of(sorted.entries.begin(), sorted.entries.end(),
                                           [](const ManifestEntry& e) { return e.solutions; });
  std::string text =
      Json{{"format", kManifestFormat}, {"version", lists_solutions ? kManifestVersion : 1}}
          .dump() +
      '\n';
  for (const auto& e : sorted.entries) {
    if (!is_valid_manifest_file_name(e.file))
      throw Error(std::string(kManifestName) + ": invalid file name '" + e.file + "' (" +
                  std::string(kManifestFileNameRule) + ")");
    // nlohmann::json keeps object keys in a std::map: sorted. Invalid UTF-8 is replaced, never
    // thrown on, so a manifest can always be written.
    text += to_json(e).dump(-1, ' ', false, Json::error_handler_t::replace) + '\n';
  }
  return text;
}

void write_manifest(const std::filesystem::path& path, const Manifest& manifest) {
  write_file_atomically(path, serialize_manifest(manifest));
}

std::vector<SourceInput> source_inputs(const Metadata& metadata, const std::string& display_name) {
  std::vector<SourceInput> inputs;
  for (std::size_t i = 0;; ++i) {
    const auto key = "source.input." + std::to_string(i);
    const auto name = metadata.get(key + ".name");
    if (!name) break;
    SourceInput input{*name, 0, metadata.get(key + ".xxh3").value_or("")};
    const auto size = metadata.get(key + ".size").value_or("");
    if (size.empty() || size.size() > 19 ||
        size.find_first_not_of("0123456789") != std::string::npos)
      throw Error(ErrorCode::damaged,
                  display_name + ": metadata " + key + ".size '" + size + "' is not a number");
    input.size = std::stoull(size);
    inputs.push_back(std::move(input));
  }
  return inputs;
}

namespace {

// What every file kind's entry says of its container: name, size, SHA-256, digest, version.
ManifestEntry container_entry(const ContainerReader& reader, const std::filesystem::path& path,
                              std::optional<std::string> sha256) {
  ManifestEntry e;
  e.file = path.filename().string();
  e.size = reader.bytes().size();
  e.sha256 = sha256 ? std::move(*sha256) : sha256_file(path);
  e.digest = reader.digest();
  e.format_version = std::to_string(reader.header().version_major) + "." +
                     std::to_string(reader.header().version_minor);
  return e;
}

}  // namespace

ManifestEntry describe_solutions(const SolutionReader& reader, const std::filesystem::path& path,
                                 std::optional<std::string> sha256) {
  auto e = container_entry(reader, path, std::move(sha256));
  // The reader holds a packed file decoded: size, version and form are the stored file's.
  const auto file = map_file(path);
  const auto stored = stated_header(file.bytes);
  if (!stored) throw Error(ErrorCode::io, path.string() + ": changed while it was read");
  e.size = file.bytes.size();
  e.format_version =
      std::to_string(stored->version_major) + "." + std::to_string(stored->version_minor);
  e.packed = is_packed(*stored);
  if (!reader.view_name().empty()) e.views.push_back(reader.view_name());
  e.query_sets.push_back(reader.query_set());
  SolutionsEntry s;
  s.instance = reader.instance_digest();
  const auto solver = reader.solver();
  s.epsilon = solver.epsilon;
  s.solver = solver.name;
  s.solvers = front_solvers(reader);
  for (std::uint64_t q = 0; q < reader.query_count(); ++q)
    ++s.statuses[std::string(to_string(reader.status(q)))];
  s.vectors = reader.vector_count();
  for (const auto statistic : kStatistics)
    if (reader.has_statistic(statistic)) s.statistics.emplace_back(to_string(statistic));
  std::sort(s.statistics.begin(), s.statistics.end());
  e.solutions = std::move(s);
  return e;
}

ManifestEntry describe_file(const std::filesystem::path& path, std::optional<std::string> sha256) {
  if (stated_file_kind(map_file(path).bytes) == format::FileKind::solutions)
    return describe_solutions(SolutionReader::open(path), path, std::move(sha256));
  const auto reader = GraphReader::open(path);
  auto e = container_entry(reader, path, std::move(sha256));
  e.packed = reader.header().required_features != 0;
  for (const auto* s : reader.all(format::SectionKind::queries)) e.query_sets.push_back(s->name);
  std::sort(e.query_sets.begin(), e.query_sets.end());
  try {
    const auto& metadata = reader.metadata();
    e.benchmark = metadata.get("benchmark").value_or("");
    for (const auto& view : view_keys(metadata)) e.views.push_back(view.name);
    e.sources = source_inputs(metadata, path.string());
  } catch (const Error& error) {
    if (error.code() != ErrorCode::packed) throw;
  }
  return e;
}

}  // namespace mosb
