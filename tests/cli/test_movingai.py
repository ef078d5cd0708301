#!/usr/bin/python3
"""End-to-end tests of `mosb convert movingai` (spec/families/games.md §6).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_movingai.py

Vertex and arc counts and arc lengths are recomputed with numpy array shifts (test_guards.py's
expected_arcs, with a zero exposure), independently of the converter's per-cell loops. The real maps
come from shared/data/movingai (skipped visibly when absent).
"""

import os

import numpy as np

import mosbtest
from mosbtest import CliTest, mosb_reader, run, setUpModule  # noqa: F401
from test_guards import (arc_rows, expected_arcs, query_cells, read_map, real_maps,
                         scenario_endpoints, sorted_rows)

HAND_MADE = "type octile\nheight 4\nwidth 5\nmap\n..@.S\n.@...\n...W.\nT.G..\n"


class MovingaiCli(CliTest):
    def check_instance(self, out, passable):
        """The instance is the octile graph of `passable`: cells, arcs and lengths."""
        inst = mosb_reader.open_instance(out)
        tx, ty, hx, hy, length, _ = expected_arcs(passable, np.zeros(passable.shape, dtype=np.int64))
        self.assertEqual(inst.n, int(passable.sum()))
        self.assertEqual(inst.m, len(tx))
        self.assertEqual([name for name, _ in inst.costs()], ["length"])
        self.assertEqual(inst.metadata["objective.length.unit"], "0.1 cell")
        cell_section = inst.section("cell", mosb_reader.VERTEX_DATA)
        self.assertEqual(np.dtype(cell_section.dtype), np.dtype("<u2"))
        cells = np.asarray(inst.array(cell_section), dtype=np.int64)
        w = passable.shape[1]
        self.assertTrue(np.array_equal(cells[:, 1] * w + cells[:, 0], np.flatnonzero(passable.ravel())))
        want = np.stack([tx, ty, hx, hy, length], axis=1)
        self.assertTrue(np.array_equal(arc_rows(inst, cells, ["length"]), sorted_rows(want)))
        self.assertEqual(inst.metadata["map.width"], str(passable.shape[1]))
        self.assertEqual(inst.metadata["map.height"], str(passable.shape[0]))
        self.assertEqual(inst.metadata["family"], "games")
        self.assertEqual(inst.metadata["source.command"], "convert movingai")
        self.assertNotIn("view.Games-GUARDS_2.objectives", inst.metadata)
        r = run("verify", out, "--level", "full")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        return inst

    def test_hand_made_map(self):
        m = self.write("hand.map", HAND_MADE)
        out = self.path("hand.mosb")
        r = run("convert", "movingai", "--map", m, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        inst = self.check_instance(out, read_map(m))
        # Worked by hand: 16 passable cells ('.', 'G', 'S'); 'W', '@' and 'T' blocked.
        self.assertEqual(inst.n, 16)
        self.assertEqual(inst.metadata["benchmark"], "hand")
        self.assertEqual(inst.metadata["source.param.water"], "blocked")
        for swamp, water in (("blocked", "passable"), ("blocked", "blocked")):
            r = run("convert", "movingai", "--map", m, "--swamp", swamp, "--water", water, "-o", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.check_instance(out, read_map(m, swamp == "passable", water == "passable"))
        # Determinism, and --name.
        a, b = self.path("a.mosb"), self.path("b.mosb")
        for path in (a, b):
            self.assertEqual(run("convert", "movingai", "--map", m, "--name", "H", "-o", path).returncode, 0)
        with open(a, "rb") as fa, open(b, "rb") as fb:
            self.assertEqual(fa.read(), fb.read())
        self.assertEqual(mosb_reader.open_instance(a).metadata["benchmark"], "H")

    def test_same_graph_as_guards(self):
        """The one octile graph: `convert guards` with zero exposure has the same arcs and lengths."""
        m = self.write("hand.map", HAND_MADE)
        zeros = self.write("zero.txt", "0 0 0 0 0\n" * 4)
        a, b = self.path("m.mosb"), self.path("g.mosb")
        self.assertEqual(run("convert", "movingai", "--map", m, "-o", a).returncode, 0)
        self.assertEqual(run("convert", "guards", "--map", m, "--exposure", zeros, "-o", b).returncode, 0)
        x, y = mosb_reader.open_instance(a), mosb_reader.open_instance(b)
        for kind in (mosb_reader.FORWARD_OFFSETS, mosb_reader.FORWARD_TARGETS):
            self.assertTrue(np.array_equal(x.array(x.of_kind(kind)[0]), y.array(y.of_kind(kind)[0])))
        self.assertTrue(np.array_equal(dict(x.costs())["length"], dict(y.costs())["length"]))

    def test_no_passable_cell_is_an_error(self):
        m = self.write("walls.map", "type octile\nheight 2\nwidth 3\nmap\n@T@\nOW@\n")
        zeros = self.write("zero.txt", "0 0 0\n0 0 0\n")
        for command, extra in (("movingai", []), ("guards", ["--exposure", zeros])):
            with self.subTest(command=command):
                out = self.path("x.mosb")
                r = run("convert", command, "--map", m, *extra, "-o", out)
                self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
                self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
                self.assertIn(m + ": the map has no passable cell", r.stderr)
                self.assertFalse(os.path.exists(out))
        # Water made passable: the same map has one vertex.
        out = self.path("w.mosb")
        r = run("convert", "movingai", "--map", m, "--water", "passable", "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(mosb_reader.open_instance(out).n, 1)

    def test_default_view_length_on_the_scenario(self):
        # The suite's default view (games.md §6): `length` on query set `scen`, so a solution file
        # can be imported for the converted file with no edit of it.
        m = self.write("hand.map", HAND_MADE)
        s = self.write("s.scen", "version 1\n0\thand.map\t5\t4\t0\t0\t1\t0\t1\n")
        out = self.path("s.mosb")
        self.ok("convert", "movingai", "--map", m, "--scen", s, "-o", out)
        md = mosb_reader.open_instance(out).metadata
        self.assertEqual(md["view.length.objectives"], "length")
        self.assertEqual(md["view.length.queries"], "scen")
        table = self.write("t.csv", "query,length\n0,10\n")
        sol = self.path("s.sol")
        self.ok("solutions", "import", "--instance", out, "--view", "length", "--table", table,
                "-o", sol)
        self.ok("solutions", "import", "--instance", out, "--objectives", "length", "--queries",
                "scen", "--table", table, "-o", self.path("o.sol"))
        self.assertEqual(open(sol, "rb").read(), open(self.path("o.sol"), "rb").read())
        # Without --scen the view waits for its set: `queries import --scen --set scen` adds it.
        bare = self.path("bare.mosb")
        self.ok("convert", "movingai", "--map", m, "--view", "twice=length@other", "-o", bare)
        md = mosb_reader.open_instance(bare).metadata
        self.assertNotIn("view.length.queries", md)
        self.assertEqual(md["source.param.view.length"], "length@scen")
        self.assertEqual(md["view.twice.objectives"], "length")
        r = self.ok("queries", "import", bare, s, "--scen", "--set", "scen", "-o", out)
        self.assertEqual(r.stderr, "query set scen is now the query set of view length\n")
        self.assertEqual(mosb_reader.open_instance(out).metadata["view.length.queries"], "scen")
        self.assertNotIn("view.twice.queries", mosb_reader.open_instance(out).metadata)

    def test_scenario_import_refuses_a_map_size_no_map_can_have(self):
        # Hostile metadata: the scenario check held width x height flags, so 4294967295 squared
        # was an allocation that could only fail (internal error). Now one line naming the file.
        m = self.write("hand.map", HAND_MADE)
        s = self.write("s.scen", "version 1\n0\thand.map\t5\t4\t0\t0\t1\t0\t1\n")
        bare = self.path("bare.mosb")
        self.ok("convert", "movingai", "--map", m, "-o", bare)
        data = bytearray(open(bare, "rb").read())
        mosbtest.set_metadata(data, **{"map.width": "4294967295", "map.height": "4294967295"})
        hostile = self.path("hostile.mosb")
        with open(hostile, "wb") as f:
            f.write(data)
        out = self.path("out.mosb")
        r = run("queries", "import", hostile, s, "--scen", "--set", "scen", "-o", out)
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("hostile.mosb: metadata map.width x map.height is 4294967295 x 4294967295, "
                      "more cells than a map may have", r.stderr)
        self.assertFalse(os.path.exists(out))

    def test_scenario_errors_are_located(self):
        m = self.write("hand.map", HAND_MADE)
        s = self.write("s.scen", "version 1\n0\thand.map\t5\t4\t0\t0\t2\t0\t1\n")
        r = run("convert", "movingai", "--map", m, "--scen", s, "-o", self.path("x.mosb"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("s.scen:2:20: the goal cell (2, 0) is blocked", r.stderr)
        self.assertFalse(os.path.exists(self.path("x.mosb")))

    def test_real_maps(self):
        for name, rows, _, m, s in real_maps(self):
            with self.subTest(map=name):
                out = self.path(name + ".mosb")
                r = run("convert", "movingai", "--map", m, "--scen", s, "-o", out)
                self.assertEqual(r.returncode, 0, r.stderr)
                inst = self.check_instance(out, read_map(m))
                endpoints = scenario_endpoints(s)
                self.assertEqual(len(endpoints), rows)
                self.assertTrue(np.array_equal(query_cells(inst), endpoints))
                self.assertEqual(inst.metadata["benchmark"], name[:-4])
                self.assertEqual(inst.metadata["source.input.0.name"], name)
                self.assertEqual(inst.metadata["source.input.1.name"], name + ".scen")


if __name__ == "__main__":
    mosbtest.main()
