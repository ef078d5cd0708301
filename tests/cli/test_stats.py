#!/usr/bin/python3
"""End-to-end tests of `mosb stats` (spec/STATS.md).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_stats.py

Every statistic is checked against an independent computation here: numpy over the columns read by
the reference reader (spec/reference/mosb_reader.py), or over the raw NetMaker text file.
"""

import functools
import json
import os
import tempfile
import unittest

import numpy as np

import mosbtest
from mosbtest import DATA, CliTest, mosb_reader, setUpModule  # noqa: F401

NETMAKER = os.path.join(DATA, "netmaker", "netMaker_3o_10000n_1amin_10amax_20i_1s_scorr_79134.gr")

# Every run here must succeed unless it says check=False.
run = functools.partial(mosbtest.run, check=True)


def stats_json(*args):
    return json.loads(run("stats", *args, "--json").stdout)


def independent_stats(n, tails, heads, columns):
    """The statistics of spec/STATS.md, computed without mosb (arcs in any order)."""
    tails = np.asarray(tails, dtype=np.int64)
    heads = np.asarray(heads, dtype=np.int64)
    out_degree = np.bincount(tails, minlength=n)
    in_degree = np.bincount(heads, minlength=n)
    pairs = tails * n + heads
    rho = {}
    for i in range(len(columns)):
        for j in range(i + 1, len(columns)):
            x = np.asarray(columns[i], dtype=np.float64)
            y = np.asarray(columns[j], dtype=np.float64)
            rho[(i, j)] = None if x.min() == x.max() or y.min() == y.max() else float(np.corrcoef(x, y)[0, 1])
    return {
        "out_degree": (int(out_degree.min()), len(tails) / n, int(out_degree.max())),
        "in_degree": (int(in_degree.min()), len(tails) / n, int(in_degree.max())),
        "self_loops": int(np.count_nonzero(tails == heads)),
        "parallel_arcs": len(pairs) - len(np.unique(pairs)),
        "scc": kosaraju(n, tails, heads),
        "costs": [(int(c.min()), float(np.mean(c, dtype=np.float64)), int(c.max())) for c in columns],
        "rho": rho,
    }


def kosaraju(n, tails, heads):
    """(count, largest) of the strongly connected components, by two iterative DFS passes."""
    def adjacency(frm, to):
        order = np.argsort(frm, kind="stable")
        offsets = np.concatenate(([0], np.cumsum(np.bincount(frm, minlength=n))))
        return offsets.tolist(), to[order].tolist()

    off, tgt = adjacency(tails, heads)
    seen = [False] * n
    finish = []
    for root in range(n):
        if seen[root]:
            continue
        seen[root] = True
        stack = [(root, off[root])]
        while stack:
            v, pos = stack[-1]
            if pos < off[v + 1]:
                stack[-1] = (v, pos + 1)
                w = tgt[pos]
                if not seen[w]:
                    seen[w] = True
                    stack.append((w, off[w]))
            else:
                stack.pop()
                finish.append(v)
    roff, src = adjacency(heads, tails)
    component = [-1] * n
    sizes = []
    for root in reversed(finish):
        if component[root] >= 0:
            continue
        component[root] = len(sizes)
        size, stack = 0, [root]
        while stack:
            v = stack.pop()
            size += 1
            for w in src[roff[v]:roff[v + 1]]:
                if component[w] < 0:
                    component[w] = len(sizes)
                    stack.append(w)
        sizes.append(size)
    return len(sizes), max(sizes, default=0)


class StatsTest(CliTest):
    maxDiff = None

    @classmethod
    def setUpClass(cls):  # one grid for every test
        cls.tmp = tempfile.TemporaryDirectory()
        cls.grid = os.path.join(cls.tmp.name, "grid.mosb")
        run("generate", "grid", "--width", "7", "--height", "5", "--objectives", "3", "--seed", "3",
            "-o", cls.grid)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def check_against(self, s, expected, names):
        self.assertEqual(s["self_loops"], expected["self_loops"])
        self.assertEqual(s["parallel_arcs"], expected["parallel_arcs"])
        self.assertEqual((s["scc"]["count"], s["scc"]["largest"]), expected["scc"])
        for key in ("out_degree", "in_degree"):
            lo, mean, hi = expected[key]
            self.assertEqual((s[key]["min"], s[key]["max"]), (lo, hi))
            self.assertAlmostEqual(s[key]["mean"], mean, places=12)
        self.assertEqual([o["name"] for o in s["objectives"]], names)
        for o, (lo, mean, hi) in zip(s["objectives"], expected["costs"]):
            self.assertEqual((o["min"], o["max"]), (lo, hi))
            self.assertAlmostEqual(o["mean"], mean, places=9)
        got = {(names.index(c["first"]), names.index(c["second"])): c["rho"] for c in s["correlations"]}
        self.assertEqual(set(got), set(expected["rho"]))
        for pair, rho in expected["rho"].items():
            if rho is None:
                self.assertIsNone(got[pair])
            else:
                self.assertAlmostEqual(got[pair], rho, places=12)

    def grid_expectation(self, names):
        inst = mosb_reader.open_instance(self.grid)
        offsets = inst.array("forward_offsets")
        heads = np.asarray(inst.array("forward_targets"))
        tails = np.repeat(np.arange(inst.n), np.diff(offsets.astype(np.int64)))
        costs = dict(inst.costs())
        return inst, independent_stats(inst.n, tails, heads, [np.asarray(costs[c]) for c in names])

    def test_json_matches_an_independent_computation(self):
        s = stats_json(self.grid)
        inst, expected = self.grid_expectation(["c1", "c2", "c3"])
        self.assertEqual((s["vertices"], s["arcs"]), (inst.n, inst.m))
        self.assertIsNone(s["view"])
        self.assertNotIn("by_kind", s)
        self.check_against(s, expected, ["c1", "c2", "c3"])

    def test_view_selects_and_orders_objectives(self):
        s = stats_json(self.grid, "--view", "Grid_2")
        self.assertEqual(s["view"], "Grid_2")
        _, expected = self.grid_expectation(["c1", "c2"])
        self.check_against(s, expected, ["c1", "c2"])

    def test_objectives_select_and_order_without_a_view(self):
        s = stats_json(self.grid, "--objectives", "c3,c1")
        self.assertIsNone(s["view"])
        _, expected = self.grid_expectation(["c3", "c1"])
        self.check_against(s, expected, ["c3", "c1"])
        self.assertIn("(listed objectives)", run("stats", self.grid, "--objectives", "c2").stdout)
        r = run("stats", self.grid, "--view", "Grid_2", "--objectives", "c1", check=False)
        self.assertEqual(r.returncode, 2, r)
        r = run("stats", self.grid, "--objectives", "c1,", check=False)
        self.assertEqual(r.returncode, 2, r)
        self.assertIn("--objectives: empty or invalid objective name ''", r.stderr)

    def test_text_is_an_aligned_table(self):
        text = run("stats", self.grid).stdout
        s = stats_json(self.grid)
        lines = text.splitlines()
        self.assertIn("vertices       %d" % s["vertices"], lines)
        self.assertIn("arcs           %d" % s["arcs"], lines)
        self.assertIn("SCCs           %d (largest %d vertices)" % (s["scc"]["count"], s["scc"]["largest"]), lines)
        rows = [line.split() for line in lines if " ~ " in line]
        self.assertEqual([(r[0], r[2]) for r in rows], [("c1", "c2"), ("c1", "c3"), ("c2", "c3")])
        for row, c in zip(rows, s["correlations"]):
            self.assertAlmostEqual(float(row[3]), c["rho"], places=6)
        table = [line for line in lines if line.startswith("  c")]
        self.assertEqual(len({line.index(" ~ ") for line in table if " ~ " in line}), 1)  # aligned
        self.assertEqual(len({len(line) for line in table if " ~ " not in line}), 1)

    def test_errors_are_one_line_naming_the_file(self):
        cases = [
            (["stats", self.grid, "--by-kind"], "no arc data section 'kind'"),
            (["stats", self.grid, "--view", "Grid_9"],
             "no view 'Grid_9' (views: Grid_2, Grid_3; did you mean 'Grid_2'?)"),
            (["stats", self.grid, "--objectives", "c9"], "no objective named 'c9'"),
            (["stats", self.grid, "--queries", "none"], "no query set 'none' (query sets: "),
            (["stats", self.grid, "--queries", "defualt"], "did you mean 'default'?)"),
            (["stats", self.path("missing.mosb")], "missing.mosb"),
        ]
        for args, message in cases:
            result = run(*args, check=False)
            self.assertEqual(result.returncode, 1, args)
            self.assertEqual(result.stdout, "")
            self.assertEqual(len(result.stderr.splitlines()), 1, result.stderr)
            self.assertIn(message, result.stderr)
            self.assertIn("mosb", result.stderr)

    def test_independent_uniform_grid_is_uncorrelated(self):
        # m ≈ 1.43M arcs; under independence sd(ρ) ≈ 1/√m ≈ 0.00084, so 0.01 is ≈ 12 sd: a failure
        # means real dependence (a generator or statistics bug), not bad luck.
        path = self.path("grid600.mosb")
        run("generate", "grid", "--width", "600", "--height", "600", "--objectives", "3", "-o", path)
        s = stats_json(path)
        self.assertEqual(len(s["correlations"]), 3)
        for c in s["correlations"]:
            self.assertLess(abs(c["rho"]), 0.01, c)
        # The grid is one component; the generator's two extra vertices are components of their own.
        self.assertEqual((s["scc"]["count"], s["scc"]["largest"]), (3, 600 * 600))

    @unittest.skipUnless(os.path.exists(NETMAKER), mosbtest.MISSING + "NetMaker data absent: " + NETMAKER)
    def test_netmaker_instance(self):
        path = self.path("netmaker.mosb")
        run("convert", "dimacs", "--gr", NETMAKER, "--id-base", "0", "-o", path)
        s = stats_json(path)
        rows = []
        with open(NETMAKER) as f:
            for line in f:
                if line.startswith("a "):
                    rows.append([int(x) for x in line.split()[1:]])
        arcs = np.array(rows, dtype=np.int64)
        expected = independent_stats(10000, arcs[:, 0], arcs[:, 1], [arcs[:, 2], arcs[:, 3], arcs[:, 4]])
        self.assertEqual((s["vertices"], s["arcs"], len(s["objectives"])), (10000, 59750, 3))
        self.check_against(s, expected, ["c1", "c2", "c3"])
        # Recorded after the check above agreed (spec/STATS.md, "Recorded values").
        recorded = {(c["first"], c["second"]): round(c["rho"], 4) for c in s["correlations"]}
        self.assertEqual(recorded, RECORDED_NETMAKER_RHO)
        self.assertEqual((s["out_degree"]["min"], s["out_degree"]["max"]), RECORDED_NETMAKER_OUT_DEGREE)
        self.assertEqual((s["in_degree"]["min"], s["in_degree"]["max"]), RECORDED_NETMAKER_IN_DEGREE)
        self.assertEqual((s["scc"]["count"], s["scc"]["largest"]), RECORDED_NETMAKER_SCC)
        self.assertEqual((s["self_loops"], s["parallel_arcs"]), RECORDED_NETMAKER_LOOPS_PARALLEL)


RECORDED_NETMAKER_RHO = {("c1", "c2"): 0.5726, ("c1", "c3"): 0.4396, ("c2", "c3"): 0.5155}
RECORDED_NETMAKER_OUT_DEGREE = (2, 10)
RECORDED_NETMAKER_IN_DEGREE = (1, 15)
RECORDED_NETMAKER_SCC = (1, 10000)
RECORDED_NETMAKER_LOOPS_PARALLEL = (0, 2)


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
