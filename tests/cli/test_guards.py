#!/usr/bin/python3
"""End-to-end tests of `mosb convert guards` (spec/families/games.md).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_guards.py

Counts and costs are recomputed here with numpy array shifts, independently of the converter's
per-cell loops. The real maps come from shared/data/movingai (skipped visibly when absent).
"""

import os

import numpy as np

import mosbtest
from mosbtest import CliTest, mosb_reader, run, setUpModule  # noqa: F401

DATA = os.path.join(mosbtest.DATA, "movingai")

SMALL_MAP = "type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n"


def read_map(path, swamp=True, water=False):
    with open(path, newline="") as f:
        lines = f.read().replace("\r\n", "\n").split("\n")
    height, width = int(lines[1].split()[1]), int(lines[2].split()[1])
    rows = lines[4:4 + height]
    chars = np.array([list(r) for r in rows])
    passable = np.isin(chars, [".", "G"] + (["S"] if swamp else []) + (["W"] if water else []))
    assert passable.shape == (height, width)
    return passable


def expected_arcs(passable, exposure):
    """(tail cell, head cell, length, exposure) for every legal move, from whole-array shifts."""
    h, w = passable.shape
    ys, xs = np.mgrid[0:h, 0:w]
    out = []
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dx == 0 and dy == 0:
                continue
            ok = passable.copy()
            hx, hy = xs + dx, ys + dy
            inside = (hx >= 0) & (hx < w) & (hy >= 0) & (hy < h)
            ok &= inside
            hxc, hyc = np.clip(hx, 0, w - 1), np.clip(hy, 0, h - 1)
            ok &= passable[hyc, hxc]
            cost = exposure[hyc, hxc]
            if dx and dy:
                ok &= passable[ys, hxc] & passable[hyc, xs]
                cost = np.maximum(cost, np.maximum(exposure[ys, hxc], exposure[hyc, xs]))
            sel = ok.nonzero()
            out.append((xs[sel], ys[sel], hxc[sel], hyc[sel], np.full(len(sel[0]), 14 if dx and dy else 10),
                        cost[sel]))
    return [np.concatenate(c) for c in zip(*out)]


def sorted_rows(a):
    return a[np.lexsort(a.T[::-1])]


def arc_rows(inst, cells, cost_names):
    """The instance's arcs as sorted rows (tail x, tail y, head x, head y, costs `cost_names`...),
    read with the reference reader; `cells` holds the (x, y) of every vertex."""
    offsets = np.asarray(inst.array(inst.of_kind(mosb_reader.FORWARD_OFFSETS)[0]), dtype=np.int64)
    targets = np.asarray(inst.array(inst.of_kind(mosb_reader.FORWARD_TARGETS)[0]), dtype=np.int64)
    tails = np.repeat(np.arange(inst.n), np.diff(offsets))
    costs = dict(inst.costs())
    return sorted_rows(np.stack([cells[tails, 0], cells[tails, 1], cells[targets, 0],
                                 cells[targets, 1],
                                 *(np.asarray(costs[c], dtype=np.int64) for c in cost_names)],
                                axis=1))


# The real maps of ../shared/data/movingai: name, rows of its scenario file, lines of that file.
# arena2.map.scen has 932 lines: `version 1`, 929 rows and 2 trailing blank lines (so 929 queries,
# not the 931 of its line count minus the header); random512-20-1: 1 + 1770 lines.
REAL_MAPS = (("arena2.map", 929, 932), ("random512-20-1.map", 1770, 1771))


def real_maps(test):
    """(name, scenario rows, scenario lines, map path, scenario path) of every real map; skips
    `test` when they are absent."""
    test.skip_unless_present(*(os.path.join(DATA, name) for name, _, _ in REAL_MAPS))
    return [(name, rows, lines, os.path.join(DATA, name), os.path.join(DATA, name + ".scen"))
            for name, rows, lines in REAL_MAPS]


def scenario_endpoints(scen):
    """(start x, start y, goal x, goal y) of every row of Moving AI scenario file `scen`."""
    with open(scen) as f:
        lines = [line for line in f.read().split("\n")[1:] if line.strip()]
    return np.array([[int(v) for v in line.split("\t")[4:8]] for line in lines])


def query_cells(inst, name="scen"):
    """(start x, start y, goal x, goal y) of every query of set `name`, from the cell section."""
    q = np.asarray(inst.queries()[name], dtype=np.int64)
    cells = np.asarray(inst.array(inst.section("cell", mosb_reader.VERTEX_DATA)), dtype=np.int64)
    return np.concatenate([cells[q[:, 0]], cells[q[:, 1]]], axis=1)


class GuardsCli(CliTest):
    def check_instance(self, out, passable, exposure_file):
        inst = mosb_reader.open_instance(out)
        exposure = np.loadtxt(exposure_file, dtype=np.int64, ndmin=2)
        self.assertEqual(exposure.shape, passable.shape)
        tx, ty, hx, hy, length, cost = expected_arcs(passable, exposure)
        self.assertEqual(inst.n, int(passable.sum()))
        self.assertEqual(inst.m, len(tx))
        cells = np.asarray(inst.array(inst.section("cell", mosb_reader.VERTEX_DATA)), dtype=np.int64)
        w = passable.shape[1]
        # Row-major numbering: the cells in vertex order are the passable cells in row-major order.
        self.assertTrue(np.array_equal(cells[:, 1] * w + cells[:, 0], np.flatnonzero(passable.ravel())))
        want = np.stack([tx, ty, hx, hy, length, cost], axis=1)
        self.assertTrue(np.array_equal(arc_rows(inst, cells, ["length", "exposure"]),
                                       sorted_rows(want)))
        self.assertEqual(inst.metadata["view.Games-GUARDS_2.objectives"], "length,exposure")
        self.assertEqual(inst.metadata["map.width"], str(passable.shape[1]))
        self.assertEqual(inst.metadata["map.height"], str(passable.shape[0]))
        return inst

    def test_small_map_guards_and_exposure_round_trip(self):
        m = self.write("small.map", SMALL_MAP)
        g = self.write("g.txt", "# guard A sees row 0 and column 0 only\n0 0\n3 2 1\n")
        out, exp = self.path("a.mosb"), self.path("e.txt")
        r = run("convert", "guards", "--map", m, "--guards", g, "--write-exposure", exp, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(exp) as f:
            self.assertEqual(f.read(), "1 1 1 1\n1 0 0 1\n1 0 1 1\n")
        self.check_instance(out, read_map(m), exp)
        # The written grid as --exposure input gives the same cost columns.
        out2 = self.path("b.mosb")
        r = run("convert", "guards", "--map", m, "--exposure", exp, "-o", out2)
        self.assertEqual(r.returncode, 0, r.stderr)
        a, b = mosb_reader.open_instance(out), mosb_reader.open_instance(out2)
        for (na, ca), (nb, cb) in zip(a.costs(), b.costs()):
            self.assertEqual(na, nb)
            self.assertTrue(np.array_equal(ca, cb))
        # Determinism: byte-identical output.
        out3 = self.path("c.mosb")
        run("convert", "guards", "--map", m, "--guards", g, "-o", out3)
        with open(out, "rb") as f1, open(out3, "rb") as f3:
            self.assertEqual(f1.read(), f3.read())
        # Where the guards stand, for plots (games.md §5); an exposure grid does not say.
        self.assertEqual(a.metadata["map.guards"], "0,0;3,2")
        self.assertNotIn("map.guards", b.metadata)
        # The paper's view name; its query set is the first one added (the paper's random pairs).
        self.assertNotIn("view.Games-GUARDS_2.queries", a.metadata)
        self.assertNotIn("source.param.view.Games-GUARDS_2", a.metadata)
        q = self.path("q.mosb")
        r = run("queries", "generate", out, "--set", "random", "--count", "3", "-o", q)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr, "query set random is now the query set of view Games-GUARDS_2\n")
        self.assertEqual(mosb_reader.open_instance(q).metadata["view.Games-GUARDS_2.queries"],
                         "random")

    def test_swamp_and_water_options(self):
        m = self.write("t.map", "type octile\nheight 1\nwidth 4\nmap\n.SW.")
        e = self.write("e.txt", "0 0 0 0\n")
        for swamp, water, n in (("passable", "blocked", 3), ("blocked", "passable", 3),
                                ("blocked", "blocked", 2), ("passable", "passable", 4)):
            out = self.path("t.mosb")
            r = run("convert", "guards", "--map", m, "--exposure", e, "--swamp", swamp, "--water", water, "-o", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            inst = self.check_instance(out, read_map(m, swamp == "passable", water == "passable"), e)
            self.assertEqual(inst.n, n)

    def test_errors_are_one_line_with_location(self):
        m = self.write("small.map", SMALL_MAP)
        cases = [
            (["--map", self.write("bad.map", SMALL_MAP.replace(".@..", ".@.")), "--exposure", m],
             "bad.map:6:4: row 2 has 3 cells"),
            (["--map", self.write("bad2.map", SMALL_MAP.replace(".@..", ".@.?")), "--exposure", m],
             "bad2.map:6:4: unknown terrain character"),
            (["--map", m, "--guards", self.write("g.txt", "0 0\n1 1 5\n")], "g.txt:2:1: guard on the blocked cell"),
            (["--map", m, "--exposure", self.write("e.txt", "1 1 1 1\n1 1 1\n1 1 1 1\n")], "e.txt:2:6:"),
            (["--map", m, "--guards", self.write("g2.txt", "0 0\n"), "--scen",
              self.write("s.scen", "version 1\n0\tsmall.map\t4\t3\t1\t1\t0\t0\t1\n")],
             "s.scen:2:17: the start cell (1, 1) is blocked"),
            (["--map", m, "--guards", self.path("g2.txt"), "--scen",
              self.write("s2.scen", "version 1\n0\tsmall.map\t4\t4\t0\t0\t0\t2\t2\n")],
             "s2.scen:2:15: the row gives a 4 x 4 map"),
        ]
        for args, expected in cases:
            r = run("convert", "guards", *args, "-o", self.path("x.mosb"))
            self.assertEqual(r.returncode, 1, (args, r.stderr))
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertIn(expected, r.stderr)
            self.assertFalse(os.path.exists(self.path("x.mosb")))
        r = run("convert", "guards", "--map", m, "-o", self.path("x.mosb"))
        self.assertNotEqual(r.returncode, 0)

    def test_real_maps(self):
        for name, rows, line_count, m, s in real_maps(self):
            with self.subTest(map=name):
                passable = read_map(m)
                # A few fixed guards: the first passable cell of rows h/4, h/2 (unlimited), 3h/4.
                h = passable.shape[0]
                lines = []
                for y, radius in ((h // 4, " 25"), (h // 2, ""), (3 * h // 4, " 25.5")):
                    x = int(np.flatnonzero(passable[y])[0])
                    lines.append("%d %d%s" % (x, y, radius))
                g = self.write("guards.txt", "\n".join(lines) + "\n")
                out, exp = self.path(name + ".mosb"), self.path(name + ".exposure")
                r = run("convert", "guards", "--map", m, "--guards", g, "--scen", s, "--write-exposure", exp,
                        "-o", out)
                self.assertEqual(r.returncode, 0, r.stderr)
                inst = self.check_instance(out, passable, exp)
                with open(s) as f:
                    self.assertEqual(f.read().count("\n"), line_count)
                endpoints = scenario_endpoints(s)
                self.assertEqual(len(endpoints), rows)
                self.assertEqual(len(inst.queries()["scen"]), rows)
                self.assertTrue(np.array_equal(query_cells(inst), endpoints))
                self.assertEqual(inst.metadata["benchmark"], name[:-4])
                self.assertEqual(inst.metadata["family"], "games")
                r = run("verify", out, "--level", "full")
                self.assertEqual(r.returncode, 0, r.stdout + r.stderr)


if __name__ == "__main__":
    mosbtest.main()
