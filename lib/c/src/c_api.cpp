// The C ABI of mosb.h over GraphReader: every entry point catches, records the message per thread
// and returns a status; outputs are written only on success.
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "mosb.h"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pack.hpp"
#include "mosb/store.hpp"
#include "mosb/verify.hpp"
#include "mosb/version.hpp"

struct mosb_graph {
  explicit mosb_graph(mosb::GraphReader r) : reader(std::move(r)), digest(reader.digest()) {
    for (const auto* s : reader.all(mosb::format::SectionKind::queries)) query_sets.push_back(s);
  }
  mosb::GraphReader reader;
  std::string digest;
  std::vector<const mosb::Section*> query_sets;
  // Parsed from the metadata on first use, so that malformed metadata fails those calls only.
  std::once_flag described;
  std::vector<std::string> units;
  std::vector<mosb::View> views;
  std::string store_view;  // mosb_store_instance's resolved view
};

namespace {

thread_local std::string last_error;

mosb_status status_of(mosb::ErrorCode code) {
  switch (code) {
    case mosb::ErrorCode::other:
      return MOSB_ERROR_OTHER;
    case mosb::ErrorCode::io:
      return MOSB_ERROR_IO;
    case mosb::ErrorCode::not_mosb:
      return MOSB_ERROR_NOT_MOSB;
    case mosb::ErrorCode::version:
      return MOSB_ERROR_VERSION;
    case mosb::ErrorCode::damaged:
      return MOSB_ERROR_DAMAGED;
    case mosb::ErrorCode::not_found:
      return MOSB_ERROR_NOT_FOUND;
    case mosb::ErrorCode::invalid_argument:
      return MOSB_ERROR_INVALID_ARGUMENT;
    case mosb::ErrorCode::packed:
      return MOSB_ERROR_PACKED;
    case mosb::ErrorCode::no_memory:
      return MOSB_ERROR_NO_MEMORY;
  }
  return MOSB_ERROR_OTHER;
}

// An error in how the library was called (a NULL pointer, an unknown enumerator): its message
// names the function, as there may be no file to name.
struct CallError : mosb::Error {
  explicit CallError(const std::string& what)
      : mosb::Error(mosb::ErrorCode::invalid_argument, what) {}
};

mosb_status failed(mosb_status status, std::string_view what) {
  try {
    // One line, whatever the message quotes from a file (metadata values, names).
    last_error = mosb::escape_for_terminal(what);
  } catch (...) {
    // Keep the previous message rather than throw out of a C function.
  }
  return status;
}

// Runs body, turning every exception into a status and a message; `function` is the entry point.
template <class Body>
mosb_status guarded(const char* function, Body&& body) noexcept {
  try {
    body();
    return MOSB_OK;
  } catch (const CallError& e) {
    try {
      return failed(MOSB_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + e.message());
    } catch (...) {
      return failed(MOSB_ERROR_INVALID_ARGUMENT, e.message());
    }
  } catch (const mosb::Error& e) {
    return failed(status_of(e.code()), e.message());
  } catch (const std::bad_alloc&) {
    // No file to name here: the function, as for a call error.
    try {
      return failed(MOSB_ERROR_NO_MEMORY, std::string(function) + ": out of memory");
    } catch (...) {
      return failed(MOSB_ERROR_NO_MEMORY, "out of memory");
    }
  } catch (const std::exception& e) {
    return failed(MOSB_ERROR_OTHER, e.what());
  } catch (...) {
    return failed(MOSB_ERROR_OTHER, "unknown internal error");
  }
}

void require(const void* pointer, const char* what) {
  if (!pointer) throw CallError(std::string(what) + " is NULL");
}

const mosb_graph& checked(const mosb_graph* graph) {
  require(graph, "the graph handle");
  return *graph;
}

mosb_graph& described(const mosb_graph* graph) {
  auto& g = const_cast<mosb_graph&>(checked(graph));
  std::call_once(g.described, [&g] {
    std::vector<std::string> units;
    for (std::size_t i = 0; i < g.reader.objective_count(); ++i)
      units.push_back(g.reader.metadata()
                          .get("objective." + g.reader.objective(i).name + ".unit")
                          .value_or(""));
    g.views = g.reader.views();  // sorted by name
    g.units = std::move(units);
  });
  return g;
}

// By reference, and read as its underlying integer: a C caller may pass any int, and loading an
// out-of-range value as the enum type is undefined behaviour in C++.
mosb::VerifyLevel level_of(const mosb_verify_level& level) {
  std::underlying_type_t<mosb_verify_level> raw{};
  std::memcpy(&raw, &level, sizeof raw);
  switch (raw) {
    case MOSB_VERIFY_HEADER:
      return mosb::VerifyLevel::header;
    case MOSB_VERIFY_CHECKSUMS:
      return mosb::VerifyLevel::checksums;
    case MOSB_VERIFY_STRUCTURE:
      return mosb::VerifyLevel::structure;
    case MOSB_VERIFY_FULL:
      return mosb::VerifyLevel::full;
  }
  throw CallError("unknown verify level " + std::to_string(raw));
}

void verify(const mosb_graph& g, const mosb_verify_level& level) {
  if (auto problem = mosb::verify(g.reader, level_of(level)))
    throw mosb::Error(mosb::ErrorCode::damaged, g.reader.display_name() + ": " + *problem);
}

const mosb::View& view_named(const mosb_graph& g, const char* name) {
  require(name, "the view name");
  const auto found =
      std::lower_bound(g.views.begin(), g.views.end(), std::string_view(name),
                       [](const mosb::View& v, std::string_view n) { return v.name < n; });
  if (found != g.views.end() && found->name == name) return *found;
  g.reader.view(name);  // throws not_found with the list of views
  throw mosb::Error(mosb::ErrorCode::not_found,
                    g.reader.display_name() + ": no view '" + name + "'");
}

}  // namespace

extern "C" {

const char* mosb_version(void) {
  return mosb::version();
}

const char* mosb_last_error(void) {
  return last_error.c_str();
}

mosb_status mosb_open(const char* path, mosb_graph** graph) {
  return guarded(__func__, [&] {
    require(path, "the path");
    require(graph, "the output handle");
    *graph = new mosb_graph(mosb::GraphReader::open_unpacked(path));
  });
}

mosb_status mosb_load(const char* path, mosb_graph** graph) {
  return guarded(__func__, [&] {
    require(path, "the path");
    require(graph, "the output handle");
    *graph = new mosb_graph(mosb::load(path));
  });
}

mosb_status mosb_load_within(const char* path, uint64_t max_memory, mosb_graph** graph) {
  return guarded(__func__, [&] {
    require(path, "the path");
    require(graph, "the output handle");
    *graph = new mosb_graph(mosb::load(path, max_memory));
  });
}

mosb_status mosb_store_instance(const char* directory, const char* name, mosb_graph** graph,
                                const char** view) {
  return guarded(__func__, [&] {
    require(directory, "the store directory");
    require(name, "the name");
    require(graph, "the output handle");
    auto resolved = mosb::Store::open(directory).instance(name);
    auto opened = std::make_unique<mosb_graph>(std::move(resolved.reader));
    if (resolved.view) opened->store_view = resolved.view->name;
    if (view) *view = opened->store_view.c_str();
    *graph = opened.release();
  });
}

mosb_status mosb_open_verified(const char* path, mosb_verify_level level, mosb_graph** graph) {
  return guarded(__func__, [&] {
    require(path, "the path");
    require(graph, "the output handle");
    level_of(level);
    std::unique_ptr<mosb_graph> opened(new mosb_graph(mosb::GraphReader::open_unpacked(path)));
    verify(*opened, level);
    *graph = opened.release();
  });
}

void mosb_close(mosb_graph* graph) {
  delete graph;
}

mosb_status mosb_verify(const mosb_graph* graph, mosb_verify_level level) {
  return guarded(__func__, [&] { verify(checked(graph), level); });
}

mosb_status mosb_vertex_count(const mosb_graph* graph, uint64_t* count) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(count, "the output count");
    *count = g.reader.vertex_count();
  });
}

mosb_status mosb_arc_count(const mosb_graph* graph, uint64_t* count) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(count, "the output count");
    *count = g.reader.arc_count();
  });
}

mosb_status mosb_forward_csr(const mosb_graph* graph, const uint64_t** offsets,
                             const uint32_t** targets) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(offsets, "the output offsets");
    require(targets, "the output targets");
    const auto o = g.reader.forward_offsets();
    const auto t = g.reader.forward_targets();
    *offsets = o.data();
    *targets = t.data();
  });
}

mosb_status mosb_reverse_csr(const mosb_graph* graph, const uint64_t** offsets,
                             const uint32_t** sources, const uint32_t** arcs) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(offsets, "the output offsets");
    require(sources, "the output sources");
    require(arcs, "the output arcs");
    const auto o = g.reader.reverse_offsets();
    const auto s = g.reader.reverse_sources();
    const auto a = g.reader.reverse_arcs();
    *offsets = o.data();
    *sources = s.data();
    *arcs = a.data();
  });
}

mosb_status mosb_objective_count(const mosb_graph* graph, size_t* count) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(count, "the output count");
    *count = g.reader.objective_count();
  });
}

mosb_status mosb_objective_name(const mosb_graph* graph, size_t objective, const char** name) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(name, "the output name");
    *name = g.reader.objective(objective).name.c_str();
  });
}

mosb_status mosb_objective_unit(const mosb_graph* graph, size_t objective, const char** unit) {
  return guarded(__func__, [&] {
    require(unit, "the output unit");  // before the metadata is parsed: a call error first
    const auto& g = described(graph);
    g.reader.objective(objective);  // range check with the reader's message
    *unit = g.units[objective].c_str();
  });
}

mosb_status mosb_objective_type(const mosb_graph* graph, size_t objective,
                                mosb_element_type* type) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(type, "the output type");
    *type = static_cast<mosb_element_type>(g.reader.objective(objective).type);
  });
}

mosb_status mosb_find_objective(const mosb_graph* graph, const char* name, size_t* objective) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(name, "the objective name");
    require(objective, "the output index");
    *objective = g.reader.objective_index(name);
  });
}

mosb_status mosb_cost(const mosb_graph* graph, size_t objective, mosb_element_type* type,
                      const void** values) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(type, "the output type");
    require(values, "the output values");
    const void* data =
        g.reader.visit_cost(objective, [](auto column) -> const void* { return column.data(); });
    *type = static_cast<mosb_element_type>(g.reader.objective(objective).type);
    *values = data;
  });
}

mosb_status mosb_cost_copy_u64(const mosb_graph* graph, size_t objective, uint64_t* out,
                               size_t count) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(out, "the output buffer");
    g.reader.read_cost_as(objective, std::span<std::uint64_t>(out, count));
  });
}

mosb_status mosb_cost_copy_f64(const mosb_graph* graph, size_t objective, double* out,
                               size_t count) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(out, "the output buffer");
    g.reader.read_cost_as(objective, std::span<double>(out, count));
  });
}

mosb_status mosb_view_count(const mosb_graph* graph, size_t* count) {
  return guarded(__func__, [&] {
    require(count, "the output count");  // before the metadata is parsed: a call error first
    const auto& g = described(graph);
    *count = g.views.size();
  });
}

mosb_status mosb_view_name(const mosb_graph* graph, size_t view, const char** name) {
  return guarded(__func__, [&] {
    require(name, "the output name");  // before the metadata is parsed: a call error first
    const auto& g = described(graph);
    if (view >= g.views.size())
      throw mosb::Error(mosb::ErrorCode::invalid_argument,
                        g.reader.display_name() + ": view index " + std::to_string(view) +
                            " out of range (the file has " + std::to_string(g.views.size()) +
                            " views)");
    *name = g.views[view].name.c_str();
  });
}

mosb_status mosb_view(const mosb_graph* graph, const char* name, const size_t** objectives,
                      size_t* count, const char** query_set) {
  return guarded(__func__, [&] {
    require(name, "the view name");
    const auto& v = view_named(described(graph), name);
    if (objectives) *objectives = v.objectives.data();
    if (count) *count = v.objectives.size();
    if (query_set) *query_set = v.query_set.c_str();
  });
}

mosb_status mosb_query_set_count(const mosb_graph* graph, size_t* count) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(count, "the output count");
    *count = g.query_sets.size();
  });
}

mosb_status mosb_query_set_name(const mosb_graph* graph, size_t set, const char** name) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(name, "the output name");
    if (set >= g.query_sets.size())
      throw mosb::Error(mosb::ErrorCode::invalid_argument,
                        g.reader.display_name() + ": query set index " + std::to_string(set) +
                            " out of range (the file has " + std::to_string(g.query_sets.size()) +
                            " query sets)");
    *name = g.query_sets[set]->name.c_str();
  });
}

mosb_status mosb_queries(const mosb_graph* graph, const char* name, const uint32_t** pairs,
                         size_t* count) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(name, "the query set name");
    require(pairs, "the output pairs");
    require(count, "the output count");
    const auto queries = g.reader.queries(name);
    static_assert(sizeof(mosb::Query) == 2 * sizeof(std::uint32_t));
    *pairs = reinterpret_cast<const std::uint32_t*>(queries.data());
    *count = queries.size();
  });
}

mosb_status mosb_metadata(const mosb_graph* graph, const char* key, const char** value,
                          size_t* length) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(key, "the key");
    require(value, "the output value");
    const auto& entries = g.reader.metadata().entries();
    const auto it = entries.find(std::string_view(key));
    if (it == entries.end())
      throw mosb::Error(mosb::ErrorCode::not_found,
                        g.reader.display_name() + ": no metadata key '" + key + "'");
    *value = it->second.c_str();
    if (length) *length = it->second.size();
  });
}

mosb_status mosb_digest(const mosb_graph* graph, const char** digest) {
  return guarded(__func__, [&] {
    const auto& g = checked(graph);
    require(digest, "the output digest");
    *digest = g.digest.c_str();
  });
}

}  // extern "C"
