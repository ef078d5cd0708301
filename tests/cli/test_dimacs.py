#!/usr/bin/python3
"""End-to-end tests of `mosb convert dimacs` (with the DIMACS-Extended options) and `mosb export dimacs`.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_dimacs.py

The real files of /work/shared/data/dimacs-small are used when present (skipped visibly otherwise).
"""

import json
import os

import mosbtest
from mosbtest import DATA as SHARED_DATA
from mosbtest import METADATA_KIND, CliTest, entries, read, setUpModule  # noqa: F401
from mosbtest import metadata as metadata_of_bytes

DATA = os.path.join(SHARED_DATA, "dimacs-small")

GRAPH = "c hand-made\np sp 4 7\na 1 2 3\na 2 3 4\na 1 3 9\na 3 4 1\na 4 1 2\na 1 2 5\na 2 2 7\n"
ELEVATION = "c metres\np aux sp elev 4\nv 1 100\nv 2 -20\nv 3 50\nv 4 50\n"


def sections(path):
    """(kind, name) -> checksum for every section but the metadata, from the raw table."""
    return {(e["kind"], e["name"]): e["checksum"] for e in entries(read(path))
            if e["kind"] != METADATA_KIND}


def metadata(path):
    return metadata_of_bytes(read(path))


class DimacsCase(CliTest):
    def read(self, name):
        return read(self.path(name), "r")

    def ok(self, *args):
        r = super().ok(*args)
        self.assertEqual(r.stderr, "", r)
        return r

    def fails(self, message, *args):
        r = self.mosb(*args)
        self.assert_one_line_error(r, message)
        self.assertEqual(r.stdout, "", r)
        return r


class RealData(DimacsCase):
    def setUp(self):
        super().setUp()
        self.skip_unless_present(DATA)

    def test_ex1_three_objective_files(self):
        gr = [os.path.join(DATA, "ex1-c%d.gr" % i) for i in (1, 2, 3)]
        r = self.ok("convert", "dimacs", "--gr", gr[0], "--gr", gr[1], "--gr", gr[2], "-o", "ex1.mosb")
        self.assertIn("5 vertices, 14 arcs, 3 objectives", r.stdout)
        self.ok("verify", "ex1.mosb", "--level", "full")

    def test_ex1_extended_and_round_trip(self):
        gr = [os.path.join(DATA, "ex1-c%d.gr" % i) for i in (1, 2, 3)]
        args = ["--gr", gr[0], "--gr", gr[1], "--objective", "distance", "--objective", "time",
                "--derive", "hop,avg-outdegree", "--view", "ex1_3=distance,time,hop", "--name", "ex1"]
        r = self.ok("convert", "dimacs", *args, "-o", "a.mosb")
        self.assertIn("5 vertices, 14 arcs, 4 objectives", r.stdout)
        r = self.ok("export", "dimacs", "a.mosb", "-o", "out")
        self.assertEqual(sorted(os.listdir(self.path("out"))),
                         ["ex1-avg_outdegree.gr", "ex1-distance.gr", "ex1-hop.gr", "ex1-time.gr"])
        self.assertEqual(r.stdout.count("wrote "), 4)
        back = ["--gr", "out/ex1-distance.gr", "--gr", "out/ex1-time.gr", "--gr", "out/ex1-avg_outdegree.gr",
                "--gr", "out/ex1-hop.gr", "--objective", "distance", "--objective", "time",
                "--objective", "avg_outdegree", "--objective", "hop"]
        self.ok("convert", "dimacs", *back, "-o", "b.mosb")
        self.assertEqual(sections(self.path("a.mosb")), sections(self.path("b.mosb")))

    def test_truncated_ny_head_is_refused_with_counts(self):
        self.fails("USA-road-d.NY.head.gr:5:13: the header declares 733846 arcs, found 92",
                   "convert", "dimacs", "--gr", os.path.join(DATA, "USA-road-d.NY.head.gr"), "-o", "ny.mosb")
        self.assertFalse(os.path.exists(self.path("ny.mosb")))


class ParallelArcsAndLoops(DimacsCase):
    def test_kept_and_counted_by_inspect(self):
        # GRAPH lists 1->2 twice (one parallel copy) and 2->2 (one self-loop).
        self.write("g.gr", GRAPH)
        self.ok("convert", "dimacs", "--gr", "g.gr", "-o", "g.mosb")
        report = json.loads(self.ok("inspect", "--json", "g.mosb", "--verify", "full").stdout)
        self.assertEqual((report["arcs"], report["self_loops"], report["parallel_arcs"]), (7, 1, 1))
        self.assertEqual(report["verified"], "full")
        text = self.ok("inspect", "g.mosb", "--verify", "full").stdout
        self.assertIn("self-loops  1", text)
        self.assertIn("parallel    1", text)
        # Without --verify, a look at the header, the table and the metadata only, which it says.
        report = json.loads(self.ok("inspect", "--json", "g.mosb").stdout)
        self.assertEqual((report["verified"], report["self_loops"]), (None, None))
        self.assertIn("verified    no (", self.ok("inspect", "g.mosb").stdout)
        # So a damaged payload is not seen by a look, and is by --verify.
        data = bytearray(read(self.path("g.mosb")))
        payload = [x for x in report["sections"] if x["kind"] != "metadata"][-1]
        data[payload["offset"]] ^= 0xFF
        with open(self.path("bad.mosb"), "wb") as f:
            f.write(data)
        self.ok("inspect", "bad.mosb")
        r = self.mosb("inspect", "bad.mosb", "--verify", "checksums")
        self.assertEqual(r.returncode, 1, r)


class Extended(DimacsCase):
    def convert(self, *extra, output="g.mosb"):
        self.write("g.gr", GRAPH)
        self.write("g.elev", ELEVATION)
        return self.mosb("convert", "dimacs", "--gr", "g.gr", *extra, "-o", output)

    def test_columns_in_fixed_order_whatever_the_option_order(self):
        r = self.convert("--derive", "hop", "--derive", "avg-outdegree", "--elevation", "g.elev")
        self.assertEqual(r.returncode, 0, r)
        names = [name for (kind, name) in sections(self.path("g.mosb")) if kind == 7]
        self.assertEqual(sorted(names), ["avg_outdegree", "c1", "elevation", "hop"])
        self.ok("export", "dimacs", "g.mosb", "-o", "x")
        arcs = lambda name: [line.split()[3] for line in self.read("x/g-%s.gr" % name).splitlines()
                             if line.startswith("a ")]
        self.assertEqual(arcs("elevation"), ["120", "50", "120", "70", "0", "0", "50"])
        self.assertEqual(arcs("avg_outdegree"), ["5", "4", "5", "3", "4", "2", "4"])
        self.assertEqual(arcs("hop"), ["1"] * 7)
        m = metadata(self.path("g.mosb"))
        self.assertEqual(m["source.param.derive"], "avg-outdegree,hop")

    def test_round_half_up(self):
        r = self.convert("--derive", "avg-outdegree", "--avg-outdegree-mode", "round-half-up")
        self.assertEqual(r.returncode, 0, r)
        self.ok("export", "dimacs", "g.mosb", "-o", "x")
        values = [line.split()[3] for line in self.read("x/g-avg_outdegree.gr").splitlines() if line[0] == "a"]
        self.assertEqual(values, ["3", "2", "3", "2", "2", "1", "2"])

    def test_views_and_view_export(self):
        r = self.convert("--derive", "hop", "--view", "two=hop,c1", "--view", "one=c1@ny100")
        self.assertEqual(r.returncode, 0, r)
        m = metadata(self.path("g.mosb"))
        self.assertEqual(m["view.two.objectives"], "hop,c1")
        self.assertEqual(m["view.one.objectives"], "c1")
        self.assertNotIn("view.one.queries", m)
        self.assertEqual(m["source.param.view.one"], "c1@ny100")
        # The instance records id_base 1: --id-base 0 is refused (exit 2) unless forced.
        r = self.mosb("export", "dimacs", "g.mosb", "-o", "v", "--view", "two", "--id-base", "0")
        self.assert_one_line_error(r, "--id-base 0 contradicts g.mosb, whose metadata records "
                                   "id_base 1", code=2)
        self.assertFalse(os.path.exists(self.path("v")))
        self.ok("export", "dimacs", "g.mosb", "-o", "v", "--view", "two", "--id-base", "0",
                "--force-id-base")
        self.assertEqual(sorted(os.listdir(self.path("v"))), ["g-c1.gr", "g-hop.gr"])
        self.assertIn("\na 0 1 3\n", self.read("v/g-c1.gr"))
        # The view's objective list given directly: the same files, no view needed.
        self.ok("export", "dimacs", "g.mosb", "-o", "w", "--objectives", "hop,c1")
        self.ok("export", "dimacs", "g.mosb", "-o", "u", "--view", "two")
        for name in ("g-c1.gr", "g-hop.gr"):
            self.assertEqual(self.read("w/" + name), self.read("u/" + name))
        r = self.mosb("export", "dimacs", "g.mosb", "-o", "z", "--view", "two", "--objectives", "c1")
        self.assertEqual(r.returncode, 2, r)
        r = self.mosb("export", "dimacs", "g.mosb", "-o", "z", "--objectives", "c1,c1")
        self.assert_one_line_error(r, "--objectives: objective 'c1' listed twice", code=2)
        self.fails("no objective named 'nope'", "export", "dimacs", "g.mosb", "-o", "z",
                   "--objectives", "nope")

    def test_errors_are_one_line_with_exit_1(self):
        self.write("bad.elev", "p aux sp elev 4\nv 1 1\nv 2 x\n")
        self.fails("bad.elev:3:5: expected an integer elevation, found 'x'", *self.convert_args("--elevation", "bad.elev"))
        self.fails("--view 'v': objective 'hop' is not a column (columns: c1)",
                   *self.convert_args("--view", "v=hop"))
        # A malformed --view is a usage error (exit 2); a view of a missing column fails on input.
        r = self.mosb(*self.convert_args("--view", "v"))
        self.assert_one_line_error(r, "--view 'v': expected NAME=OBJ1,OBJ2,...[@QUERYSET]", code=2)
        self.assertFalse(os.path.exists(self.path("g.mosb")))
        r = self.mosb(*self.convert_args("--derive", "elevation"))
        self.assertNotEqual(r.returncode, 0, r)
        self.ok("convert", "dimacs", "--gr", "g.gr", "-o", "g.mosb")
        self.fails("no view 'nope'", "export", "dimacs", "g.mosb", "-o", "o", "--view", "nope")
        self.fails("g.gr", "export", "dimacs", "g.gr", "-o", "o")

    def test_a_file_name_that_is_not_utf8_is_kept_escaped_and_the_file_verifies(self):
        # Metadata is UTF-8 (FORMAT.md §7): the name of the input, bytes on Linux, used to go in
        # raw, giving a file that `verify` refuses. A --name that is not UTF-8 is refused.
        name = "caf\udce9.gr"  # the byte 0xE9 alone (surrogateescape)
        self.write(name, GRAPH)
        self.ok("convert", "dimacs", "--gr", name, "-o", "g.mosb")
        self.ok("verify", "g.mosb", "--level", "full")
        meta = mosbtest.mosb_reader.open_instance(self.path("g.mosb")).metadata
        self.assertEqual(meta["benchmark"], "caf\\xe9")
        self.assertEqual(meta["source.input.0.name"], "caf\\xe9.gr")
        r = self.mosb("convert", "dimacs", "--gr", name, "--name", "bad\udcff", "-o", "n.mosb")
        self.assert_one_line_error(r, "metadata value of 'benchmark' is not valid UTF-8")
        self.assertFalse(os.path.exists(self.path("n.mosb")))

    def convert_args(self, *extra):
        self.write("g.gr", GRAPH)
        return ["convert", "dimacs", "--gr", "g.gr", *extra, "-o", "g.mosb"]

    def test_deterministic_bytes(self):
        for out in ("1.mosb", "2.mosb"):
            self.write("g.elev", ELEVATION)
            r = self.convert("--elevation", "g.elev", "--derive", "hop", output=out)
            self.assertEqual(r.returncode, 0, r)
        with open(self.path("1.mosb"), "rb") as a, open(self.path("2.mosb"), "rb") as b:
            self.assertEqual(a.read(), b.read())


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
