#!/usr/bin/python3
"""End-to-end tests of Moving AI `optimal` references (section kind 17, spec/SOLUTIONS.md §6):
`convert movingai --scen`, `convert guards --scen`, `queries import --scen`, `inspect`, `verify`
and the bracket of `solutions verify`.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_references.py

The section is read back with the independent reference reader (spec/reference), which knows no
kind 17 and reads it as a plain f64 column. The real maps come from shared/data/movingai (skipped
visibly when absent).
"""

import hashlib
import json
import os

import mosbtest
from mosbtest import CliTest, mosb_reader, run, setUpModule  # noqa: F401
from test_guards import real_maps

QUERY_REFERENCE = 17
MAP = "type octile\nheight 3\nwidth 3\nmap\n...\n...\n.@.\n"
# (sx, sy, gx, gy, optimal): one diagonal pair (c* = 28), two straight steps (c* = 20), a step of
# each (c* = 24), and a detour around the wall at (1, 2) (c* = 40: four straight steps, since no
# move cuts the wall's corners).
ROWS = [(0, 0, 2, 2, "2.82842712"), (0, 0, 2, 0, "2"), (0, 0, 2, 1, "2.41421356"),
        (0, 2, 2, 2, "4")]
SCEN = "version 1\n" + "".join("0\tm.map\t3\t3\t%d\t%d\t%d\t%d\t%s\n" % r for r in ROWS)


class ReferencesCli(CliTest):
    def setUp(self):
        super().setUp()
        self.map = self.write("m.map", MAP)
        self.scen = self.write("m.scen", SCEN)

    def refused(self, args, message):
        self.assert_error(self.mosb(*args), message)

    def reference(self, instance, name="scen"):
        inst = mosb_reader.open_instance(instance)
        return [float(v) for v in inst.array(inst.section(name, QUERY_REFERENCE))], inst

    def test_convert_movingai_keeps_optimal_unchanged(self):
        out = self.path("a.mosb")
        self.ok("convert", "movingai", "--map", self.map, "--scen", self.scen, "-o", out)
        values, inst = self.reference(out)
        self.assertEqual(values, [float(r[4]) for r in ROWS])
        self.assertEqual(inst.metadata["queries.scen.reference.objective"], "length")
        self.assertEqual(inst.metadata["queries.scen.reference.source"], "movingai-optimal")
        with open(out, "rb") as f:
            data = f.read()
        self.assertEqual(int.from_bytes(data[14:16], "little"), 0)  # still version 1.0
        self.ok("verify", "--level", "full", out)
        text = self.ok("inspect", out).stdout
        self.assertIn("scen                    4 queries, references for 'length' (movingai-optimal)",
                      text)
        sets = json.loads(self.ok("inspect", "--json", out).stdout)["query_sets"]
        self.assertEqual(sets, [{"name": "scen", "queries": 4, "reference":
                                 {"objective": "length", "source": "movingai-optimal"}}])
        # Rerun: byte-identical.
        again = self.path("b.mosb")
        self.ok("convert", "movingai", "--map", self.map, "--scen", self.scen, "-o", again)
        with open(again, "rb") as f:
            self.assertEqual(hashlib.sha256(f.read()).digest(), hashlib.sha256(data).digest())

    def test_bad_optimal_is_located(self):
        for bad in ("-1", "1e999", "nan", "inf", "two"):
            with self.subTest(optimal=bad):
                s = self.write("bad.scen", "version 1\n0\tm.map\t3\t3\t0\t0\t2\t2\t%s\n" % bad)
                self.refused(("convert", "movingai", "--map", self.map, "--scen", s, "-o",
                              self.path("x.mosb")),
                             "%s:2:21: expected the optimal length (a non-negative number), found "
                             "'%s'" % (s, bad))
                self.assertFalse(os.path.exists(self.path("x.mosb")))

    def test_queries_import_scen_matches_convert(self):
        bare, full = self.path("bare.mosb"), self.path("full.mosb")
        self.ok("convert", "movingai", "--map", self.map, "-o", bare)
        self.ok("convert", "movingai", "--map", self.map, "--scen", self.scen, "-o", full)
        out = self.path("imported.mosb")
        self.ok("queries", "import", bare, self.scen, "--scen", "--set", "scen", "-o", out)
        sections = lambda f: {(s["kind"], s["name"]): s["checksum"]  # noqa: E731
                              for s in json.loads(self.ok("inspect", "--json", f).stdout)["sections"]
                              if s["kind"] in ("queries", "query_reference")}
        self.assertEqual(sections(out), sections(full))
        self.assertEqual(len(sections(out)), 2)
        meta = mosb_reader.open_instance(out).metadata
        self.assertEqual(meta["queries.scen.format"], "movingai-scen")
        self.assertEqual(meta["queries.scen.reference.source"], "movingai-optimal")
        self.ok("verify", "--level", "full", out)
        # Replaced by plain pairs: the reference and its keys go.
        pairs = self.write("p.txt", "0 1\n")
        self.ok("queries", "import", out, pairs, "--set", "scen", "--replace", "--in-place")
        inst = mosb_reader.open_instance(out)
        self.assertEqual([s for s in inst.sections if s.kind == QUERY_REFERENCE], [])
        self.assertNotIn("queries.scen.reference.objective", inst.metadata)
        self.assertNotIn("queries.scen.format", inst.metadata)
        self.ok("verify", "--level", "full", out)

    def test_queries_import_scen_errors(self):
        bare = self.path("bare.mosb")
        self.ok("convert", "movingai", "--map", self.map, "-o", bare)
        blocked = self.write("b.scen", "version 1\n0\tm.map\t3\t3\t1\t2\t0\t0\t1\n")
        self.refused(("queries", "import", bare, blocked, "--scen", "--set", "s", "-o",
                      self.path("x.mosb")),
                     "%s:2:13: the start cell (1, 2) is blocked in %s" % (blocked, bare))
        self.refused(("queries", "import", bare, self.scen, "--scen", "--id-base", "1", "--set", "s",
                      "-o", self.path("x.mosb")),
                     "a scenario (--scen) gives cells, not ids: --id-base and --match do not apply")
        grid = self.path("grid.mosb")
        self.ok("generate", "grid", "--width", "3", "--height", "3", "-o", grid)
        r = run("queries", "import", grid, self.scen, "--scen", "--set", "s", "-o",
                self.path("x.mosb"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("--scen needs an instance converted from a Moving AI map", r.stderr)
        self.assertFalse(os.path.exists(self.path("x.mosb")))

    def solutions(self, instance, table):
        t = self.write("front.csv", "query,length,exposure\n" + table)
        sol = self.path("f.sol")
        self.ok("solutions", "import", "--instance", instance, "--view", "Games-GUARDS_2", "--queries",
                  "scen", "--table", t, "-o", sol)
        return run("solutions", "verify", sol, "--instance", instance), sol

    def test_solutions_verify_applies_the_bracket(self):
        exposure = self.write("e.txt", "0 1 2\n1 1 1\n0 0 5\n")
        inst = self.path("g.mosb")
        self.ok("convert", "guards", "--map", self.map, "--exposure", exposure, "--scen", self.scen,
                  "-o", inst)
        self.assertEqual(self.reference(inst)[0], [float(r[4]) for r in ROWS])
        ok, _ = self.solutions(inst, "0,28,6\n0,30,1\n1,20,3\n2,24,2\n3,40,9\n")
        self.assertEqual(ok.returncode, 0, ok.stderr)
        # Query 1's minimum length raised to 30: c*/10 = 3 > L* = 2.
        bad, sol = self.solutions(inst, "0,28,6\n1,30,3\n")
        self.assertEqual(bad.returncode, 1)
        self.assertEqual(bad.stderr.strip(),
                         "mosb: %s: query 1: [reference] the smallest length c* = 30 does not match "
                         "the movingai-optimal optimum L* = 2: c*/10 = 3 > L* + tau "
                         "(spec/SOLUTIONS.md section 6)" % sol)
        # Query 3's minimum lowered to 20 (a path through the wall): L* exceeds the upper bound.
        bad, sol = self.solutions(inst, "3,20,1\n")
        self.assertEqual(bad.returncode, 1)
        self.assertIn("query 3: [reference] the smallest length c* = 20 does not match the "
                      "movingai-optimal optimum L* = 4: L* > (sqrt 2/1.4) c*/10 + tau", bad.stderr)
        # Unsolved queries are not checked; only the minimum of a front counts.
        ok, _ = self.solutions(inst, "1,20,9\n1,40,1\n")
        self.assertEqual(ok.returncode, 0, ok.stderr)

    def test_real_maps(self):
        for name, rows, _, m, s in real_maps(self):
            with self.subTest(map=name):
                out = self.path(name + ".mosb")
                self.ok("convert", "movingai", "--map", m, "--scen", s, "-o", out)
                values, _ = self.reference(out)
                with open(s) as f:
                    optimal = [float(line.split("\t")[8]) for line in f.read().splitlines()[1:]
                               if line.strip()]
                self.assertEqual(len(values), rows)
                self.assertEqual(values, optimal)
                self.ok("verify", "--level", "full", out)


if __name__ == "__main__":
    mosbtest.main()
