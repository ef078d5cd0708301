#!/usr/bin/python3
"""The `mosb` Python package (python/), installed the way the README says: a venv with
--system-site-packages and `pip install --no-build-isolation --no-index ./python`.

Run under /usr/bin/python3 by ctest with MOSB (the program), MOSB_DUMP_JSON (the C++ dump tool),
MOSB_SOURCE_DIR and MOSB_PY_VENV (where to build the venv). The script installs the package into
that venv, then re-runs itself with the venv's interpreter, so every test imports the installed
package, not the source tree.
"""
import gc
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import mosbtest  # noqa: E402 (main: the suites' skip exit code)

import numpy as np

SOURCE = os.environ["MOSB_SOURCE_DIR"]
MOSB = os.environ["MOSB"]
DUMP_JSON = os.environ["MOSB_DUMP_JSON"]
VENV = os.environ["MOSB_PY_VENV"]
SHARED_DATA = os.path.join(SOURCE, "..", "shared", "data")
NETMAKER = os.path.join(SHARED_DATA, "netmaker",
                        "netMaker_3o_10000n_1amin_10amax_20i_1s_scorr_79134.gr")
DTYPES = {"u8": "uint8", "u16": "uint16", "u32": "uint32", "u64": "uint64", "f32": "float32",
          "f64": "float64"}
GOLDEN_SMALL = os.path.join(SOURCE, "spec", "golden", "1.0", "valid", "small.mosb")


def install_and_reexec():
    """The README's route, verbatim apart from the paths."""
    python = os.path.join(VENV, "bin", "python")
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", VENV], check=True)
    env = dict(os.environ)
    if shutil.which("ccache"):  # the extension compiles the library sources: cache them
        env.setdefault("CC", "ccache gcc")
        env.setdefault("CCACHE_BASEDIR", os.path.dirname(SOURCE))
    log = os.path.join(os.path.dirname(VENV), "pip-install.log")
    with open(log, "w") as out:
        done = subprocess.run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index",
                               os.path.join(SOURCE, "python")],
                              stdout=out, stderr=subprocess.STDOUT, env=env)
    if done.returncode != 0:
        with open(log) as f:
            sys.exit("pip install ./python failed:\n" + f.read()[-4000:])
    os.environ["MOSB_PY_INSTALLED"] = "1"
    os.execv(python, [python, os.path.abspath(__file__)] + sys.argv[1:])


if __name__ == "__main__" and not os.environ.get("MOSB_PY_INSTALLED"):
    install_and_reexec()

import mosb  # noqa: E402 (only importable once installed)


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


def cpp_dump(path):
    """Everything the C++ reader sees in the file (tests/support/dump_json.cpp)."""
    done = run(DUMP_JSON, path)
    if done.returncode != 0:
        raise AssertionError(done.stderr)
    return json.loads(done.stdout)


def patch(path, offset, data):
    with open(path, "r+b") as f:
        f.seek(offset)
        f.write(data)


class Temp(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="mosb-python-")
        self.addCleanup(shutil.rmtree, self.dir)

    def generate_grid(self, name="grid.mosb", *extra):
        out = os.path.join(self.dir, name)
        done = run(MOSB, "generate", "grid", "--width", 30, "--height", 20, "--objectives", 3,
                   "--seed", 4, *extra, "-o", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        return out

    def assert_same_as_cpp(self, path):
        """Every array, the metadata and the digest equal what the C++ reader reports."""
        g = mosb.open(path)
        dump = cpp_dump(path)
        self.assertEqual((g.vertex_count, g.arc_count), (dump["n"], dump["m"]))
        self.assertEqual(g.metadata, dump["metadata"])
        by_kind = {}
        for s in dump["sections"]:
            by_kind.setdefault(s["kind"], []).append(s)
        structural = {2: g.forward_offsets, 3: g.forward_targets, 4: g.reverse_offsets,
                      5: g.reverse_sources, 6: g.reverse_arcs}
        for kind, array in structural.items():
            (s,) = by_kind[kind]
            self.assertEqual(array.dtype.name, DTYPES[s["type"]])
            self.assertEqual(array.tolist(), s["values"], s["name"])
        costs = by_kind.get(7, [])
        self.assertEqual(g.objectives, tuple(s["name"] for s in costs))
        for i, s in enumerate(costs):
            for key in (i, s["name"]):
                column = g.cost(key)
                self.assertEqual(column.dtype.name, DTYPES[s["type"]])
                self.assertEqual(column.tolist(), s["values"], s["name"])
        queries = by_kind.get(10, [])
        self.assertEqual(g.query_sets, tuple(s["name"] for s in queries))
        for s in queries:
            rows = g.queries(s["name"])
            self.assertEqual(rows.shape, (s["rows"], 2))
            self.assertEqual(rows.reshape(-1).tolist(), s["values"])
        inspect = json.loads(run(MOSB, "inspect", "--json", path).stdout)
        self.assertEqual(g.digest, inspect["digest"])
        return g


class InstallTest(unittest.TestCase):
    def test_imported_from_the_venv_not_the_source_tree(self):
        package_dir = os.path.realpath(os.path.dirname(mosb.__file__))
        self.assertTrue(package_dir.startswith(os.path.realpath(VENV)), package_dir)
        self.assertIn("site-packages", package_dir)

    def test_version_is_the_projects(self):
        with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
            version = re.search(r"project\(\s*mosb\s+VERSION\s+([0-9.]+)", f.read()).group(1)
        self.assertEqual(mosb.__version__, version)
        self.assertIn(version, run(MOSB, "--version").stdout + run(MOSB, "--version").stderr)

    def test_suite_is_the_description_the_library_builds_from(self):
        with open(os.path.join(SOURCE, "spec", "suite.json"), encoding="utf-8") as f:
            expected = json.load(f)
        suite = mosb.suite()
        self.assertEqual(suite, expected)
        grid = [g for g in suite["generated"] if g["generator"] == "grid"][0]
        self.assertEqual(len(grid["sizes"]) ** 2, 49)
        suite["seed"] = 2  # a copy: the next call is unaffected
        self.assertEqual(mosb.suite()["seed"], 1)

    def test_import_loads_no_optional_library(self):
        done = run(sys.executable, "-c",
                   "import sys, mosb; print(sorted(m for m in ('scipy', 'pandas', 'networkx', "
                   "'igraph') if m in sys.modules))")
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(done.stdout.strip(), "[]")


def readme_python_blocks():
    """The ```sh and ```python blocks of the README's '## Python' section."""
    with open(os.path.join(SOURCE, "README.md"), encoding="utf-8") as f:
        text = f.read()
    section = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    return dict(re.findall(r"```(sh|python)\n(.*?)```", section, re.S))


class ReadmeTest(Temp):
    def test_install_commands_are_the_ones_this_test_ran(self):
        commands = readme_python_blocks()["sh"].splitlines()
        self.assertIn("/usr/bin/python3 -m venv --system-site-packages .venv", commands)
        self.assertIn(".venv/bin/pip install --no-build-isolation --no-index ./python", commands)

    def test_example_runs(self):
        example = readme_python_blocks()["python"]
        self.assertLessEqual(len(example.splitlines()), 12)
        self.generate_grid("grid.mosb")
        done = subprocess.run([sys.executable, "-c", example], cwd=self.dir, capture_output=True,
                              text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        last = done.stdout.splitlines()[-1]
        self.assertTrue(last.startswith("602 2340 ('c1', 'c2', 'c3') Grid-30x20 "), last)


class ValuesTest(Temp):
    def test_golden_small_equals_cpp(self):
        g = self.assert_same_as_cpp(GOLDEN_SMALL)
        # small.mosb holds u16, f32, f64, u32 and u64 cost columns.
        self.assertEqual({g.cost(o).dtype.name for o in g.objectives},
                         {"uint16", "float32", "float64", "uint32", "uint64"})

    def test_generated_grids_equal_cpp(self):
        self.assert_same_as_cpp(self.generate_grid())
        tiny = os.path.join(self.dir, "tiny.mosb")
        run(MOSB, "generate", "grid", "--width", 1, "--height", 1, "--objectives", 1, "--seed", 1,
            "-o", tiny)
        self.assert_same_as_cpp(tiny)

    def test_no_arcs(self):
        text = os.path.join(self.dir, "empty.gr")
        with open(text, "w") as f:
            f.write("p sp 3 0\n")
        path = os.path.join(self.dir, "empty.mosb")
        done = run(MOSB, "convert", "netmaker", text, "-o", path)
        self.assertEqual(done.returncode, 0, done.stderr)
        g = self.assert_same_as_cpp(path)
        self.assertEqual(g.arc_count, 0)
        for array in (g.forward_targets, g.reverse_arcs, g.cost(0)):
            self.assertEqual(array.shape, (0,))
            self.assertFalse(array.flags.writeable)
        self.assertEqual(g.forward_offsets.tolist(), [0, 0, 0, 0])
        self.assertEqual(g.to_scipy_csr(0).nnz, 0)

    def test_open_accepts_path_objects_and_verify(self):
        import pathlib
        g = mosb.open(pathlib.Path(GOLDEN_SMALL), verify="full")
        self.assertEqual(g.path, GOLDEN_SMALL)
        for level in mosb.VERIFY_LEVELS:
            g.verify(level)
        with self.assertRaisesRegex(ValueError, "header, checksums, structure, full"):
            g.verify("everything")

    def test_load_decodes_a_packed_file(self):
        plain = self.generate_grid()
        packed = os.path.join(self.dir, "packed.mosb")
        done = run(MOSB, "pack", plain, "-o", packed)
        self.assertEqual(done.returncode, 0, done.stderr)
        with self.assertRaises(mosb.Error) as caught:
            mosb.open(packed, verify="full")
        self.assertIn("zstd-packed", str(caught.exception))
        original, loaded = mosb.open(plain), mosb.load(packed, verify="full")
        self.assertEqual(loaded.digest, original.digest)
        self.assertTrue((loaded.forward_targets == original.forward_targets).all())
        for o in original.objectives:
            self.assertTrue((loaded.cost(o) == original.cost(o)).all())
        # A cap of the caller's: refused before anything is allocated, with its own code.
        with self.assertRaises(mosb.Error) as caught:
            mosb.load(packed, max_memory=1024)
        self.assertEqual(caught.exception.code, "no_memory")
        self.assertIn("cap of 1024 bytes", str(caught.exception))
        self.assertEqual(mosb.load(packed, max_memory=1 << 30).digest, original.digest)
        for bad in (0, -1, 2**64, 1.5, True, "1G"):
            with self.assertRaises(TypeError):
                mosb.load(packed, max_memory=bad)

    def test_store_resolves_a_packed_entry_through_its_cache(self):
        plain = self.generate_grid()
        store = os.path.join(self.dir, "store")
        for args in (("store", "init", store), ("store", "add", "--pack", store, plain)):
            done = run(MOSB, *args)
            self.assertEqual(done.returncode, 0, done.stderr)
        s = mosb.Store(store)
        self.assertEqual(s.files, (os.path.basename(plain),))
        found = s.instance("Grid_2")
        self.assertEqual(found.view.name, "Grid_2")
        self.assertEqual(len(found.view.objectives), 2)
        self.assertEqual(found.path, os.path.join(store, ".cache", os.path.basename(plain)))
        original = mosb.open(plain)
        self.assertEqual(found.instance.digest, original.digest)
        self.assertTrue((found.instance.forward_targets == original.forward_targets).all())
        with self.assertRaises(mosb.Error) as caught:
            s.instance("Grid_9")
        self.assertEqual(caught.exception.code, "not_found")
        with self.assertRaises(mosb.Error):
            mosb.Store(self.dir)  # no MANIFEST


class ZeroCopyTest(Temp):
    def test_two_accessors_share_the_mapping(self):
        g = mosb.open(self.generate_grid())
        start, size = g._reader.mapping_range()
        for name in ("forward_offsets", "forward_targets", "reverse_offsets", "reverse_sources",
                     "reverse_arcs"):
            first, second = getattr(g, name), getattr(g, name)
            self.assertTrue(np.shares_memory(first, second), name)
            self.assertTrue(start <= first.ctypes.data and
                            first.ctypes.data + first.nbytes <= start + size, name)
        for i, objective in enumerate(g.objectives):
            self.assertTrue(np.shares_memory(g.cost(i), g.cost(objective)))
            self.assertTrue(start <= g.cost(i).ctypes.data < start + size)
        rows = g.queries(g.query_sets[0])
        self.assertTrue(np.shares_memory(rows, g.queries(g.query_sets[0])))
        self.assertTrue(start <= rows.ctypes.data < start + size)

    def test_arrays_are_read_only(self):
        g = mosb.open(GOLDEN_SMALL)
        for array in (g.forward_offsets, g.forward_targets, g.reverse_arcs, g.cost("time"),
                      g.queries("default")):
            self.assertFalse(array.flags.writeable)
            self.assertFalse(array.flags.owndata)
            with self.assertRaises(ValueError):
                array[0] = 1
            with self.assertRaisesRegex(ValueError, "WRITEABLE"):
                array.setflags(write=True)

    def test_array_outlives_the_handle_and_the_file_name(self):
        path = self.generate_grid()
        expected = cpp_dump(path)
        g = mosb.open(path)
        targets, cost = g.forward_targets, g.cost(1)
        del g
        gc.collect()
        os.unlink(path)  # the mapping, not the name, holds the data
        gc.collect()
        self.assertEqual(targets.tolist(), next(s["values"] for s in expected["sections"]
                                                if s["kind"] == 3))
        self.assertEqual(cost.tolist(), [s for s in expected["sections"] if s["kind"] == 7][1]
                         ["values"])


class ErrorTest(Temp):
    def cli_verify_failure(self, path, level):
        done = run(MOSB, "verify", "--level", level, path)
        self.assertEqual(done.returncode, 1)
        self.assertTrue(done.stdout.startswith("FAIL "), done.stdout)
        return done.stdout[len("FAIL "):].rstrip("\n")

    def test_damaged_header_same_message_as_cli(self):
        path = self.generate_grid("damaged.mosb")
        patch(path, 64, b"\x07")  # vertex_count: the header checksum no longer matches
        with self.assertRaises(mosb.Error) as caught:
            mosb.open(path)
        message = str(caught.exception)
        self.assertIn(path, message)
        self.assertNotIn("\n", message)
        self.assertEqual(message, self.cli_verify_failure(path, "header"))
        done = run(MOSB, "inspect", path)
        self.assertEqual(done.stderr.strip(), "mosb: " + message)

    def test_damaged_section_same_message_as_cli(self):
        path = self.generate_grid("targets.mosb")
        g = mosb.open(path)
        offset = int(g.forward_targets.ctypes.data - g._reader.mapping_range()[0])
        del g
        patch(path, offset, (0xFFFFFFF0).to_bytes(4, "little"))
        g = mosb.open(path)  # open checks are O(1): the damage shows when verifying
        for level in ("checksums", "structure"):
            with self.assertRaises(mosb.Error) as caught:
                g.verify(level)
            self.assertIn(path, str(caught.exception))
            self.assertEqual(str(caught.exception), self.cli_verify_failure(path, level))
        with self.assertRaises(mosb.Error):
            mosb.open(path, verify="full")

    def test_golden_invalid_files_fail_where_expected(self):
        directory = os.path.join(SOURCE, "spec", "golden", "1.0", "invalid")
        with open(os.path.join(directory, "EXPECTED.tsv")) as f:
            rows = [line.rstrip("\n").split("\t") for line in f if not line.startswith("#")]
        for name, level, fragment in rows:
            path = os.path.join(directory, name)
            with self.assertRaises(mosb.Error, msg=name) as caught:
                mosb.open(path, verify="header" if level == "open" else level)
            self.assertIn(fragment, str(caught.exception))
            self.assertIn(path, str(caught.exception))

    def test_error_codes(self):
        """mosb.Error.code is the C++ ErrorCode's name, so callers need not match messages."""
        golden = os.path.join(SOURCE, "spec", "golden", "1.0")
        g = mosb.open(GOLDEN_SMALL)
        cases = (
            (lambda: g.cost("nope"), "not_found"), (lambda: g.view("nope"), "not_found"),
            (lambda: g.queries("nope"), "not_found"), (lambda: g.cost(9), "invalid_argument"),
            (lambda: mosb.open(os.path.join(self.dir, "missing.mosb")), "io"),
            (lambda: mosb.open(os.path.join(golden, "invalid", "bad-magic.mosb")), "not_mosb"),
            (lambda: mosb.open(os.path.join(golden, "invalid", "newer-major.mosb")), "version"),
            (lambda: mosb.open(os.path.join(golden, "invalid", "truncated.mosb")), "damaged"),
            (lambda: mosb.open(os.path.join(golden, "invalid", "target-range.mosb"),
                               verify="structure"), "damaged"))
        for call, code in cases:
            with self.assertRaises(mosb.Error) as caught:
                call()
            self.assertEqual(caught.exception.code, code, str(caught.exception))
            self.assertEqual(caught.exception.args, (str(caught.exception),))

    def test_lookup_errors(self):
        g = mosb.open(GOLDEN_SMALL)
        with self.assertRaisesRegex(mosb.Error, "no objective named 'nope'"):
            g.cost("nope")
        with self.assertRaisesRegex(mosb.Error, "objective index 9 out of range"):
            g.cost(9)
        with self.assertRaises(IndexError):
            g.cost(-1)
        with self.assertRaisesRegex(mosb.Error, "no query set named 'nope'"):
            g.queries("nope")
        with self.assertRaisesRegex(mosb.Error, "cannot open"):
            mosb.open(os.path.join(self.dir, "missing.mosb"))


class HardeningTest(Temp):
    """What a damaged file or a careless call must never do: crash, corrupt memory, or surface as
    a foreign exception (issue: the bindings keep the CLI's promise)."""

    def flip_target(self):
        path = self.generate_grid("flip.mosb")
        g = mosb.open(path)
        offset = int(g.forward_targets.ctypes.data - g._reader.mapping_range()[0])
        del g
        patch(path, offset + 3, b"\x80")  # target 0 becomes >= 2^31; checksums untouched
        return path

    def test_adapters_refuse_an_unchecked_walk(self):
        path = self.flip_target()
        g = mosb.open(path)
        adapters = [g.arc_sources, lambda: g.to_scipy_csr("c1"), g.to_networkx, g.to_igraph,
                    g.arcs_frame]
        for adapter in adapters:
            with self.assertRaises(mosb.Error) as caught:
                adapter()
            self.assertIn(path, str(caught.exception))
            self.assertEqual(caught.exception.code, "damaged")
        # A sound file is verified once, then walked.
        sound = mosb.open(self.generate_grid())
        self.assertEqual(sound.to_scipy_csr(0).nnz, sound.arc_count)
        self.assertTrue(sound._structure_checked)

    def test_zero_copy_open_refuses_a_packed_file_at_once(self):
        packed = os.path.join(self.dir, "packed.mosb")
        done = run(MOSB, "pack", self.generate_grid(), "-o", packed)
        self.assertEqual(done.returncode, 0, done.stderr)
        with self.assertRaises(mosb.Error) as caught:
            mosb.open(packed)
        self.assertEqual(caught.exception.code, "packed")
        self.assertIn("mosb.load", str(caught.exception))
        self.assertEqual(mosb.load(packed).vertex_count, 30 * 20 + 2)

    def test_paths_str_bytes_pathlike_and_nul(self):
        import pathlib
        odd = os.path.join(os.fsencode(self.dir), b"g\xff.mosb")  # not UTF-8
        shutil.copy(self.generate_grid(), odd)
        for path in (odd, os.fsdecode(odd), pathlib.Path(os.fsdecode(odd))):
            g = mosb.open(path)
            self.assertEqual(g.path, os.fsdecode(odd))
        with self.assertRaises(mosb.Error) as caught:
            mosb.open(GOLDEN_SMALL + "\0junk")
        self.assertEqual(caught.exception.code, "invalid_argument")
        with self.assertRaises(mosb.Error) as caught:
            mosb.open(os.path.join(os.fsencode(self.dir), b"missing\xff.mosb"))
        self.assertEqual(caught.exception.code, "io")
        self.assertIn("missing", str(caught.exception))

    def test_text_that_is_not_utf8_is_a_mosb_error(self):
        path = self.generate_grid("text.mosb")
        with open(path, "rb") as f:
            data = f.read()
        patch(path, data.index(b"view.Grid_2") + 9, b"\xff")  # a view name in the metadata
        g = mosb.open(path)
        for call in (lambda: g.metadata, lambda: g.views):
            with self.assertRaises(mosb.Error) as caught:
                call()
            self.assertEqual(caught.exception.code, "damaged")
            self.assertIn(path, str(caught.exception))

    def test_argument_checks_name_the_argument(self):
        g = mosb.open(GOLDEN_SMALL)
        with self.assertRaises(mosb.Error) as caught:
            g.objective_index(99)
        self.assertEqual(caught.exception.code, "invalid_argument")
        self.assertIn("objective index 99 out of range", str(caught.exception))
        with self.assertRaisesRegex(TypeError, "view must be a view name"):
            g._objective_list(5)


class AdapterTest(Temp):
    def test_scipy_csr_shares_every_cost_type(self):
        # small.mosb: u16, f32, f64, u32, u64; the grid: u8. Costs are never of another type.
        for path in (GOLDEN_SMALL, self.generate_grid()):
            self.check_scipy_csr(mosb.open(path))

    def check_scipy_csr(self, g):
        import scipy.sparse
        n = g.vertex_count
        sources = g.arc_sources()
        for objective in g.objectives:
            matrix = g.to_scipy_csr(objective)
            cost = g.cost(objective)
            self.assertIsInstance(matrix, scipy.sparse.csr_matrix)
            self.assertEqual(matrix.shape, (n, n))
            self.assertEqual(matrix.dtype, cost.dtype, objective)
            self.assertTrue(np.shares_memory(matrix.data, cost), objective)
            self.assertTrue(np.shares_memory(matrix.indices, g.forward_targets), objective)
            dense = np.zeros((n, n), dtype=np.float64)
            np.add.at(dense, (sources, g.forward_targets), cost.astype(np.float64))
            self.assertTrue(np.array_equal(matrix.toarray().astype(np.float64), dense), objective)

    def test_networkx_igraph_pandas(self):
        g = mosb.open(GOLDEN_SMALL)
        sources, targets = g.arc_sources().tolist(), g.forward_targets.tolist()
        nx_graph = g.to_networkx()
        self.assertEqual(nx_graph.number_of_nodes(), g.vertex_count)
        self.assertEqual(nx_graph.number_of_edges(), g.arc_count)
        for a in range(g.arc_count):
            attributes = nx_graph.edges[sources[a], targets[a], a]
            self.assertEqual(attributes, {o: g.cost(o)[a].item() for o in g.objectives})
        ig_graph = g.to_igraph()
        self.assertTrue(ig_graph.is_directed())
        self.assertEqual(ig_graph.vcount(), g.vertex_count)
        self.assertEqual([e.tuple for e in ig_graph.es], list(zip(sources, targets)))
        for o in g.objectives:
            self.assertEqual(ig_graph.es[o], g.cost(o).tolist())
        frame = g.arcs_frame()
        self.assertEqual(list(frame.columns), ["source", "target"] + list(g.objectives))
        self.assertEqual(frame["source"].tolist(), sources)
        self.assertEqual(frame["target"].tolist(), targets)
        for o in g.objectives:
            self.assertEqual(frame[o].tolist(), g.cost(o).tolist())
            self.assertEqual(frame[o].dtype, g.cost(o).dtype)

    def test_views(self):
        g = mosb.open(GOLDEN_SMALL)
        self.assertEqual(g.views, ("Small_2", "Small_5"))
        self.assertEqual(g.view("Small_2"), mosb.View("Small_2", (0, 1), "default"))
        self.assertEqual(g.view("Small_5"), mosb.View("Small_5", (0, 1, 2, 3, 4), "reverse"))
        with self.assertRaisesRegex(mosb.Error, "no view 'nope'"):
            g.view("nope")
        edge = next(iter(g.to_networkx("Small_2").edges(data=True)))[2]
        self.assertEqual(sorted(edge), ["distance", "time"])
        self.assertEqual(sorted(g.to_igraph(g.view("Small_2")).es.attributes()),
                         ["distance", "time"])
        self.assertEqual(list(g.arcs_frame("Small_2").columns),
                         ["source", "target", "distance", "time"])

    def test_missing_library_named(self):
        g = mosb.open(GOLDEN_SMALL)
        for method, module, package in (("to_scipy_csr", "scipy.sparse", "scipy"),
                                        ("to_networkx", "networkx", "networkx"),
                                        ("to_igraph", "igraph", "igraph"),
                                        ("arcs_frame", "pandas", "pandas")):
            saved = sys.modules.get(module)
            sys.modules[module] = None  # makes `import module` raise ImportError
            try:
                args = (0,) if method == "to_scipy_csr" else ()
                with self.assertRaisesRegex(ImportError, "%s needs the Python package '%s'"
                                            % (method, package)):
                    getattr(g, method)(*args)
            finally:
                if saved is None:
                    del sys.modules[module]
                else:
                    sys.modules[module] = saved


@unittest.skipUnless(os.path.isfile(NETMAKER),
                     mosbtest.MISSING + "real NetMaker fixture not found: ../shared/data is absent")
class RealNetMakerTest(Temp):
    def setUp(self):
        super().setUp()
        self.path = os.path.join(self.dir, "netmaker.mosb")
        done = run(MOSB, "convert", "netmaker", NETMAKER, "-o", self.path)
        self.assertEqual(done.returncode, 0, done.stderr)

    def test_values_equal_cpp(self):
        g = self.assert_same_as_cpp(self.path)
        self.assertEqual((g.vertex_count, g.arc_count), (10000, 59750))
        g.verify("full")

    def test_scipy_matrix_without_copying_costs(self):
        g = mosb.open(self.path)
        start, size = g._reader.mapping_range()
        with open(NETMAKER) as f:
            arcs = [line.split() for line in f if line.startswith("a ")]
        for i, objective in enumerate(g.objectives):
            matrix = g.to_scipy_csr(objective)
            self.assertTrue(np.shares_memory(matrix.data, g.cost(objective)))
            self.assertTrue(start <= matrix.data.ctypes.data < start + size)
            self.assertFalse(matrix.data.flags.writeable)
            # Every arc of the text file is an entry of the matrix (the sum over parallel arcs).
            expected = {}
            for a in arcs:
                key = (int(a[1]), int(a[2]))
                expected[key] = expected.get(key, 0) + int(a[3 + i])
            coo = matrix.tocoo()
            self.assertEqual(int(coo.sum()), sum(expected.values()))
            tail, head = arcs[123][1:3]
            self.assertEqual(matrix[int(tail), int(head)], expected[int(tail), int(head)])


class SolutionsTest(Temp):
    """mosb.open_solutions: a solution file's fronts, statuses and statistics, zero-copy columns
    and pandas frames, equal to what `mosb solutions export` writes."""

    def setUp(self):
        super().setUp()
        self.grid = os.path.join(self.dir, "g.mosb")
        done = run(MOSB, "generate", "grid", "--width", "6", "--height", "6", "--seed", "3",
                   "-o", self.grid)
        self.assertEqual(done.returncode, 0, done.stderr)
        done = run(MOSB, "queries", "generate", self.grid, "--set", "three", "--count", "3",
                   "--in-place")
        self.assertEqual(done.returncode, 0, done.stderr)
        # Query 0: two vectors, query 1: one; query 2 is not run.
        table = os.path.join(self.dir, "t.csv")
        with open(table, "w") as f:
            f.write("query,c1,c2\n0,1000,2\n0,3,900\n1,70000,5\n")
        self.sol = os.path.join(self.dir, "s.sol")
        done = run(MOSB, "solutions", "import", "--instance", self.grid, "--view", "Grid_2",
                   "--queries", "three", "--table", table, "--solver", "boa", "-o", self.sol)
        self.assertEqual(done.returncode, 0, done.stderr)

    def test_fronts_statuses_and_binding(self):
        s = mosb.open_solutions(self.sol)
        info = json.loads(run(MOSB, "solutions", "inspect", self.sol, "--json").stdout)
        self.assertEqual((s.view, s.objectives, s.vector_count), ("Grid_2", ("c1", "c2"), 3))
        self.assertEqual(s.instance_digest, mosb.open(self.grid).digest)
        self.assertEqual(s.query_count, info["queries"])
        self.assertEqual(s.solver["name"], "boa")
        self.assertEqual((s.status(0), s.status(1), s.status(2)), ("solved", "solved", "not-run"))
        c1, c2 = s.front(0)
        self.assertEqual(sorted(zip(c1.tolist(), c2.tolist())), [(3, 900), (1000, 2)])
        # Path sums beyond the grid's u8 arc type: the columns are u64.
        self.assertEqual(s.front(1)[0].tolist(), [70000])
        self.assertEqual(s.column("c1").dtype, np.uint64)
        self.assertFalse(s.column(0).flags.writeable)
        self.assertEqual(len(s.front(2)[0]), 0)
        self.assertIsNone(s.statistic("expanded"))
        with self.assertRaises(IndexError):
            s.front(s.query_count)
        with self.assertRaises(mosb.Error) as raised:
            s.column("c9")
        self.assertIn(self.sol, str(raised.exception))
        with self.assertRaises(ValueError):
            s.statistic("speed")

    def test_pandas_frames(self):
        s = mosb.open_solutions(self.sol)
        vectors = s.fronts_frame()
        self.assertEqual(list(vectors.columns), ["query", "status", "c1", "c2"])
        self.assertEqual(len(vectors), 3)
        self.assertEqual(set(vectors["status"]), {"solved"})
        self.assertEqual(sorted(vectors[vectors["query"] == 0]["c2"].tolist()), [2, 900])
        queries = s.queries_frame()
        self.assertEqual(len(queries), s.query_count)
        self.assertEqual(queries.loc[0, "front_size"], 2)
        self.assertEqual(queries.loc[2, "status"], "not-run")

    def test_a_packed_file_reads_as_its_unpacked_form(self):
        # spec/SOLUTIONS.md §1 (format 1.6): the golden packed file, decoded into owned memory.
        golden = os.path.join(SOURCE, "spec", "golden", "1.6", "solutions", "valid",
                              "fronts.packed.sol.mosb")
        packed = mosb.open_solutions(golden)
        unpacked = os.path.join(self.dir, "fronts.sol")
        done = run(MOSB, "unpack", golden, "-o", unpacked)
        self.assertEqual(done.returncode, 0, done.stderr)
        plain = mosb.open_solutions(unpacked)
        self.assertEqual((packed.vector_count, packed.objectives), (257, ("distance", "time")))
        for q in range(packed.query_count):
            self.assertEqual(packed.status(q), plain.status(q))
            for a, b in zip(packed.front(q), plain.front(q)):
                self.assertEqual(a.tolist(), b.tolist())
        self.assertFalse(packed.column(0).flags.writeable)

    def test_a_damaged_file_is_a_mosb_error_naming_it(self):
        with open(self.sol, "rb") as f:
            data = bytearray(f.read())
        data[-1] ^= 0xFF
        bad = os.path.join(self.dir, "bad.sol")
        with open(bad, "wb") as f:
            f.write(data)
        with self.assertRaises(mosb.Error) as raised:
            mosb.open_solutions(bad)
        self.assertIn(bad, str(raised.exception))


class PlotTest(Temp):
    """mosb.plot (issue 22 §3): matplotlib figures of a front and of two solvers' comparison, from
    solution files imported from JSON logs with runtimes (a 3-objective grid, three queries)."""

    def setUp(self):
        super().setUp()
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise mosbtest.missing("python3-matplotlib is not installed")
        import mosb.plot
        self.plot = mosb.plot
        self.grid = self.generate_grid("g.mosb")
        done = run(MOSB, "queries", "generate", self.grid, "--set", "three", "--count", "3",
                   "--in-place")
        self.assertEqual(done.returncode, 0, done.stderr)
        self.queries = mosb.open(self.grid).queries("three").tolist()
        # exact: every query, 2 s each; fast: queries 0 and 1 only, 1 s and 4 s.
        self.exact = self.solutions("exact", [[(10, 40, 5), (20, 20, 7)], [(30, 30, 30)],
                                              [(1, 2, 3)]], [2000, 2000, 2000])
        self.fast = self.solutions("fast", [[(10, 40, 5), (21, 21, 8)], [(30, 30, 30)], None],
                                   [1000, 4000, None])

    def solutions(self, solver, fronts, milliseconds):
        records = []
        for (start, goal), front, ms in zip(self.queries, fronts, milliseconds):
            if front is None:
                records.append({"source": start, "target": goal, "status": "timeout"})
            else:
                records.append({"source": start, "target": goal, "total_runtime(ms)": ms,
                                "finish_info": {"solutions": [{"cost_until_now": list(v)}
                                                              for v in front]}})
        log = os.path.join(self.dir, solver + ".json")
        with open(log, "w") as f:
            json.dump(records, f)
        out = os.path.join(self.dir, solver + ".sol")
        done = run(MOSB, "solutions", "import", "--instance", self.grid, "--view", "Grid_3",
                   "--queries", "three", "--json-log", log, "--solver", solver, "-o", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        return out

    def test_front_is_a_labelled_projection(self):
        fig = self.plot.front(self.fast, 0, reference=self.exact)
        (ax,) = fig.axes
        rings, dots = ax.collections
        self.assertEqual(sorted(map(tuple, rings.get_offsets().tolist())), [(10, 40), (20, 20)])
        self.assertEqual(sorted(map(tuple, dots.get_offsets().tolist())), [(10, 40), (21, 21)])
        self.assertIn("projection on c1, c2 of 3 objectives", ax.get_title())
        self.assertEqual([t.get_text() for t in ax.get_legend().get_texts()],
                         ["reference exact (2 vectors)", "fast (2 vectors)"])
        self.assertEqual((ax.get_xlim()[0], ax.get_ylim()[0]), (0, 0))
        fig = self.plot.front(self.fast, 0, objectives=("c3", "c1"))
        self.assertEqual(fig.axes[0].get_xlabel(), "c3")
        png = os.path.join(self.dir, "front.png")
        fig.savefig(png)
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_runtime_figure_data_refuses_malformed_arrays(self):
        """The binding of lib/solutions' runtime figure data: arrays of other lengths, a status
        code that is none of STATUSES and an empty solver list are refused, not misread."""
        from mosb import _mosb
        codes, one = np.array([0, 9], dtype=np.uint8), np.array([1.0, 2.0])
        with self.assertRaisesRegex(ValueError, "status code 9 is not one of STATUSES"):
            _mosb.cactus_series(codes, one)
        with self.assertRaisesRegex(ValueError, "two arrays of one length"):
            _mosb.cactus_series(np.array([0], dtype=np.uint8), one)
        with self.assertRaisesRegex(ValueError, "one array of each per solver"):
            _mosb.performance_profile([], [])
        with self.assertRaisesRegex(ValueError, "differ in length"):
            _mosb.runtime_scatter(np.array([0], dtype=np.uint8), np.array([1.0]),
                                  np.array([0, 0], dtype=np.uint8), one)
        data = _mosb.runtime_scatter(np.array([0, 3], dtype=np.uint8), np.array([1.0, 0.0]),
                                     np.array([0, 3], dtype=np.uint8), np.array([2.0, 5.0]))
        self.assertEqual((data["points"], data["query"], data["zero"]), ([(1.0, 2.0)], [0], 1))

    def test_comparison_figures(self):
        (ax,) = self.plot.cactus([self.exact, self.fast]).axes
        exact, fast = ax.get_lines()
        self.assertEqual(exact.get_ydata().tolist(), [2, 2, 2])
        self.assertEqual(fast.get_ydata().tolist(), [1, 4])
        self.assertEqual(fast.get_label(), "fast (2 solved)")
        self.assertEqual(ax.get_yscale(), "log")
        (ax,) = self.plot.performance_profile([self.exact, self.fast]).axes
        exact, fast = ax.get_lines()
        # exact is best on queries 1 and 2 and twice the best on query 0; fast best on query 0,
        # twice the best on query 1 and never solves query 2.
        self.assertEqual(exact.get_xdata().tolist(), [1, 2])
        self.assertEqual(exact.get_ydata().tolist(), [2 / 3, 1])
        self.assertAlmostEqual(fast.get_ydata().tolist()[-1], 2 / 3)
        (ax,) = self.plot.runtime_scatter(self.exact, self.fast).axes
        self.assertEqual(sorted(map(tuple, ax.collections[0].get_offsets().tolist())),
                         [(2, 1), (2, 4)])
        self.assertEqual(ax.get_title(), "Runtime per query (2 both completed)")

    def test_runtime_figures_read_the_data_as_the_report_does(self):
        """spec/EVALUATION.md §7's definitions, as `mosb report` draws them: the cactus plot counts
        solved queries, the scatter plot the queries both completed (solved or shown
        unreachable), and both show the solvers' own runtimes when every file has them on one
        clock; `runtime="wall"` shows mosb's."""
        if "WRITE_SOLUTION" not in os.environ:
            raise mosbtest.missing("WRITE_SOLUTION (mosb_test_write_solution) is not set")

        def write(name, spec):
            out = os.path.join(self.dir, name + ".sol")
            done = mosbtest.run(self.grid, "Grid_3", out, "0", "three", input=spec,
                                program=os.environ["WRITE_SOLUTION"],
                                env=dict(os.environ, MOSB_TEST_SOLVER_NAME=name))
            self.assertEqual(done.returncode, 0, done.stderr)
            return out
        a = write("a", "0 solved 1,2,3 t=2 r=0.5\n1 disconnected t=1 r=0.25\n2 timeout\n")
        b = write("b", "0 solved 1,2,3 t=4 r=1.5\n1 disconnected t=3 r=0.75\n"
                       "2 solved 1,2,3 t=1 r=0.1\n")
        (ax,) = self.plot.runtime_scatter(a, b).axes
        self.assertEqual(sorted(map(tuple, ax.collections[0].get_offsets().tolist())),
                         [(0.25, 0.75), (0.5, 1.5)])
        self.assertEqual(ax.get_title(), "Runtime per query (2 both completed)")
        (ax,) = self.plot.runtime_scatter(a, b, runtime="wall").axes
        self.assertEqual(sorted(map(tuple, ax.collections[0].get_offsets().tolist())),
                         [(1, 3), (2, 4)])
        (ax,) = self.plot.cactus([a, b]).axes
        self.assertEqual([line.get_ydata().tolist() for line in ax.get_lines()],
                         [[0.5], [0.1, 1.5]])
        self.assertEqual([line.get_label() for line in ax.get_lines()],
                         ["a (1 solved)", "b (2 solved)"])
        # The report over the same files: the same counts in its legends and notes.
        html = os.path.join(self.dir, "r.html")
        done = run(MOSB, "report", self.grid, "--solutions", a, b, "-o", html)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(html, encoding="utf-8") as f:
            page = f.read()
        self.assertIn(">a (1 solved)<", page)
        self.assertIn(">b (2 solved)<", page)
        self.assertIn("runtime as each solver reported it", page)
        self.assertIn("1 query completed by one of the two only, not drawn", page)
        with self.assertRaises(ValueError):
            self.plot.cactus([a], runtime="cpu")


class ParallelArcsTest(Temp):
    def test_to_scipy_csr_reduces_parallel_arcs_as_asked(self):
        gr = os.path.join(self.dir, "p.gr")
        with open(gr, "w") as f:
            f.write("p sp 3 4\na 1 2 5 1\na 1 2 1 7\na 2 3 2 250\na 1 2 3 250\n")
        path = os.path.join(self.dir, "p.mosb")
        done = run(MOSB, "convert", "dimacs", "--gr", gr, "-o", path)
        self.assertEqual(done.returncode, 0, done.stderr)
        g = mosb.open(path)
        keep = g.to_scipy_csr("c1")
        self.assertEqual(keep.nnz, 4)
        self.assertEqual(keep.toarray()[0, 1], 9)  # what scipy does with duplicates: a sum
        self.assertEqual(g.to_scipy_csr("c1", parallel="min").toarray()[0, 1], 1)
        self.assertEqual(g.to_scipy_csr("c1", parallel="max").toarray()[0, 1], 5)
        wide = g.to_scipy_csr("c2", parallel="sum")  # 1 + 7 + 250 overflows c2's u8
        self.assertEqual(wide.toarray()[0, 1], 258)
        self.assertEqual(wide.nnz, 2)
        self.assertEqual(g.to_scipy_csr("c2", parallel="min").dtype, g.cost("c2").dtype)
        with self.assertRaises(ValueError):
            g.to_scipy_csr("c1", parallel="mean")


if __name__ == "__main__":
    mosbtest.main()
