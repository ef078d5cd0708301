"""The installed package, used as a solver author would (issue 9).

Installs the build under test into a temporary prefix, builds tests/install/consumer (the README's
C and C++ programs, extracted from README.md, and examples/dijkstra.c) out of tree once through
find_package and once through pkg-config, and runs them on a generated grid, checking their output
against values computed independently with the reference reader (spec/reference). A second,
library-only shared build shows the package needs neither CLI11, Boost nor doctest, and carries a
SONAME. A reader-only consumer (find_package COMPONENTS core, pkg-config mosb-core) links xxHash and
nothing else; one asking for COMPONENTS pull gets libcurl, which no other target names; ctypes loads libmosb.so, which exports the C ABI alone. Environment: MOSB_BUILD_DIR, MOSB_SOURCE_DIR, MOSB_VERSION, CMAKE.
"""
import ctypes
import heapq
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import mosbtest  # noqa: E402 (main: the suites' skip exit code)

BUILD = os.environ["MOSB_BUILD_DIR"]
SOURCE = os.environ["MOSB_SOURCE_DIR"]
VERSION = os.environ["MOSB_VERSION"]
CMAKE = os.environ.get("CMAKE", "cmake")
sys.path.insert(0, os.path.join(SOURCE, "spec", "reference"))
import mosb_reader  # noqa: E402


def run(*args, env=None, cwd=None):
    r = subprocess.run([str(a) for a in args], capture_output=True, text=True, env=env, cwd=cwd)
    if r.returncode != 0:
        raise AssertionError("%s failed (%d):\n%s\n%s" % (" ".join(map(str, args)), r.returncode,
                                                          r.stdout[-3000:], r.stderr[-3000:]))
    return r.stdout


def readme_programs(directory):
    """The ```c and ```cpp blocks of README.md's "Use mosb in your solver" section."""
    with open(os.path.join(SOURCE, "README.md")) as f:
        text = f.read()
    section = text.split("## Use mosb in your solver", 1)[1].split("\n## ", 1)[0]
    blocks = dict(re.findall(r"```(c|cpp)\n(.*?)```", section, re.S))
    for lang in ("c", "cpp"):
        with open(os.path.join(directory, "readme." + lang), "w") as f:
            f.write(blocks[lang])
    with open(os.path.join(SOURCE, "docs", "C_API.md")) as f:
        example = f.read().split("## A complete example", 1)[1]
    with open(os.path.join(directory, "c_api_doc.c"), "w") as f:
        f.write(re.search(r"```c\n(.*?)```", example, re.S).group(1))


def search_path_entries(path):
    """The directories of an ELF file's DT_RUNPATH and DT_RPATH entries, in order."""
    entries = []
    for paths in re.findall(r"Library (?:runpath|rpath): \[(.*)\]", run("readelf", "-d", path)):
        entries += paths.split(":")
    return entries


def libdir(prefix):
    for name in ("lib", "lib64"):
        if os.path.isdir(os.path.join(prefix, name, "pkgconfig")):
            return os.path.join(prefix, name)
    raise AssertionError("no lib/pkgconfig under " + prefix)


def expected_outputs(path):
    """What readme_c, readme_cpp and dijkstra must print, from the reference reader."""
    inst = mosb_reader.open_instance(path)
    costs = inst.costs()
    readme_c = ["%d vertices, %d arcs" % (inst.n, inst.m)]
    for name, column in costs:
        total = 0.0
        for x in column.tolist():  # one addition at a time, in arc order, as the C program does
            total += float(x)
        readme_c.append("%s total %.17g" % (name, total))
    md = inst.metadata
    views = sorted(k[5:-11] for k in md if k.startswith("view.") and k.endswith(".objectives"))
    readme_cpp = ["mosb %s: %d vertices, %d arcs" % (VERSION, inst.n, inst.m)]
    names = [name for name, _ in costs]
    for view in views:
        line = "view %s:" % view
        for name in md["view.%s.objectives" % view].split(","):
            line += " %s<=%g" % (name, max(costs[names.index(name)][1].tolist()))
        readme_cpp.append(line + " queries " + md.get("view.%s.queries" % view, "-"))
    offsets = inst.array("forward_offsets").tolist()
    targets = inst.array("forward_targets").tolist()
    first = md["view.%s.objectives" % views[0]].split(",")[0]
    cost = [float(x) for x in costs[names.index(first)][1].tolist()]
    dijkstra = []
    for start, goal in inst.queries()[md["view.%s.queries" % views[0]]].tolist():
        dist = {start: 0.0}
        heap, done = [(0.0, start)], set()
        while heap:
            d, v = heapq.heappop(heap)
            if v in done:
                continue
            done.add(v)
            for a in range(offsets[v], offsets[v + 1]):
                w = targets[a]
                if d + cost[a] < dist.get(w, float("inf")):
                    dist[w] = d + cost[a]
                    heapq.heappush(heap, (dist[w], w))
        d = dist.get(goal, float("inf"))
        dijkstra.append("%d %d %s" % (start, goal, "inf" if d == float("inf") else "%.17g" % d))
    # docs/C_API.md's example: the digest, one line per objective, the arcs out of the first start.
    start = inst.queries()[md["view.%s.queries" % views[0]]].tolist()[0][0]
    view_costs = [costs[names.index(n)][1].tolist() for n in md["view.%s.objectives" % views[0]].split(",")]
    doc = ["digest " + inst.content_digest()]
    for i, (name, column) in enumerate(costs):
        doc.append("objective %d: %s [%s] element type %d" % (
            i, name, md.get("objective.%s.unit" % name, ""),
            mosb_reader._type_code(inst.section(name, mosb_reader.COST).element_type)))
    doc.append("view %s, %d objectives, query set %s; arcs out of %d:" % (
        views[0], len(view_costs), md["view.%s.queries" % views[0]], start))
    for a in range(offsets[start], offsets[start + 1]):
        doc.append("  -> %d" % targets[a] + "".join(" %g" % c[a] for c in view_costs))
    return {"readme_c": readme_c, "readme_cpp": readme_cpp, "dijkstra": dijkstra, "c_api_doc": doc}


class InstalledPackage(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="mosb-install-")
        cls.prefix = os.path.join(cls.tmp, "prefix")
        run(CMAKE, "--install", BUILD, "--prefix", cls.prefix)
        cls.snippets = os.path.join(cls.tmp, "snippets")
        os.mkdir(cls.snippets)
        readme_programs(cls.snippets)
        mosb = os.path.join(cls.prefix, "bin", "mosb")
        cls.grid = os.path.join(cls.tmp, "grid.mosb")
        run(mosb, "generate", "grid", "--width", "30", "--height", "20", "--objectives", "3",
            "--seed", "11", "-o", cls.grid)
        run(mosb, "queries", "generate", cls.grid, "--in-place", "--set", "default", "--count", "25",
            "--seed", "5", "--replace")
        cls.expected = expected_outputs(cls.grid)
        # What the C programs must refuse: the file packed, and one target bit flipped with the
        # checksums untouched (the walk would index out of bounds).
        cls.packed = os.path.join(cls.tmp, "packed.mosb")
        run(mosb, "pack", cls.grid, "-o", cls.packed)
        cls.flipped = os.path.join(cls.tmp, "flipped.mosb")
        shutil.copy(cls.grid, cls.flipped)
        inst = mosb_reader.open_instance(cls.grid)
        with open(cls.flipped, "r+b") as f:
            f.seek(inst.of_kind(mosb_reader.FORWARD_TARGETS)[0].offset + 3)
            f.write(b"\x80")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def consumer(self, prefix, via, name, build=None, *extra):
        build = build or os.path.join(self.tmp, name)
        env = dict(os.environ)
        if prefix:
            env["PKG_CONFIG_PATH"] = os.path.join(libdir(prefix), "pkgconfig")
            extra += ("-DCMAKE_PREFIX_PATH=" + prefix,)
        run(CMAKE, "-S", os.path.join(SOURCE, "tests", "install", "consumer"), "-B", build,
            "-DMOSB_VIA=" + via, "-DSNIPPETS=" + self.snippets,
            "-DEXAMPLES=" + os.path.join(SOURCE, "examples"), *extra, env=env)
        run(CMAKE, "--build", build, "-j2", env=env)
        for program in ("readme_c", "readme_cpp", "dijkstra", "c_api_doc"):
            out = run(os.path.join(build, program), self.grid).splitlines()
            self.assertEqual(out, self.expected[program], program + " via " + via)
        for program in ("readme_c", "dijkstra", "c_api_doc"):
            for bad, why in ((self.packed, "packed"), (self.flipped, "damaged")):
                r = subprocess.run([os.path.join(build, program), bad], capture_output=True,
                                   text=True)
                self.assertEqual(r.returncode, 1, (program, why, r.stdout, r.stderr))
                self.assertIn(bad, r.stderr, program)
                self.assertEqual(len(r.stderr.splitlines()), 1, (program, r.stderr))
        return build

    def test_installs_library_headers_program_and_package_files(self):
        lib = libdir(self.prefix)
        for path in ("include/mosb.h", "include/mosb/graph_reader.hpp", "include/mosb/format.hpp",
                     "include/mosb/version.hpp", "include/mosb/pack.hpp", "include/mosb/store.hpp",
                     "include/mosb/solution_file.hpp", "bin/mosb"):
            self.assertTrue(os.path.isfile(os.path.join(self.prefix, path)), path)
        # Internal headers stay in the source tree.
        self.assertFalse(os.path.exists(os.path.join(self.prefix, "include", "mosb", "internal")))
        for path in ("cmake/mosb/mosbConfig.cmake", "cmake/mosb/mosbConfigVersion.cmake",
                     "pkgconfig/mosb.pc", "pkgconfig/mosb-core.pc", "pkgconfig/mosb_c.pc"):
            self.assertTrue(os.path.isfile(os.path.join(lib, path)), path)
        self.assertEqual(run(os.path.join(self.prefix, "bin", "mosb"), "--version").strip(),
                         "mosb " + VERSION)
        env = dict(os.environ, PKG_CONFIG_PATH=os.path.join(lib, "pkgconfig"))
        self.assertEqual(run("pkg-config", "--modversion", "mosb", env=env).strip(), VERSION)
        self.assertEqual(run("pkg-config", "--modversion", "mosb_c", env=env).strip(), VERSION)
        with open(os.path.join(self.prefix, "include", "mosb", "version.hpp")) as f:
            self.assertIn('#define MOSB_VERSION_STRING "%s"' % VERSION, f.read())

    def test_version_file_accepts_same_minor_only(self):
        major, minor, _ = VERSION.split(".")
        script = os.path.join(self.tmp, "version_check.cmake")
        config = os.path.join(libdir(self.prefix), "cmake", "mosb", "mosbConfigVersion.cmake")
        for wanted, compatible in (("%s.%s" % (major, minor), True),
                                   ("%s.%d" % (major, int(minor) + 1), False),
                                   ("%d.0" % (int(major) + 1), False)):
            with open(script, "w") as f:
                wanted_major, wanted_minor = wanted.split(".")
                f.write('set(PACKAGE_FIND_VERSION "%s")\nset(PACKAGE_FIND_VERSION_MAJOR %s)\n'
                        'set(PACKAGE_FIND_VERSION_MINOR %s)\nset(PACKAGE_FIND_VERSION_PATCH 0)\n'
                        'set(PACKAGE_FIND_VERSION_COUNT 2)\ninclude("%s")\n'
                        'message("${PACKAGE_VERSION_COMPATIBLE}")\n'
                        % (wanted, wanted_major, wanted_minor, config))
            r = subprocess.run([CMAKE, "-P", script], capture_output=True, text=True)
            self.assertEqual(r.stderr.strip() in ("TRUE", "1"), compatible, (wanted, r.stderr))

    def test_consumer_through_find_package(self):
        self.consumer(self.prefix, "cmake", "consumer-cmake")

    def test_consumer_through_pkg_config(self):
        self.consumer(self.prefix, "pkg-config", "consumer-pkg-config")

    def test_installed_examples_build_and_run(self):
        # The example solvers' sources are installed (share/mosb/examples) and build against the
        # installed package alone.
        examples = os.path.join(self.prefix, "share", "mosb", "examples")
        self.assertTrue(os.path.isfile(os.path.join(examples, "CMakeLists.txt")), examples)
        build = os.path.join(self.tmp, "examples")
        run(CMAKE, "-S", examples, "-B", build, "-DCMAKE_PREFIX_PATH=" + self.prefix)
        run(CMAKE, "--build", build, "-j2")
        out = run(os.path.join(build, "dijkstra"), self.grid).splitlines()
        self.assertEqual(out, self.expected["dijkstra"])

    def test_add_subdirectory_builds_the_libraries_only(self):
        # As a subproject, mosb must not look for CLI11, Boost or doctest, nor build the program.
        build = os.path.join(BUILD, "install-test-subdirectory")
        self.consumer(None, "subdirectory", None, build, "-DMOSB_SOURCE=" + SOURCE, "-G", "Ninja",
                      "-DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON",
                      "-DCMAKE_DISABLE_FIND_PACKAGE_Boost=ON",
                      "-DCMAKE_DISABLE_FIND_PACKAGE_doctest=ON")
        self.assertFalse(os.path.exists(os.path.join(build, "mosb", "tools")))
        self.assertFalse(os.path.exists(os.path.join(build, "mosb", "tests")))

    def assert_no_search_in_the_current_directory(self, path):
        # The loader reads an empty or relative RUNPATH entry against the current directory: a
        # library planted where mosb is run would be loaded (CMake pads a build-tree RUNPATH with
        # empty entries to make room for a longer install RPATH).
        for entry in search_path_entries(path):
            self.assertTrue(entry.startswith("/") or entry.startswith("$ORIGIN"),
                            "%s: library search path entry %r" % (path, entry))

    def test_program_and_library_load_nothing_from_the_current_directory(self):
        for path in (os.path.join(BUILD, "tools", "mosb"),
                     os.path.join(BUILD, "lib", "c", "libmosb.so"),
                     os.path.join(self.prefix, "bin", "mosb"),
                     os.path.join(libdir(self.prefix), "libmosb.so")):
            self.assert_no_search_in_the_current_directory(path)

    def test_shared_library_only_build(self):
        # mosb as a library only: no CLI11, Boost or doctest may be looked up, and the shared
        # libraries carry a SONAME of major.minor.
        # Kept in the build tree between runs (incremental, and ccache-friendly under /work).
        build = os.path.join(BUILD, "install-test-shared")
        prefix = os.path.join(self.tmp, "shared-prefix")
        run(CMAKE, "-S", SOURCE, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
            "-DBUILD_SHARED_LIBS=ON", "-DMOSB_BUILD_TOOLS=OFF", "-DMOSB_BUILD_TESTS=OFF",
            "-DMOSB_BENCHMARKS=OFF", "-DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON",
            "-DCMAKE_DISABLE_FIND_PACKAGE_Boost=ON", "-DCMAKE_DISABLE_FIND_PACKAGE_doctest=ON")
        run(CMAKE, "--build", build, "-j2")
        run(CMAKE, "--install", build, "--prefix", prefix)
        self.assertFalse(os.path.exists(os.path.join(prefix, "bin", "mosb")))
        major, minor, _ = VERSION.split(".")
        for lib in ("libmosb", "libmosb_core", "libmosb_pack", "libmosb_store"):
            path = os.path.join(libdir(prefix), lib + ".so")
            self.assertTrue(os.path.islink(path), path)
            dynamic = run("readelf", "-d", path)
            self.assertIn("Library soname: [%s.so.%s.%s]" % (lib, major, minor), dynamic)
            self.assert_no_search_in_the_current_directory(path)
            # Each finds mosb's other libraries beside itself (RUNPATH $ORIGIN), from any directory.
            self.assertNotIn("not found", run("ldd", path, cwd=self.tmp))
        build_consumer = self.consumer(prefix, "pkg-config", "consumer-shared")
        self.assertIn("libmosb.so." + major, run("ldd", os.path.join(build_consumer, "readme_c")))

    def test_core_component_links_xxhash_alone(self):
        # A solver that only maps files: find_package(mosb COMPONENTS core) and mosb-core.pc give
        # the reader with libxxhash as its one dependency.
        project = os.path.join(self.tmp, "core-only")
        os.makedirs(project, exist_ok=True)
        with open(os.path.join(project, "CMakeLists.txt"), "w") as f:
            f.write("cmake_minimum_required(VERSION 3.16)\nproject(core_only CXX)\n"
                    "find_package(mosb 0.2 REQUIRED COMPONENTS core)\n"
                    "add_executable(count count.cpp)\n"
                    "target_link_libraries(count PRIVATE mosb::core)\n")
        with open(os.path.join(project, "count.cpp"), "w") as f:
            f.write('#include <iostream>\n#include <mosb/graph_reader.hpp>\n'
                    'int main(int, char** argv) {\n'
                    '  auto g = mosb::GraphReader::open(argv[1], mosb::VerifyLevel::full);\n'
                    '  std::cout << g.vertex_count() << " " << g.arc_count() << "\\n";\n}\n')
        build = os.path.join(self.tmp, "core-only-build")
        run(CMAKE, "-S", project, "-B", build, "-DCMAKE_PREFIX_PATH=" + self.prefix)
        run(CMAKE, "--build", build)
        with open(os.path.join(build, "CMakeFiles", "count.dir", "link.txt")) as f:
            libraries = sorted({os.path.basename(word) for word in f.read().split()
                                if re.search(r"\.(a|so)(\.[0-9.]+)?$", word) or
                                word.startswith("-l")})
        self.assertEqual(libraries, ["libmosb_core.a", "libxxhash.so"], libraries)
        inst = mosb_reader.open_instance(self.grid)
        self.assertEqual(run(os.path.join(build, "count"), self.grid).split(),
                         [str(inst.n), str(inst.m)])
        env = dict(os.environ, PKG_CONFIG_PATH=os.path.join(libdir(self.prefix), "pkgconfig"))
        flags = run("pkg-config", "--libs", "mosb-core", env=env).split()
        self.assertEqual([x for x in flags if x.startswith("-l")], ["-lmosb_core", "-lxxhash"])

    def test_pull_component_alone_brings_libcurl(self):
        # mosb::pull is the one component that links libcurl (find_package finds it for that
        # component); the umbrella mosb::mosb and the store do not name it. `run` is asked for
        # too: every installed component is one find_package knows.
        project = os.path.join(self.tmp, "pull-only")
        os.makedirs(project, exist_ok=True)
        with open(os.path.join(project, "CMakeLists.txt"), "w") as f:
            f.write("cmake_minimum_required(VERSION 3.16)\nproject(pull_only CXX)\n"
                    "find_package(mosb 0.2 REQUIRED COMPONENTS pull run)\n"
                    "add_executable(plan plan.cpp)\n"
                    "target_link_libraries(plan PRIVATE mosb::pull)\n")
        with open(os.path.join(project, "plan.cpp"), "w") as f:
            f.write('#include <iostream>\n#include <mosb/pull.hpp>\n'
                    'int main(int, char** argv) {\n'
                    '  mosb::PullOptions options;\n  options.dry_run = true;\n'
                    '  const auto result = mosb::pull(argv[1], argv[2], options);\n'
                    '  for (const auto& e : result.entries) std::cout << e.entry.file << "\\n";\n}\n')
        build = os.path.join(self.tmp, "pull-only-build")
        run(CMAKE, "-S", project, "-B", build, "-DCMAKE_PREFIX_PATH=" + self.prefix)
        run(CMAKE, "--build", build)
        with open(os.path.join(build, "CMakeFiles", "plan.dir", "link.txt")) as f:
            self.assertIn("libcurl", f.read())
        published = os.path.join(self.tmp, "published")
        mosb = os.path.join(self.prefix, "bin", "mosb")
        run(mosb, "store", "init", published)
        run(mosb, "store", "add", published, self.grid)
        self.assertEqual(run(os.path.join(build, "plan"), os.path.join(self.tmp, "pulled"),
                             published).split(), ["grid.mosb"])
        self.assertFalse(os.path.exists(os.path.join(self.tmp, "pulled")), "a dry run writes nothing")
        with open(os.path.join(libdir(self.prefix), "cmake", "mosb", "mosbTargets.cmake")) as f:
            targets = f.read()
        for target in ("mosb::store", "mosb::mosb", "mosb::core"):
            block = targets.split("set_target_properties(%s " % target, 1)[1].split(")\n", 1)[0]
            self.assertNotIn("CURL", block, target)
            self.assertNotIn("mosb::pull", block, target)

    def test_ctypes_reads_an_instance_through_libmosb_so(self):
        # The shared C ABI loads without a build, as Julia ccall or R .Call would load it, and
        # exports the mosb_* functions and nothing else.
        path = os.path.join(libdir(self.prefix), "libmosb.so")
        lib = ctypes.CDLL(path)
        lib.mosb_version.restype = ctypes.c_char_p
        self.assertEqual(lib.mosb_version().decode(), VERSION)
        graph = ctypes.c_void_p()
        self.assertEqual(lib.mosb_open(self.grid.encode(), ctypes.byref(graph)), 0)
        n, m = ctypes.c_uint64(), ctypes.c_uint64()
        self.assertEqual(lib.mosb_vertex_count(graph, ctypes.byref(n)), 0)
        self.assertEqual(lib.mosb_arc_count(graph, ctypes.byref(m)), 0)
        offsets, targets = ctypes.POINTER(ctypes.c_uint64)(), ctypes.POINTER(ctypes.c_uint32)()
        self.assertEqual(lib.mosb_forward_csr(graph, ctypes.byref(offsets), ctypes.byref(targets)), 0)
        inst = mosb_reader.open_instance(self.grid)
        self.assertEqual((n.value, m.value), (inst.n, inst.m))
        self.assertEqual(offsets[:n.value + 1], inst.array("forward_offsets").tolist())
        self.assertEqual(targets[:m.value], inst.array("forward_targets").tolist())
        self.assertEqual(lib.mosb_close(graph), 0)
        self.assertNotEqual(lib.mosb_open(b"/nonexistent.mosb", ctypes.byref(graph)), 0)
        lib.mosb_last_error.restype = ctypes.c_char_p
        self.assertIn("/nonexistent.mosb", lib.mosb_last_error().decode())
        symbols = run("nm", "-D", "--defined-only", path).split("\n")
        exported = sorted({line.split()[-1] for line in symbols if line.strip()})
        self.assertTrue(exported and all(name.startswith("mosb_") for name in exported), exported)


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
