#!/usr/bin/python3
"""The example solvers (examples/): exact Pareto fronts on small random graphs, agreement of
boa_star and namoa on the real NetMaker and Moving AI fixtures, the command line and its errors.

    MOSB=build/release/tools/mosb EXAMPLES=build/release/examples /usr/bin/python3 tests/cli/test_examples.py

The exact front of a small graph is computed here by enumerating every simple path, independently
of the solvers. The real-data parts skip with a message when shared/data is absent.
"""

import json
import os
import random

import mosbtest
from mosbtest import DATA, CliTest, mosb_reader, run, setUpModule  # noqa: F401

EXAMPLES = os.path.abspath(os.environ.get("EXAMPLES", "examples"))


def run_solver(name, *args):
    return run(*args, program=os.path.join(EXAMPLES, name), timeout=600)


def random_gr(rng, n, d):
    """A random multi-column .gr (1-based ids): a cycle through all vertices, random arcs,
    parallel arcs with other costs and a self-loop; costs 0..4 so equal cost vectors are common."""
    arcs = [(v, (v + 1) % n) for v in range(n)]
    arcs += [(rng.randrange(n), rng.randrange(n)) for _ in range(rng.randrange(n, 2 * n + 1))]
    arcs += [arcs[rng.randrange(len(arcs))] for _ in range(2)]
    arcs.append((0, 0))
    rows = [(u, v, tuple(rng.randrange(5) for _ in range(d))) for u, v in arcs]
    text = "p sp %d %d\n" % (n, len(rows))
    text += "".join("a %d %d %s\n" % (u + 1, v + 1, " ".join(map(str, c))) for u, v, c in rows)
    return rows, text


def exact_front(rows, n, start, goal, objectives):
    """Cost vectors of every simple path start -> goal, reduced to the deduplicated Pareto set."""
    out = [[] for _ in range(n)]
    for u, v, c in rows:
        out[u].append((v, tuple(c[k] for k in objectives)))
    costs = set()
    zero = tuple(0 for _ in objectives)

    def walk(v, seen, g):
        if v == goal:
            costs.add(g)
            return
        for w, c in out[v]:
            if w not in seen:
                seen.add(w)
                walk(w, seen, tuple(a + b for a, b in zip(g, c)))
                seen.remove(w)

    walk(start, {start}, zero)
    return sorted(c for c in costs
                  if not any(o != c and all(a <= b for a, b in zip(o, c)) for o in costs))


def read_fronts(directory, count):
    fronts = []
    for i in range(count):
        with open(os.path.join(directory, "%d.txt" % i)) as f:
            fronts.append([tuple(int(x) for x in line.split(" ")) for line in f.read().splitlines()])
    return fronts


class Base(CliTest):
    def solve(self, name, instance, *args, fronts=None):
        """Runs a solver; returns (output rows, fronts) and checks the output line format."""
        fronts_dir = self.path("fronts-%s-%d" % (name, len(os.listdir(self.dir))))
        r = run_solver(name, instance, *args, "--fronts", fronts_dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = [line.split() for line in r.stdout.splitlines()]
        for row in rows:
            self.assertEqual(len(row), 5, row)
            int(row[0]), int(row[1]), int(row[2]), float(row[3]), int(row[4])
        got = read_fronts(fronts_dir, len(rows))
        for row, front in zip(rows, got):
            self.assertEqual(int(row[2]), len(front))
            self.assertEqual(front, sorted(front))
        self.assertEqual(len(os.listdir(fronts_dir)), len(rows))
        return rows, got


class RandomGraphs(Base):
    def check(self, seed, d):
        rng = random.Random(seed)
        n = rng.randrange(3, 8)
        rows, text = random_gr(rng, n, d)
        gr = self.write("g%d.gr" % seed, text)
        inst = self.path("g%d.mosb" % seed)
        views = ["--view", "P13=c1,c3"] if d == 3 else []
        self.ok("convert", "dimacs", "--gr", gr, *views, "-o", inst)
        pairs = [(s, t) for s in range(n) for t in range(n)]
        query_args = [x for s, t in pairs for x in ("--query", str(s), str(t))]
        expected = [exact_front(rows, n, s, t, range(d)) for s, t in pairs]
        # With 3 objectives the file's only view (P13) is the default; all three by name here.
        every = ["--objectives", "c1,c2,c3"] if d == 3 else []
        out, fronts = self.solve("namoa", inst, *every, *query_args)
        self.assertEqual([(int(r[0]), int(r[1])) for r in out], pairs)
        self.assertEqual(fronts, expected, "namoa, seed %d" % seed)
        if d == 2:
            self.assertEqual(self.solve("boa_star", inst, *query_args)[1], expected, "boa_star, seed %d" % seed)
        else:
            # Two of three objectives: through the file's view, and through --objectives.
            expected = [exact_front(rows, n, s, t, (0, 2)) for s, t in pairs]
            for args in ([], ["--view", "P13"], ["--objectives", "c1,c3"]):
                for name in ("boa_star", "namoa"):
                    self.assertEqual(self.solve(name, inst, *args, *query_args)[1], expected,
                                     "%s %s, seed %d" % (name, args, seed))
        # The text-loader build of namoa (the benchmark's baseline) finds the same fronts.
        text_args = [x for s, t in pairs for x in ("--query", str(s + 1), str(t + 1))]
        self.assertEqual(self.solve("namoa_text", gr, *text_args)[1],
                         [exact_front(rows, n, s, t, range(d)) for s, t in pairs])

    def test_two_objectives(self):
        for seed in range(40):
            with self.subTest(seed=seed):
                self.check(seed, 2)

    def test_three_objectives(self):
        for seed in range(100, 130):
            with self.subTest(seed=seed):
                self.check(seed, 3)

    def test_default_query_set_and_determinism(self):
        rng = random.Random(7)
        rows, text = random_gr(rng, 7, 2)
        inst = self.path("q.mosb")
        self.ok("convert", "dimacs", "--gr", self.write("q.gr", text), "-o", inst)
        self.ok("queries", "generate", inst, "--in-place", "--set", "some", "--count", "6", "--seed", "3")
        stored = [tuple(int(x) for x in q) for q in mosb_reader.open_instance(inst).queries()["some"]]
        self.assertEqual(len(stored), 6)
        for name in ("boa_star", "namoa"):
            out, fronts = self.solve(name, inst)
            self.assertEqual([(int(r[0]), int(r[1])) for r in out], stored)
            self.assertEqual(fronts, [exact_front(rows, 7, s, t, (0, 1)) for s, t in stored])
            # Same input, same front files, byte for byte.
            a, b = self.path("a-" + name), self.path("b-" + name)
            for d in (a, b):
                self.assertEqual(run_solver(name, inst, "--fronts", d).returncode, 0)
            for i in range(6):
                with open(os.path.join(a, "%d.txt" % i), "rb") as fa, open(os.path.join(b, "%d.txt" % i), "rb") as fb:
                    self.assertEqual(fa.read(), fb.read())


class ImportedAsSolutionFiles(Base):
    """An example solver's fronts and its per-query lines become a solution file (solutions import
    --dir --example-log) that verifies against the instance and evaluates against itself."""

    def grid_with_queries(self, width, height, seed, count, query_seed):
        """A generated grid with a query set `q` of `count` queries."""
        inst = self.path("g.mosb")
        self.ok("generate", "grid", "--width", str(width), "--height", str(height), "--seed",
                  str(seed), "-o", inst)
        self.ok("queries", "generate", inst, "--in-place", "--set", "q", "--count", str(count),
                  "--seed", str(query_seed))
        return inst

    def run_namoa(self, inst):
        fronts = self.path("fronts")
        r = run_solver("namoa", inst, "--view", "Grid_3", "--queries", "q", "--fronts", fronts)
        self.assertEqual(r.returncode, 0, r.stderr)
        return fronts, self.write("namoa.log", r.stdout), r.stdout.splitlines()

    def test_fronts_and_statistics_are_imported(self):
        inst = self.grid_with_queries(9, 8, 5, 4, 2)
        fronts, log, lines = self.run_namoa(inst)
        out = self.path("namoa.sol.mosb")
        self.ok("solutions", "import", "--instance", inst, "--view", "Grid_3", "--queries", "q",
                  "--dir", fronts, "--example-log", log, "--solver", "namoa", "-o", out)
        self.ok("solutions", "verify", "--instance", inst, out)
        summary = json.loads(self.ok("solutions", "inspect", "--json", out).stdout)
        rows = [line.split() for line in lines]
        self.assertEqual(summary["statuses"]["solved"], 4)
        self.assertEqual(summary["vectors"], sum(int(r[2]) for r in rows))
        stats = summary["statistics"]
        self.assertEqual(stats["expanded"]["queries"], 4)
        self.assertEqual(stats["expanded"]["total"], sum(int(r[4]) for r in rows))
        self.assertAlmostEqual(stats["runtime_seconds"]["max"], max(float(r[3]) for r in rows))
        self.ok("eval", "--reference", out, "--solutions", out, "--eps", "0")
        # Without the log: the same fronts, no statistics.
        plain = self.path("plain.sol.mosb")
        self.ok("solutions", "import", "--instance", inst, "--view", "Grid_3", "--queries", "q",
                  "--dir", fronts, "-o", plain)
        self.assertEqual(json.loads(self.ok("solutions", "inspect", "--json", plain).stdout)
                         ["statistics"], {})

    def test_path_sums_beyond_the_arc_type_import(self):
        # Issue 19: on a 40x40 grid the fronts' sums pass 255, the u8 arc type of c2; the file
        # stores path sums (u64), so the import no longer fails.
        inst = self.path("g40.mosb")
        self.ok("generate", "grid", "--width", "40", "--height", "40", "--seed", "1", "-o", inst)
        fronts = self.path("fronts40")
        r = run_solver("namoa", inst, "--view", "Grid_2", "--fronts", fronts)
        self.assertEqual(r.returncode, 0, r.stderr)
        log = self.write("namoa40.log", r.stdout)
        out = self.path("g40.sol")
        self.ok("solutions", "import", "--instance", inst, "--view", "Grid_2", "--dir", fronts,
                "--example-log", log, "-o", out)
        self.ok("solutions", "verify", "--instance", inst, out)
        summary = json.loads(self.ok("solutions", "inspect", "--json", out).stdout)
        self.assertEqual([o["type"] for o in summary["objectives"]], ["u64", "u64"])

    def test_a_log_that_disagrees_with_the_fronts_is_refused_at_its_line(self):
        inst = self.grid_with_queries(7, 6, 1, 3, 4)
        fronts, log, lines = self.run_namoa(inst)
        rows = [line.split() for line in lines]

        def refused(text, fragment):
            bad = self.write("bad.log", text)
            out = self.path("bad.sol.mosb")
            r = self.mosb("solutions", "import", "--instance", inst, "--view", "Grid_3",
                          "--queries", "q", "--dir", fronts, "--example-log", bad, "-o", out)
            self.assert_one_line_error(r, fragment)
            self.assertFalse(os.path.exists(out))

        def joined(changed):
            return "".join(" ".join(r) + "\n" for r in changed)

        swapped = [list(r) for r in rows]
        swapped[1][0], swapped[1][1] = rows[1][1], rows[1][0]
        if rows[1][0] != rows[1][1]:
            refused(joined(swapped), "bad.log:2:1: query 1 goes from")
        wrong_size = [list(r) for r in rows]
        wrong_size[2][2] = str(int(rows[2][2]) + 1)
        col = len(rows[2][0]) + len(rows[2][1]) + 3
        refused(joined(wrong_size), "bad.log:3:%d: front size" % col)
        refused(joined(rows[:2]), "no line for query 2")
        refused(joined(rows) + joined(rows[:1]), "bad.log:4:1: a line for query 3")
        refused(joined(rows).replace(rows[0][3], "-1", 1), "bad.log:1:")
        r = self.mosb("solutions", "import", "--instance", inst, "--view", "Grid_3", "--queries",
                      "q", "--table", log, "--example-log", log, "-o", self.path("x.sol.mosb"))
        self.assertEqual(r.returncode, 2, r.stderr)  # --example-log goes with --dir


class Errors(Base):
    def test_bad_input_and_usage(self):
        rows, text = random_gr(random.Random(1), 5, 3)
        inst = self.path("e.mosb")
        self.ok("convert", "dimacs", "--gr", self.write("e.gr", text), "-o", inst)
        garbage = self.write("garbage.mosb", "not a mosb file at all\n" * 10)
        for name in ("boa_star", "namoa"):
            for args, code, needle in (
                    ([self.path("missing.mosb"), "--query", "0", "1"], 1, "missing.mosb"),
                    ([garbage, "--query", "0", "1"], 1, "garbage.mosb"),
                    ([inst, "--query", "0", "9"], 1, "e.mosb"),
                    ([inst, "--view", "nope", "--query", "0", "1"], 1, "e.mosb"),
                    ([inst, "--objectives", "c1,zz", "--query", "0", "1"], 1, "e.mosb"),
                    ([inst], 1, "e.mosb"),  # no view and no query set
                    ([], 2, "no instance"),
                    ([inst, "--bogus"], 2, "--bogus"),
                    ([inst, "--query", "0"], 2, "--query"),
                    ([inst, "--query", "0", "x"], 2, "'x'"),
                    ([inst, "--queries", "a", "--query", "0", "1"], 2, "exclude")):
                with self.subTest(solver=name, args=args):
                    r = run_solver(name, *args)
                    self.assertEqual(r.returncode, code, r.stderr)
                    self.assertIn(needle, r.stderr.splitlines()[0])
                    self.assertEqual(r.stdout, "")
        # boa_star needs exactly two objectives; this file has three.
        r = run_solver("boa_star", inst, "--query", "0", "1")
        self.assertEqual(r.returncode, 2)
        self.assertIn("--objectives", r.stderr)


class RealData(Base):
    def agree(self, inst, args):
        boa, boa_fronts = self.solve("boa_star", inst, *args)
        namoa, namoa_fronts = self.solve("namoa", inst, *args)
        self.assertEqual([r[:3] for r in boa], [r[:3] for r in namoa])
        self.assertEqual(boa_fronts, namoa_fronts)
        return boa

    def test_netmaker(self):
        gr = os.path.join(DATA, "netmaker", "netMaker_3o_10000n_1amin_10amax_20i_1s_scorr_79134.gr")
        self.skip_unless_present(gr)
        inst = self.path("nm.mosb")
        self.ok("convert", "netmaker", gr, "-o", inst)
        self.ok("queries", "import", inst, os.path.join(DATA, "netmaker", "netMaker_4d.inst"), "--in-place",
                  "--set", "nm", "--match", "_79134.gr")
        # Every published query, on the first two objectives of the file's only view (NetMaker-10k_3).
        rows = self.agree(inst, ["--objectives", "c1,c2", "--queries", "nm"])
        self.assertEqual(len(rows), 40)
        self.assertEqual(rows[0][:2], ["8326", "5528"])
        self.assertGreater(sum(int(r[2]) for r in rows), 40)

    def test_arena2_guards(self):
        m = os.path.join(DATA, "movingai", "arena2.map")
        self.skip_unless_present(m)
        with open(m) as f:
            lines = f.read().split("\n")
        h = int(lines[1].split()[1])
        grid = lines[4:4 + h]
        guards = []
        for y, radius in ((h // 4, " 25"), (h // 2, ""), (3 * h // 4, " 25")):
            guards.append("%d %d%s" % (grid[y].index("."), y, radius))
        inst = self.path("arena2.mosb")
        self.ok("convert", "guards", "--map", m, "--guards", self.write("guards.txt", "\n".join(guards) + "\n"),
                  "--scen", m + ".scen", "-o", inst)
        queries = [tuple(int(x) for x in q) for q in mosb_reader.open_instance(inst).queries()["scen"]]
        self.assertEqual(len(queries), 929)
        picked = queries[::116]  # buckets from short to long
        args = [x for s, t in picked for x in ("--query", str(s), str(t))]
        rows = self.agree(inst, ["--view", "Games-GUARDS_2"] + args)
        self.assertEqual(len(rows), len(picked))
        self.assertTrue(all(int(r[2]) >= 1 for r in rows))


class ResearchLoop(Base):
    """Issue 19's acceptance: on a Grid benchmark, on GUARDS random512-20-1 and on a Moving AI map,
    the example solvers' own output imports, verifies against the instance, and evaluates; BOA*
    and NAMOA* agree exactly. No file is edited by hand: only the programs' output is used."""

    def import_run(self, name, inst, view, query_set):
        """Runs example solver `name` over the query set; returns its solution file."""
        fronts = self.path("fronts-" + name)
        r = run_solver(name, inst, "--view", view, "--queries", query_set, "--fronts", fronts)
        self.assertEqual(r.returncode, 0, r.stderr)
        log = self.write(name + ".log", r.stdout)
        out = self.path(name + ".sol")
        self.ok("solutions", "import", "--instance", inst, "--view", view, "--queries", query_set,
                "--dir", fronts, "--example-log", log, "--solver", name, "-o", out)
        self.ok("solutions", "verify", out, "--instance", inst)
        return out

    def boa_agrees_with_namoa(self, inst, view, query_set):
        reference = self.import_run("namoa", inst, view, query_set)
        boa = self.import_run("boa_star", inst, view, query_set)
        r = self.ok("eval", "--reference", reference, "--solutions", boa, "--eps", "0,0.01,0.05,0.1",
                    "--json")
        (solver,) = json.loads(r.stdout)["solvers"]
        solved = solver["statuses"]["solved"]
        self.assertGreater(solved, 0)
        self.assertEqual([e["covered"] for e in solver["epsilons"]], [solved] * 4)
        self.assertEqual(solver["achieved_epsilon"]["max"], 0)
        self.ok("solutions", "compare", reference, boa)
        return solver

    def test_grid_benchmark(self):
        inst = self.path("grid.mosb")
        self.ok("generate", "grid", "--width", "30", "--height", "30", "--seed", "1", "-o", inst)
        self.ok("queries", "generate", inst, "--in-place", "--set", "q", "--count", "6", "--seed", "2")
        solver = self.boa_agrees_with_namoa(inst, "Grid_2", "q")
        self.assertEqual(solver["statuses"]["solved"], 6)

    def test_guards_random512(self):
        m = os.path.join(DATA, "movingai", "random512-20-1.map")
        self.skip_unless_present(m)
        with open(m) as f:
            rows = f.read().split("\n")[4:4 + 512]
        guards = "".join("%d %d 40\n" % (rows[y].index("."), y) for y in (64, 192, 320, 448))
        inst = self.path("guards.mosb")
        self.ok("convert", "guards", "--map", m, "--guards", self.write("guards.txt", guards),
                "--scen", m + ".scen", "-o", inst)
        self.ok("queries", "generate", inst, "--in-place", "--set", "q", "--count", "4", "--seed", "3")
        self.boa_agrees_with_namoa(inst, "Games-GUARDS_2", "q")

    def test_movingai_dijkstra_lengths_verify_against_the_scenario(self):
        m = os.path.join(DATA, "movingai", "arena2.map")
        self.skip_unless_present(m)
        inst = self.path("arena2.mosb")
        self.ok("convert", "movingai", "--map", m, "--scen", m + ".scen", "-o", inst)
        # The README's C solver: `start goal cost` per query of the view `length` (set `scen`).
        r = run_solver("dijkstra", inst, "length")
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = [line.split() for line in r.stdout.splitlines()]
        self.assertEqual(len(rows), 929)
        table = self.write("lengths.csv", "query,length\n" + "".join(
            "%d,%s\n" % (q, row[2]) for q, row in enumerate(rows)))
        out = self.path("dijkstra.sol")
        self.ok("solutions", "import", "--instance", inst, "--view", "length", "--table", table,
                "--solver", "dijkstra", "-o", out)
        # verify checks each length against the scenario's optimal length (spec/SOLUTIONS.md §6).
        self.ok("solutions", "verify", out, "--instance", inst)
        # One length off by one: verify names the query.
        table = self.write("off.csv", "query,length\n" + "".join(
            "%d,%s\n" % (q, float(row[2]) + (q == 5)) for q, row in enumerate(rows)))
        off = self.path("off.sol")
        self.ok("solutions", "import", "--instance", inst, "--view", "length", "--table", table,
                "-o", off)
        r = self.mosb("solutions", "verify", off, "--instance", inst)
        self.assertEqual(r.returncode, 1)
        self.assertIn("query 5", r.stderr)


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
