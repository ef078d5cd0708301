#!/usr/bin/python3
"""End-to-end tests of `mosb generate netmaker`, `mosb convert netmaker` and the `--suite` mode of
`generate grid` and `generate netmaker` (spec/GENERATORS.md: NetMaker, Suites).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_synthetic.py

The full suites write about 1.3 GB; these tests use the hidden subset options (--sizes, --vertices).
"""

import hashlib
import json
import os
import pty
import re
import subprocess

import mosbtest
from mosbtest import DATA, MOSB, CliTest, read, setUpModule  # noqa: F401
from test_queries import MASK, mix  # SplitMix64 as spec/GENERATORS.md writes it

NETMAKER_FILE = os.path.join(DATA, "netmaker", "netMaker_3o_10000n_1amin_10amax_20i_1s_scorr_79134.gr")

GOLDEN = 0x9E3779B97F4A7C15


def instance_seed(suite_seed, key):
    return mix((suite_seed + GOLDEN * key) & MASK)


class SyntheticTest(CliTest):
    def inspect(self, path):
        return json.loads(self.ok("inspect", "--json", path).stdout)

    def read(self, *names):
        return read(self.path(*names))

    def manifest(self, directory):
        """The MANIFEST's entries (spec/MANIFEST.md) as [benchmark, file, size, digest] rows, after
        checking its header record and each entry's SHA-256 against the file."""
        with open(self.path(directory, "MANIFEST"), encoding="utf-8") as f:
            records = [json.loads(line) for line in f.read().splitlines()]
        self.assertEqual(records[0], {"format": "mosb-manifest", "version": 1})
        rows = []
        for record in records[1:]:
            self.assertEqual(record["sha256"],
                             hashlib.sha256(self.read(directory, record["file"])).hexdigest())
            rows.append([record["benchmark"], record["file"], str(record["size"]),
                         record["digest"]])
        return rows


class GenerateNetMaker(SyntheticTest):
    ARGS = ["generate", "netmaker", "--vertices", "1000", "--amin", "1", "--amax", "10",
            "--locality", "20"]

    def test_instance_shape_views_and_metadata(self):
        r = self.ok(*self.ARGS, "--seed", "3", "-o", self.path("n.mosb"))
        self.assertIn("1000 vertices", r.stdout)
        self.ok("verify", "--level", "full", self.path("n.mosb"))
        info = self.inspect(self.path("n.mosb"))
        md = info["metadata"]
        self.assertEqual(md["view.NetMaker-1k_3.objectives"], "c1,c2,c3")
        self.assertEqual(md["view.NetMaker-1k_3.queries"], "default")
        self.assertEqual(md["family"], "synthetic")
        self.assertEqual(md["id_base"], "0")
        self.assertEqual(md["source.command"], "generate netmaker")
        self.assertEqual(md["source.param.seed"], "3")
        self.assertEqual(info["query_sets"], [{"name": "default", "queries": 50}])
        (kind,) = [s for s in info["sections"] if s["kind"] == "arc_data"]
        self.assertEqual((kind["name"], kind["type"], kind["rows"]), ("kind", "u8", info["arcs"]))
        self.assertLess(abs(info["arcs"] - 6000), 400)  # sd of the arc count ~ sqrt(1000 * 20/3) = 82

    def test_same_seed_same_bytes_other_seed_other_bytes(self):
        for name, seed in (("a", "5"), ("b", "5"), ("c", "6")):
            self.ok(*self.ARGS, "--seed", seed, "-o", self.path(name + ".mosb"))
        self.assertEqual(self.read("a.mosb"), self.read("b.mosb"))
        self.assertNotEqual(self.read("a.mosb"), self.read("c.mosb"))

    def test_bad_parameters_are_one_line_errors(self):
        r = self.mosb("generate", "netmaker", "--vertices", "100", "--amin", "5", "--amax", "5",
                      "-o", self.path("x.mosb"))
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r)
        self.assertFalse(os.path.exists(self.path("x.mosb")))
        r = self.mosb("generate", "netmaker", "--vertices", "1000")
        self.assertNotEqual(r.returncode, 0, r)
        self.assertIn("--suite", r.stderr)
        r = self.mosb("generate", "netmaker", "--suite", self.path("s"), "-o", self.path("x.mosb"))
        self.assertNotEqual(r.returncode, 0, r)
        self.assertFalse(os.path.exists(self.path("s")))


class Suites(SyntheticTest):
    def test_netmaker_suite_subset_independent_of_threads(self):
        self.ok("generate", "netmaker", "--suite", self.path("one"), "--vertices", "1000",
                "--threads", "1")
        r = self.ok("generate", "netmaker", "--suite", self.path("many"), "--vertices", "1000")
        self.assertEqual(r.stderr, "", "no progress when stderr is not a terminal")
        self.assertEqual(len(r.stdout.splitlines()), 1, r)
        rows = self.manifest("one")
        self.assertEqual([row[0] for row in rows],
                         ["NetMaker-N1000-I20-1", "NetMaker-N1000-I20-2",
                          "NetMaker-N1000-I50-1", "NetMaker-N1000-I50-2"])
        self.assertEqual(self.read("one", "MANIFEST"), self.read("many", "MANIFEST"))
        for name, file, size, digest in rows:
            self.assertEqual(file, name + ".mosb")
            self.assertEqual(int(size), os.path.getsize(self.path("one", file)))
            self.assertEqual(self.read("one", file), self.read("many", file))
            self.assertEqual(self.inspect(self.path("one", file))["digest"], digest)
        # The seed of an instance comes from its parameters: the standalone command reproduces it.
        seed = instance_seed(1, ((1000 << 16) + 50) * 4 + 2)
        self.ok("generate", "netmaker", "--vertices", "1000", "--locality", "50", "--seed", str(seed),
                "--name", "NetMaker-N1000-I50-2", "-o", self.path("single.mosb"))
        self.assertEqual(self.read("single.mosb"), self.read("one", "NetMaker-N1000-I50-2.mosb"))

    def test_grid_suite_subset_matches_single_generation(self):
        self.ok("generate", "grid", "--suite", self.path("g"), "--sizes", "300,350", "--seed", "4")
        rows = self.manifest("g")
        self.assertEqual([row[0] for row in rows],
                         ["Grid-300x300", "Grid-300x350", "Grid-350x300", "Grid-350x350"])
        self.assertEqual(sorted(os.listdir(self.path("g"))),
                         sorted(["MANIFEST"] + [row[1] for row in rows]))
        seed = instance_seed(4, (300 << 20) + 350)
        self.ok("generate", "grid", "--width", "300", "--height", "350", "--objectives", "3",
                "--seed", str(seed), "-o", self.path("single.mosb"))
        self.assertEqual(self.read("single.mosb"), self.read("g", "Grid-300x350.mosb"))
        md = self.inspect(self.path("g", "Grid-350x300.mosb"))["metadata"]
        self.assertEqual(md["view.Grid_2.objectives"], "c1,c2")
        self.assertEqual(md["view.Grid_3.objectives"], "c1,c2,c3")
        self.assertEqual(md["source.param.seed"], str(instance_seed(4, (350 << 20) + 300)))

    def on_terminal(self, *args):
        """Runs mosb with stderr on a pseudo-terminal; returns (result, what the terminal showed)."""
        leader, follower = pty.openpty()
        out = b""
        try:
            process = subprocess.Popen([MOSB, *args], cwd=self.dir, stdout=subprocess.PIPE,
                                       stderr=follower, text=True)
            os.close(follower)
            follower = -1
            while True:  # read while it runs, so a full terminal buffer cannot block it
                try:
                    chunk = os.read(leader, 4096)
                except OSError:  # EIO: the terminal has no writer left
                    break
                if not chunk:
                    break
                out += chunk
            stdout, _ = process.communicate(timeout=300)
        finally:
            if follower >= 0:
                os.close(follower)
            os.close(leader)
        return process.returncode, stdout, out.decode()

    def test_suite_progress_on_a_terminal(self):
        code, stdout, shown = self.on_terminal("generate", "grid", "--suite", self.path("t"), "--sizes", "20,30")
        self.assertEqual(code, 0, shown)
        self.assertEqual(len(stdout.splitlines()), 1, stdout)
        self.assertIn("mosb: suite 4/4 (100%)", shown)

    def test_progress_of_a_long_command_on_a_terminal(self):
        # Seconds of work: the stage line starts at 0 and ends at 100%.
        code, stdout, shown = self.on_terminal("generate", "grid", "--width", "1200", "--height", "1200",
                                               "-o", self.path("big.mosb"))
        self.assertEqual(code, 0, shown)
        self.assertTrue(stdout.startswith("wrote "), stdout)
        draws = re.findall(r"mosb: write (\d+)/(\d+) \((\d+)%\)", shown)
        self.assertGreaterEqual(len(draws), 2, shown)
        self.assertEqual(draws[-1][0], draws[-1][1])
        self.assertEqual(draws[-1][2], "100")
        self.assertTrue(shown.endswith("\n"), repr(shown[-40:]))

    def test_no_progress_when_stderr_is_not_a_terminal(self):
        r = self.ok("generate", "grid", "--width", "1200", "--height", "1200", "-o", self.path("big.mosb"))
        self.assertEqual(r.stderr, "")

    def test_suite_options_conflicts(self):
        r = self.mosb("generate", "grid", "--suite", self.path("x"), "--width", "10")
        self.assertNotEqual(r.returncode, 0, r)
        r = self.mosb("generate", "grid", "--sizes", "20", "-o", self.path("y.mosb"))
        self.assertNotEqual(r.returncode, 0, r)
        self.assertEqual(os.listdir(self.dir), [])


class ConvertNetMaker(SyntheticTest):
    def test_view_option_adds_or_replaces_views(self):
        # Every convert and generate command takes --view NAME=OBJ,...[@SET] (the parser of
        # convert dimacs): here one more view and a replaced default.
        gr = self.write("n.gr", "p sp 3 2\na 0 1 5 6\na 1 2 7 8\n")
        self.ok("convert", "netmaker", gr, "--view", "second=c2", "--view", "NetMaker-3_2=c2,c1",
                "-o", self.path("n.mosb"))
        md = self.inspect(self.path("n.mosb"))["metadata"]
        self.assertEqual(md["view.second.objectives"], "c2")
        self.assertEqual(md["source.param.view.second"], "c2@default")
        self.assertEqual(md["view.NetMaker-3_2.objectives"], "c2,c1")
        r = self.mosb("convert", "netmaker", gr, "--view", "x=c9", "-o", self.path("x.mosb"))
        self.assert_one_line_error(r, "--view 'x': objective 'c9' is not a column (columns: c1,c2)")
        self.assertFalse(os.path.exists(self.path("x.mosb")))
        self.ok("generate", "grid", "--width", "3", "--height", "3", "--view", "Grid_2=c2,c1",
                "--view", "one=c3@default", "-o", self.path("g.mosb"))
        md = self.inspect(self.path("g.mosb"))["metadata"]
        self.assertEqual(md["view.Grid_2.objectives"], "c2,c1")
        self.assertEqual(md["view.Grid_2.queries"], "default")
        self.assertEqual(md["view.one.queries"], "default")
        self.assertEqual(md["view.Grid_3.objectives"], "c1,c2,c3")
        r = self.mosb("generate", "netmaker", "--suite", self.path("s"), "--view", "v=c1")
        self.assertEqual(r.returncode, 2, r)

    def test_published_file(self):
        self.skip_unless_present(NETMAKER_FILE)
        r = self.ok("convert", "netmaker", NETMAKER_FILE, "-o", self.path("n.mosb"))
        self.assertIn("10000 vertices, 59750 arcs, 3 objectives", r.stdout)
        md = self.inspect(self.path("n.mosb"))["metadata"]
        self.assertEqual(md["view.NetMaker-10k_3.objectives"], "c1,c2,c3")
        self.assertNotIn("view.NetMaker-10k_3.queries", md)
        self.assertEqual(md["family"], "synthetic")
        self.assertEqual(md["id_base"], "0")
        self.assertEqual(md["source.command"], "convert netmaker")
        self.assertEqual(md["benchmark"], "netMaker_3o_10000n_1amin_10amax_20i_1s_scorr_79134")
        self.assertEqual(md["source.input.0.size"], str(os.path.getsize(NETMAKER_FILE)))
        self.ok("convert", "netmaker", NETMAKER_FILE, "--name", "NetMaker-10k", "-o", self.path("m.mosb"))
        self.assertEqual(self.inspect(self.path("m.mosb"))["metadata"]["benchmark"], "NetMaker-10k")

    def test_small_file_and_errors(self):
        with open(self.path("t.gr"), "w") as f:
            f.write("p sp 3 3\na 0 1 5 6 7\na 1 2 1 2 3\na 2 0 9 9 9\n")
        r = self.ok("convert", "netmaker", self.path("t.gr"), "-o", self.path("t.mosb"))
        self.assertIn("3 vertices, 3 arcs, 3 objectives", r.stdout)
        with open(self.path("bad.gr"), "w") as f:
            f.write("p sp 3 1\na 0 3 1 1 1\n")  # id 3 is out of range for 0-based ids
        r = self.mosb("convert", "netmaker", self.path("bad.gr"), "-o", self.path("bad.mosb"))
        self.assertEqual(r.returncode, 1, r)
        self.assertIn("bad.gr:2:", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r)


if __name__ == "__main__":
    mosbtest.main()
