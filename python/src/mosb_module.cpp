// mosb._mosb: the Python binding of the C++ reader (lib/). Every array handed out is a read-only
// numpy view into the mapping whose base owns a reference to the reader, so an array outlives the
// Python object it came from and the mapping stays valid as long as any array does.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pack.hpp"
#include "mosb/runtime_figures.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_summary.hpp"
#include "mosb/store.hpp"
#include "mosb/verify.hpp"
#include "mosb/version.hpp"

namespace py = pybind11;

namespace {

using ReaderPtr = std::shared_ptr<mosb::GraphReader>;        // the holder type of Reader
using SolutionsPtr = std::shared_ptr<mosb::SolutionReader>;  // the holder type of SolutionsReader

// The base object of every array: a capsule holding one more owner of the reader.
template <class Reader>
py::capsule owner_of(const std::shared_ptr<Reader>& reader) {
  using Owner = std::shared_ptr<Reader>;
  return py::capsule(new Owner(reader), [](void* p) { delete static_cast<Owner*>(p); });
}

template <class T, class Reader>
py::array read_only_array(const std::shared_ptr<Reader>& reader, const T* data,
                          std::vector<py::ssize_t> shape) {
  py::array array(py::dtype::of<T>(), std::move(shape), data, owner_of(reader));
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

template <class T, class Reader>
py::array column(const std::shared_ptr<Reader>& reader, std::span<const T> values) {
  return read_only_array(reader, values.data(), {static_cast<py::ssize_t>(values.size())});
}

template <class T>
py::array section_array(const ReaderPtr& reader, const mosb::Section& s) {
  return column(reader, reader->values<T>(s));
}

// A cost column in its stored type (u8..u64, f32, f64; §5), without a copy.
py::array cost_column(const ReaderPtr& reader, std::size_t index) {
  using mosb::format::ElementType;
  const auto& s = reader->objective(index);
  switch (s.type) {
    case ElementType::u8:
      return section_array<std::uint8_t>(reader, s);
    case ElementType::u16:
      return section_array<std::uint16_t>(reader, s);
    case ElementType::u32:
      return section_array<std::uint32_t>(reader, s);
    case ElementType::u64:
      return section_array<std::uint64_t>(reader, s);
    case ElementType::i8:
      return section_array<std::int8_t>(reader, s);
    case ElementType::i16:
      return section_array<std::int16_t>(reader, s);
    case ElementType::i32:
      return section_array<std::int32_t>(reader, s);
    case ElementType::i64:
      return section_array<std::int64_t>(reader, s);
    case ElementType::f32:
      return section_array<float>(reader, s);
    case ElementType::f64:
      return section_array<double>(reader, s);
  }
  throw mosb::Error(reader->display_name() + ": section '" + s.name + "' has an unknown type");
}

// Text from the file (names, metadata) as str. The format requires UTF-8, but an unverified file
// may break that: such text is a mosb.Error ('damaged') naming the file, never UnicodeDecodeError.
py::str text_of(const mosb::ContainerReader& reader, std::string_view text) {
  PyObject* decoded =
      PyUnicode_DecodeUTF8(text.data(), static_cast<py::ssize_t>(text.size()), "strict");
  if (!decoded) {
    PyErr_Clear();
    throw mosb::Error(mosb::ErrorCode::damaged,
                      reader.display_name() + ": text in the file is not valid UTF-8");
  }
  return py::reinterpret_steal<py::str>(decoded);
}

py::list texts_of(const mosb::GraphReader& reader, const std::vector<std::string>& texts) {
  py::list out;
  for (const auto& text : texts) out.append(text_of(reader, text));
  return out;
}

// A file's metadata as a dict of str; text that is not UTF-8 is a mosb.Error (text_of).
template <class Reader>
py::dict metadata_of(const Reader& r) {
  py::dict entries;
  for (const auto& [key, value] : r.metadata().entries())
    entries[text_of(r, key)] = text_of(r, value);
  return entries;
}

std::vector<std::string> names_of(const std::vector<const mosb::Section*>& sections) {
  std::vector<std::string> names;
  for (const auto* s : sections) names.push_back(s->name);
  return names;
}

// A path as the operating system has it (bytes; Python hands str paths over with
// os.fsencode) shown as os.fsdecode would: undecodable bytes as surrogate escapes.
py::str path_text(const std::string& path) {
  return py::reinterpret_steal<py::str>(
      PyUnicode_DecodeFSDefaultAndSize(path.data(), static_cast<py::ssize_t>(path.size())));
}

// mosb::Error as the Python exception mosb.Error.
void bind_error(py::module_& m) {
  // One message line (naming the file) as str(error), and the C++ ErrorCode as error.code.
  static py::exception<mosb::Error> error_type(m, "Error");
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const mosb::Error& e) {
      // One line, whatever the message quotes from a file (metadata values, names), as the C ABI
      // and the CLI print it; names and paths need not be UTF-8.
      const std::string what = mosb::escape_for_terminal(e.message());
      auto message = py::reinterpret_steal<py::str>(PyUnicode_DecodeUTF8(
          what.data(), static_cast<py::ssize_t>(what.size()), "backslashreplace"));
      py::object error = py::reinterpret_borrow<py::object>(error_type.ptr())(message);
      error.attr("code") = std::string(mosb::kErrorCodeNames.name(e.code()));
      PyErr_SetObject(error_type.ptr(), error.ptr());
    }
  });
}

// Opening, sizes, the arrays (zero-copy views that keep the mapping alive), names and views.
void bind_reader_data(py::class_<mosb::GraphReader, ReaderPtr>& reader) {
  reader
      .def_static(
          "open",
          [](const std::string& path) {
            return std::make_shared<mosb::GraphReader>(mosb::GraphReader::open_unpacked(path));
          },
          py::arg("path"), py::call_guard<py::gil_scoped_release>())
      .def_static(
          "load",
          [](const std::string& path, std::uint64_t max_memory) {
            return std::make_shared<mosb::GraphReader>(mosb::load(path, max_memory));
          },
          py::arg("path"), py::arg("max_memory") = 0, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("display_name",
                             [](const mosb::GraphReader& r) { return path_text(r.display_name()); })
      .def_property_readonly("vertex_count", &mosb::GraphReader::vertex_count)
      .def_property_readonly("arc_count", &mosb::GraphReader::arc_count)
      .def_property_readonly("format_version",
                             [](const mosb::GraphReader& r) {
                               return py::make_tuple(r.header().version_major,
                                                     r.header().version_minor);
                             })
      .def("digest", &mosb::GraphReader::digest)
      .def("forward_offsets", [](const ReaderPtr& r) { return column(r, r->forward_offsets()); })
      .def("forward_targets", [](const ReaderPtr& r) { return column(r, r->forward_targets()); })
      .def("reverse_offsets", [](const ReaderPtr& r) { return column(r, r->reverse_offsets()); })
      .def("reverse_sources", [](const ReaderPtr& r) { return column(r, r->reverse_sources()); })
      .def("reverse_arcs", [](const ReaderPtr& r) { return column(r, r->reverse_arcs()); })
      .def("objective_names",
           [](const mosb::GraphReader& r) {
             py::list names;
             for (std::size_t i = 0; i < r.objective_count(); ++i)
               names.append(text_of(r, r.objective(i).name));
             return names;
           })
      .def("objective_index", &mosb::GraphReader::objective_index, py::arg("name"))
      .def("objective_type",
           [](const mosb::GraphReader& r, std::size_t i) {
             return std::string(mosb::format::to_string(r.objective(i).type));
           })
      .def("cost", &cost_column, py::arg("index"))
      .def("query_set_names",
           [](const mosb::GraphReader& r) {
             return texts_of(r, names_of(r.all(mosb::format::SectionKind::queries)));
           })
      .def(
          "queries",
          [](const ReaderPtr& r, const std::string& name) {
            const auto queries = r->queries(name);
            static_assert(sizeof(mosb::Query) == 2 * sizeof(std::uint32_t));
            return read_only_array(r, reinterpret_cast<const std::uint32_t*>(queries.data()),
                                   {static_cast<py::ssize_t>(queries.size()), 2});
          },
          py::arg("name"))
      .def("view_names", [](const mosb::GraphReader& r) { return texts_of(r, r.view_names()); })
      // Every view resolved in one pass over the metadata (sorted by name): what a caller that
      // resolves many views keeps, as the C ABI does; fails as the first bad view does.
      .def("views",
           [](const mosb::GraphReader& r) {
             py::list out;
             for (const auto& view : r.views())
               out.append(py::make_tuple(text_of(r, view.name), view.objectives,
                                         text_of(r, view.query_set)));
             return out;
           })
      .def(
          "view",
          [](const mosb::GraphReader& r, const std::string& name) {
            auto view = r.view(name);
            return py::make_tuple(text_of(r, view.name), view.objectives,
                                  text_of(r, view.query_set));
          },
          py::arg("name"));
}

// Metadata, verification and the mapping's address range (for the tests of zero-copy views).
void bind_reader_checks(py::class_<mosb::GraphReader, ReaderPtr>& reader) {
  reader.def("metadata", &metadata_of<mosb::GraphReader>)
      .def(
          "verify",
          [](const mosb::GraphReader& r, const std::string& level) {
            const auto parsed = mosb::parse_verify_level(level);
            if (!parsed)
              throw py::value_error("verify level '" + level + "' is not one of " +
                                    mosb::kVerifyLevelNames.choices_text());
            std::optional<std::string> problem;
            {
              py::gil_scoped_release release;
              problem = mosb::verify(r, *parsed);
            }
            // The message the CLI's `mosb verify` prints after FAIL.
            if (problem)
              throw mosb::Error(mosb::ErrorCode::damaged, r.display_name() + ": " + *problem);
          },
          py::arg("level"))
      .def("mapping_range", [](const mosb::GraphReader& r) {
        return py::make_tuple(reinterpret_cast<std::uintptr_t>(r.bytes().data()), r.bytes().size());
      });
}

// A store's instances by name, and its listing.
void bind_store(py::module_& m) {
  // (reader, view name or "", query set or "", path mapped, manifest file name) of
  // mosb::Store::instance.
  m.def(
      "store_instance",
      [](const std::string& directory, const std::string& name) {
        auto found = [&] {
          py::gil_scoped_release release;
          return mosb::Store::open(directory).instance(name);
        }();
        return py::make_tuple(std::make_shared<mosb::GraphReader>(std::move(found.reader)),
                              found.view ? found.view->name : std::string(), found.query_set,
                              found.path.string(), found.entry.file);
      },
      py::arg("directory"), py::arg("name"));
  m.def(
      "store_files",
      [](const std::string& directory) {
        const auto store = mosb::Store::open(directory);
        std::vector<std::string> files;
        for (const auto& e : store.manifest().entries) files.push_back(e.file);
        return files;
      },
      py::arg("directory"));
}

// Solution files (spec/SOLUTIONS.md), opened with their payload verified: the fronts' columns
// zero-copy in their stored types (u64/f64 path sums; the arc types in files before 1.3).
void bind_solutions(py::module_& m) {
  py::class_<mosb::SolutionReader, SolutionsPtr>(m, "SolutionsReader")
      .def_static(
          "open",
          [](const std::string& path) {
            return std::make_shared<mosb::SolutionReader>(
                mosb::SolutionReader::open_verified(path));
          },
          py::arg("path"), py::call_guard<py::gil_scoped_release>())
      .def_property_readonly(
          "display_name", [](const mosb::SolutionReader& r) { return path_text(r.display_name()); })
      .def_property_readonly("instance_digest", &mosb::SolutionReader::instance_digest)
      .def_property_readonly(
          "solver_name",
          [](const mosb::SolutionReader& r) { return text_of(r, mosb::solver_name(r)); })
      .def_property_readonly(
          "view", [](const mosb::SolutionReader& r) { return text_of(r, r.view_name()); })
      .def_property_readonly(
          "query_set", [](const mosb::SolutionReader& r) { return text_of(r, r.query_set()); })
      .def_property_readonly("query_count", &mosb::SolutionReader::query_count)
      .def_property_readonly("vector_count", &mosb::SolutionReader::vector_count)
      .def("objective_names",
           [](const mosb::SolutionReader& r) {
             py::list names;
             for (std::size_t i = 0; i < r.objective_count(); ++i)
               names.append(text_of(r, r.objective_name(i)));
             return names;
           })
      .def("metadata", &metadata_of<mosb::SolutionReader>)
      .def("statuses",
           [](const mosb::SolutionReader& r) {
             py::array_t<std::uint8_t> codes(static_cast<py::ssize_t>(r.query_count()));
             auto out = codes.mutable_unchecked<1>();
             for (std::uint64_t q = 0; q < r.query_count(); ++q)
               out(static_cast<py::ssize_t>(q)) = static_cast<std::uint8_t>(r.status(q));
             return codes;
           })
      .def("front_offsets", [](const SolutionsPtr& r) { return column(r, r->front_offsets()); })
      .def(
          "column",
          [](const SolutionsPtr& r, std::size_t i) {
            return r->visit_column(i, [&](auto values) { return column(r, values); });
          },
          py::arg("index"))
      .def(
          "statistic",
          [](const mosb::SolutionReader& r, const std::string& name) -> py::object {
            const auto found = mosb::kStatisticNames.parse(name);
            if (!found)
              throw py::value_error("statistic '" + name + "' is not one of " +
                                    mosb::kStatisticNames.choices_text());
            if (!r.has_statistic(*found)) return py::none();
            // float64 with NaN for an absent value: what pandas and numpy expect of a column.
            py::array_t<double> values(static_cast<py::ssize_t>(r.query_count()));
            auto out = values.mutable_unchecked<1>();
            for (std::uint64_t q = 0; q < r.query_count(); ++q) {
              out(static_cast<py::ssize_t>(q)) =
                  r.statistic_as_double(*found, q).value_or(std::nan(""));
            }
            return values;
          },
          py::arg("name"));
  py::list statuses;
  for (const auto& name : mosb::kQueryStatusNames.names()) statuses.append(name);
  m.attr("STATUSES") = py::tuple(statuses);
}

// A solver's queries as the runtime figures read them: status codes (indexing STATUSES) and
// runtimes (NaN where absent), two arrays of one length.
std::vector<mosb::QueryRun> runs_of(const py::array_t<std::uint8_t>& statuses,
                                    const py::array_t<double>& runtimes) {
  if (statuses.ndim() != 1 || runtimes.ndim() != 1 || statuses.size() != runtimes.size())
    throw py::value_error("statuses and runtimes: two arrays of one length");
  const auto s = statuses.unchecked<1>();
  const auto t = runtimes.unchecked<1>();
  std::vector<mosb::QueryRun> runs(static_cast<std::size_t>(statuses.size()));
  for (py::ssize_t q = 0; q < statuses.size(); ++q) {
    if (s(q) > mosb::kLastQueryStatus)
      throw py::value_error("status code " + std::to_string(s(q)) + " is not one of STATUSES");
    auto& run = runs[static_cast<std::size_t>(q)];
    run.status = static_cast<mosb::QueryStatus>(s(q));
    if (!std::isnan(t(q))) run.runtime = t(q);
  }
  return runs;
}

py::list points_of(const std::vector<mosb::FigurePoint>& points) {
  py::list out;
  for (const auto& p : points) out.append(py::make_tuple(p.x, p.y));
  return out;
}

// The runtime figures' data (mosb/runtime_figures.hpp), which mosb.plot draws: the report's own.
void bind_runtime_figures(py::module_& m) {
  m.def(
      "cactus_series",
      [](const py::array_t<std::uint8_t>& statuses, const py::array_t<double>& runtimes) {
        const auto data = mosb::cactus_series(runs_of(statuses, runtimes));
        py::dict out;
        out["points"] = points_of(data.points);
        out["solved"] = data.solved;
        out["zero"] = data.zero;
        return out;
      },
      py::arg("statuses"), py::arg("runtimes"));
  m.def(
      "performance_profile",
      [](const std::vector<py::array_t<std::uint8_t>>& statuses,
         const std::vector<py::array_t<double>>& runtimes) {
        if (statuses.size() != runtimes.size() || statuses.empty())
          throw py::value_error("statuses and runtimes: one array of each per solver");
        std::vector<std::vector<mosb::QueryRun>> by_solver;
        for (std::size_t k = 0; k < statuses.size(); ++k)
          by_solver.push_back(runs_of(statuses[k], runtimes[k]));
        std::vector<std::vector<mosb::QueryRun>> by_query(by_solver.front().size());
        for (const auto& runs : by_solver) {
          if (runs.size() != by_query.size())
            throw py::value_error("the solvers' arrays differ in length");
          for (std::size_t q = 0; q < runs.size(); ++q) by_query[q].push_back(runs[q]);
        }
        const auto data = mosb::performance_profile(by_query, by_solver.size());
        py::dict out;
        out["queries"] = data.queries;
        py::list series;
        for (const auto& points : data.series) series.append(points_of(points));
        out["series"] = series;
        return out;
      },
      py::arg("statuses"), py::arg("runtimes"));
  m.def(
      "runtime_scatter",
      [](const py::array_t<std::uint8_t>& statuses_a, const py::array_t<double>& runtimes_a,
         const py::array_t<std::uint8_t>& statuses_b, const py::array_t<double>& runtimes_b) {
        const auto a = runs_of(statuses_a, runtimes_a), b = runs_of(statuses_b, runtimes_b);
        if (a.size() != b.size()) throw py::value_error("the two solvers' arrays differ in length");
        const auto data = mosb::runtime_scatter(a, b);
        py::dict out;
        out["points"] = points_of(data.points);
        out["query"] = data.query;
        out["one_only"] = data.one_only;
        out["zero"] = data.zero;
        return out;
      },
      py::arg("statuses_a"), py::arg("runtimes_a"), py::arg("statuses_b"), py::arg("runtimes_b"));
}

}  // namespace

PYBIND11_MODULE(_mosb, m) {
  m.doc() = "Binding of the mosb C++ reader; use the `mosb` package, not this module.";
  m.attr("__version__") = mosb::kVersion;
  bind_error(m);
  py::list levels;
  for (const auto& name : mosb::kVerifyLevelNames.names()) levels.append(name);
  m.attr("VERIFY_LEVELS") = py::tuple(levels);
  py::class_<mosb::GraphReader, ReaderPtr> reader(m, "Reader");
  bind_reader_data(reader);
  bind_reader_checks(reader);
  bind_store(m);
  bind_solutions(m);
  bind_runtime_figures(m);
}
