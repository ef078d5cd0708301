#!/usr/bin/python3
"""End-to-end tests of `mosb eval` (spec/EVALUATION.md §4).

    MOSB=build/release/tools/mosb WRITE_SOLUTION=build/release/tests/cli/mosb_test_write_solution \
        /usr/bin/python3 tests/cli/test_eval.py

Reference and solver solution files are written with SolutionWriter (the helper program) for the
golden instance spec/golden/1.0/valid/small.mosb, view Small_2 (3 queries, 2 objectives).
"""

import csv
import io
import json
import os

import mosbtest
from mosbtest import GOLDEN, CliTest, run, setUpModule, write_solution  # noqa: F401

SMALL = os.path.join(GOLDEN, "1.0", "valid", "small.mosb")

# Reference: query 0 has a 3-vector front, query 1 a single vector, query 2 is disconnected.
REFERENCE = "0 solved 10,40 20,20 40,10\n1 solved 30,30\n2 disconnected\n"


class EvalTest(CliTest):
    def setUp(self):
        super().setUp()
        self.reference = self.solution("ref", REFERENCE)

    def solution(self, name, spec, view="Small_2", solver_epsilon=None, instance=SMALL):
        extra = [] if solver_epsilon is None else [solver_epsilon]
        return write_solution(self.path(name + ".sol.mosb"), instance, view, spec, *extra)

    def eval(self, solutions, *extra):
        return self.mosb("eval", "--reference", self.reference, "--solutions", solutions, *extra)

    def eval_json(self, solutions, *extra):
        """The exit status and the one solver's part of the JSON report."""
        result = self.eval(solutions, "--json", *extra)
        report = json.loads(result.stdout)
        self.assertEqual(len(report["solvers"]), 1)
        self.assertEqual(report["ok"], report["solvers"][0]["ok"])
        return result.returncode, report["solvers"][0]

    def test_exact_solution_passes_at_every_epsilon(self):
        rc, report = self.eval_json(self.solution("exact", "0 solved 40,10 20,20 10,40\n"
                                               "1 solved 30,30\n2 disconnected\n"), "--eps", "0,0.1")
        self.assertEqual(rc, 0, report)
        self.assertTrue(report["ok"])
        self.assertEqual([s["covered"] for s in report["epsilons"]], [2, 2])
        self.assertEqual(report["queries"][0]["achieved_epsilon"], "0")
        self.assertFalse(report["queries"][2]["failed"])

    def test_epsilon_approximate_set(self):
        # (21,21) covers (20,20) at 0.05; (10,40) and (40,10) exactly; 30,31 covers 30,30 at 1/30.
        # The solver declares ε = 0.05, so its dominated vectors are expected, not a bug.
        approx = "0 solved 10,40 21,21 40,10\n1 solved 30,31\n2 disconnected\n"
        rc, report = self.eval_json(self.solution("approx", approx, solver_epsilon="0.05"),
                                    "--eps", "0.01,0.05,0.1")
        # Not covered at 0.01, below its own ε: the approximation it announced, not a failure.
        self.assertEqual(rc, 0)
        q0, q1 = report["queries"][0], report["queries"][1]
        self.assertEqual([c["covered"] for c in q0["coverage"]], [False, True, True])
        self.assertEqual(q0["achieved_epsilon"], "0.05")
        self.assertEqual(q0["worst_reference"], [20, 20])
        self.assertEqual([c["covered"] for c in q1["coverage"]], [False, True, True])
        self.assertAlmostEqual(q1["achieved_epsilon_value"], 1 / 30)
        self.assertEqual([s["covered"] for s in report["epsilons"]], [0, 2, 2])
        self.assertEqual(q0["dominated_by_reference"], [1])
        # The same vectors from a solver that claims ε = 0.01 break its own promise.
        rc, report = self.eval_json(self.solution("approx2", approx, solver_epsilon="0.01"),
                                    "--eps", "0.01,0.05,0.1")
        self.assertEqual(rc, 1, report)
        self.assertEqual([q["failed"] for q in report["queries"]], [True, True, False])
        # The same vectors from a solver claiming exactness: (21,21) is a solver bug.
        rc, report = self.eval_json(self.solution("approx3", approx), "--eps", "0.05,0.1")
        self.assertEqual(rc, 1)
        self.assertTrue(report["queries"][0]["failed"])

    def test_missing_extreme_point(self):
        rc, report = self.eval_json(self.solution("missing", "0 solved 10,40 20,20\n"
                                               "1 solved 30,30\n2 disconnected\n"))
        self.assertEqual(rc, 1)
        q0 = report["queries"][0]
        self.assertTrue(q0["failed"])
        self.assertEqual([c["uncovered"] for c in q0["coverage"]], [1, 1, 1])
        self.assertEqual(q0["worst_reference"], [40, 10])

    def test_dominated_vector_is_reported_loudly(self):
        sol = self.solution("dominated", "0 solved 10,40 20,20 40,10 25,25\n"
                         "1 solved 30,30\n2 disconnected\n")
        rc, report = self.eval_json(sol, "--eps", "0.1")
        self.assertEqual(rc, 1)
        self.assertEqual(report["queries"][0]["dominated_by_reference"], [3])
        text = self.eval(sol, "--eps", "0.1", "--per-query")
        self.assertEqual(text.returncode, 1)
        self.assertIn("query 0: SOLVER BUG: 1 returned vector(s) strictly dominated", text.stdout)

    def test_vector_covered_only_at_tenth(self):
        # (22,22) covers (20,20) at exactly ε = 0.1 and not below.
        rc, report = self.eval_json(self.solution("tenth", "0 solved 10,40 22,22 40,10\n"
                                               "1 solved 30,30\n2 disconnected\n", solver_epsilon="0.1"),
                                    "--eps", "0.05,0.0999,0.1")
        self.assertEqual(rc, 0)  # covered at its own ε; below it, nothing was promised
        self.assertEqual([c["covered"] for c in report["queries"][0]["coverage"]],
                         [False, False, True])
        self.assertEqual(report["queries"][0]["achieved_epsilon"], "0.1")

    def test_timed_out_query_fails(self):
        sol = self.solution("timeout", "0 solved 10,40 20,20 40,10\n1 timeout\n2 disconnected\n")
        rc, report = self.eval_json(sol)
        self.assertEqual(rc, 1)
        q1 = report["queries"][1]
        self.assertEqual(q1["status"], "timeout")
        self.assertTrue(q1["failed"])
        self.assertNotIn("coverage", q1)
        self.assertEqual([s["covered"] for s in report["epsilons"]], [1, 1, 1])
        self.assertIn("query 1: timeout (not solved", self.eval(sol, "--per-query").stdout)
        self.assertNotIn("query 1:", self.eval(sol).stdout)  # per solver only, by default

    def test_mismatched_view_names_both_files(self):
        # Same instance, another view (and query set): a one-line error naming both files.
        other = self.solution("other", "", view="Small_5")
        result = self.eval(other)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
        self.assertIn("ref.sol.mosb", result.stderr)
        self.assertIn("other.sol.mosb", result.stderr)

    def test_integer_view_is_compared_exactly(self):
        # A generated grid's costs are u8. Query 0: (8,30,100) covers (7,30,100) from ε = 1/7 on,
        # (20,11,50) covers (20,10,50) from 1/10: the achieved ε is exactly 1/7. The 18-digit ε
        # just below 1/7 must not cover (in double arithmetic 1 + ε rounds to 8/7 and would).
        grid = self.path("grid.mosb")
        run("generate", "grid", "--width", "3", "--height", "3", "--objectives", "3", "-o", grid,
            check=True)
        self.reference = self.solution("grid-ref", "0 solved 7,30,100 20,10,50\n", view="Grid_3",
                                    instance=grid)
        sol = self.solution("grid-sol", "0 solved 8,30,100 20,11,50\n", view="Grid_3",
                         solver_epsilon="0.15", instance=grid)
        below, above = ".142857142857142857", ".142857142857142858"  # 18 digits at most
        rc, report = self.eval_json(sol, "--eps", "0.1,%s,%s" % (below, above))
        self.assertEqual(rc, 0, report)  # the solver claims 0.15: nothing below it is promised
        (q0,) = report["queries"]
        self.assertEqual([c["covered"] for c in q0["coverage"]], [False, False, True])
        self.assertEqual([c["uncovered"] for c in q0["coverage"]], [1, 1, 0])
        self.assertEqual([c["epsilon"] for c in q0["coverage"]],
                         ["0.1", "0" + below, "0" + above])
        self.assertEqual(q0["achieved_epsilon"], "0.142857143")  # 1/7 rounded up at digit 9
        self.assertAlmostEqual(q0["achieved_epsilon_value"], 1 / 7, places=15)
        self.assertEqual(q0["worst_reference"], [7, 30, 100])
        self.assertEqual(q0["dominated_by_reference"], [0, 1])  # listed; ε = 0.15 allows them
        rc, report = self.eval_json(sol, "--eps", above)
        self.assertEqual(rc, 0, report)
        text = self.eval(sol, "--eps", "0.1", "--per-query").stdout
        self.assertIn("query 0: solved, |S| 2, |R| 2, |S|/|R| 1, achieved ε 0.142857143, "
                      "ε=0.1 NOT covered (1 uncovered), worst reference vector (7, 30, 100)\n",
                      text)  # not a FAIL: below the solver's own ε

    def test_bad_epsilon_is_a_usage_error(self):
        result = self.eval(self.reference, "--eps", "0.1,-1")
        self.assertEqual(result.returncode, 2)
        self.assertIn("--eps", result.stderr)
        # Issue 33 §6: a value out of range says so, wherever an ε is taken.
        self.assert_one_line_error(self.eval(self.reference, "--eps", "1e400"), "--eps",
                                   "'1e400'", "out of range", code=2)
        self.assertNotIn("not a number", self.eval(self.reference, "--eps", "1e400").stderr)
        r = self.mosb("plot", "front", "--solutions", self.reference, "--reference",
                      self.reference, "--query", "0", "--eps", "1e400", "-o", self.path("f.svg"))
        self.assert_one_line_error(r, "out of range", code=2)

    def test_dominated_vectors_are_counted_apart_from_coverage(self):
        # Issue 33 §2: the reference's front plus a vector it dominates, from a solver claiming
        # exactness, was "ε=0: 1 covered, 1 not covered" and "NOT covered (0 uncovered)".
        sol = self.solution("dominated", "0 solved 10,40 20,20 40,10 25,25\n1 solved 30,30\n"
                            "2 disconnected\n")
        rc, report = self.eval_json(sol, "--eps", "0,0.1")
        self.assertEqual(rc, 1)
        self.assertEqual(report["epsilons"],
                         [{"epsilon": e, "covered": 1, "not_covered": 0, "dominated": 1,
                           "not_solved": 0} for e in ("0", "0.1")])
        q0 = report["queries"][0]
        self.assertEqual([(c["uncovered"], c["extra"], c["outcome"]) for c in q0["coverage"]],
                         [(0, 1, "dominated"), (0, 0, "dominated")])
        text = self.eval(sol, "--eps", "0,0.1", "--per-query").stdout
        self.assertIn("  ε=0: 1 covered, 0 not covered, 1 with vectors the reference dominates "
                      "while claiming ε = 0, 0 not solved\n", text)
        self.assertIn("ε=0 NOT covered (0 uncovered, 1 extra)", text)
        rows = list(csv.DictReader(io.StringIO(self.eval(sol, "--eps", "0,0.1", "--csv").stdout)))
        self.assertEqual([(r["covered@0"], r["not_covered@0"], r["dominated@0"], r["not_solved"])
                          for r in rows], [("1", "0", "1", "0")])
        # Every query the reference solved is in one column per ε; a timeout is "not solved".
        sol = self.solution("timeout", "0 solved 10,40 20,20\n1 timeout\n2 disconnected\n")
        rc, report = self.eval_json(sol, "--eps", "0")
        self.assertEqual(report["epsilons"], [{"epsilon": "0", "covered": 0, "not_covered": 1,
                                               "dominated": 0, "not_solved": 1}])

    def test_float_objectives_compare_within_a_tolerance(self):
        # Issue 33 §3: Small_2 is c1 (u32: exact) and c2 (f32, summed in f64). Two exact solvers
        # whose c2 sums differ in the last place are equal within the default 1e-9; with
        # --tolerance 0 the solver vector one ulp above the reference's is dominated by it.
        self.reference = self.solution("fref", "0 solved 10,43.88583999999999 20,20\n"
                                       "1 solved 1000000000,30\n2 disconnected\n")
        sol = self.solution("f", "0 solved 20,20 10,43.88584\n1 solved 1000000000,30\n"
                            "2 disconnected\n")
        rc, report = self.eval_json(sol, "--eps", "0")
        self.assertEqual(rc, 0, report)
        self.assertEqual(report["queries"][0]["achieved_epsilon_value"], 0)
        full = json.loads(self.eval(sol, "--json", "--eps", "0").stdout)
        self.assertEqual(full["tolerance"], 1e-9)
        self.assertIn("float objectives compared within a relative tolerance of 1e-09",
                      self.eval(sol, "--eps", "0").stdout)
        rc, report = self.eval_json(sol, "--eps", "0", "--tolerance", "0")
        self.assertEqual(rc, 1)
        self.assertEqual(report["epsilons"][0]["dominated"], 1)
        self.assertGreater(report["queries"][0]["achieved_epsilon_value"], 0)
        self.assertLess(report["queries"][0]["achieved_epsilon_value"], 1e-15)
        compare = self.mosb("solutions", "compare", self.reference, sol)
        self.assertEqual(compare.returncode, 0, compare.stdout)
        self.assertIn("3 equal, 0 different", compare.stdout)
        compare = self.mosb("solutions", "compare", self.reference, sol, "--tolerance", "0")
        self.assertEqual(compare.returncode, 1)
        self.assertIn("query 0: DIFFERENT fronts: (10, 43.88583999999999) only in", compare.stdout)
        # The integer objective stays exact whatever the tolerance: 1e9 against 1e9 + 1.
        other = self.solution("i", "0 solved 20,20 10,43.88584\n1 solved 1000000001,30\n"
                              "2 disconnected\n")
        compare = self.mosb("solutions", "compare", self.reference, other, "--tolerance", "0.1")
        self.assertIn("query 1: DIFFERENT fronts: (1000000000, 30) only in", compare.stdout)
        for bad in ("-1", "1", "abc", "nan"):
            self.assert_one_line_error(self.eval(sol, "--tolerance", bad), "--tolerance", code=2)
            self.assertEqual(self.mosb("solutions", "compare", self.reference, sol, "--tolerance",
                                       bad).returncode, 2)

    def test_one_ulp_above_the_reference_returns_at_once(self):
        # Issue 33 §1: this hung (12 minutes on a real EMOA* front, ε stepped an ulp of ε at a
        # time). self.mosb fails the test on a hang.
        self.reference = self.solution("uref", "0 solved 10,43.88583999999999\n1 solved 30,30\n"
                                       "2 disconnected\n")
        sol = self.solution("u", "0 solved 10,43.88584\n1 solved 30,30\n2 disconnected\n",
                            solver_epsilon="0.01")
        r = self.mosb("eval", "--reference", self.reference, "--solutions", sol, "--tolerance",
                      "0", "--eps", "0,0.01", "--json", timeout=60)
        self.assertEqual(r.returncode, 0, r.stderr)  # no multiset at ε = 0 was promised
        q0 = json.loads(r.stdout)["solvers"][0]["queries"][0]
        self.assertEqual([c["covered"] for c in q0["coverage"]], [False, True])
        self.assertEqual(q0["achieved_epsilon"], "0.000000001")  # rounded up at the 9th digit
        r = self.mosb("solutions", "compare", self.reference, sol, "--tolerance", "0", timeout=60)
        self.assertEqual(r.returncode, 1)

    def test_runtime_wall_or_reported(self):
        # Issue 33 §7: the solver's own runtime (format 1.5) beside mosb's wall clock.
        self.reference = self.solution("rref", REFERENCE)
        reports = self.solution("reports", "0 solved 10,40 20,20 40,10 t=2 r=0.5\n"
                                "1 solved 30,30 t=4 r=1.5\n2 disconnected t=1 r=0.25\n")
        silent = self.solution("silent", "0 solved 10,40 20,20 40,10 t=3\n1 solved 30,30 t=3\n"
                               "2 disconnected t=3\n")
        run_eval = lambda *extra: self.mosb("eval", "--reference", self.reference, "--solutions",
                                            reports, silent, "--eps", "0", *extra)
        wall = json.loads(run_eval("--json").stdout)
        self.assertEqual(wall["runtime"], "wall")
        self.assertEqual(wall["solvers"][0]["runtime_seconds"]["median"], 2)
        reported = json.loads(run_eval("--json", "--runtime", "reported").stdout)
        self.assertEqual(reported["runtime"], "reported")
        self.assertEqual(reported["solvers"][0]["runtime_seconds"]["median"], 0.5)
        self.assertTrue(reported["solvers"][0]["runtime_recorded"])
        self.assertIsNone(reported["solvers"][1]["runtime_seconds"])
        self.assertFalse(reported["solvers"][1]["runtime_recorded"])
        text = run_eval("--runtime", "reported").stdout
        self.assertIn("  reported runtime over 3 queries every solver completed: median 0.5 s", text)
        self.assertIn("  reported runtime over 0 queries every solver completed: none (the file "
                      "records no reported_runtime_seconds)", text)
        self.assertIn("  wall runtime over 3 queries", run_eval().stdout)
        rows = list(csv.DictReader(io.StringIO(run_eval("--csv", "--per-query", "--runtime",
                                                        "reported").stdout)))
        self.assertEqual([r["reported_runtime_seconds"] for r in rows],
                         ["0.5", "1.5", "0.25", "", "", ""])
        self.assertEqual(run_eval("--runtime", "cpu").returncode, 2)
        compare = self.mosb("solutions", "compare", silent, reports, "--runtime", "reported",
                            "--json")
        self.assertIsNone(json.loads(compare.stdout)["runtime_ratio"])
        compare = self.mosb("solutions", "compare", reports, reports, "--runtime", "reported")
        self.assertIn("; reported runtime ", compare.stdout)


class SolverComparisonTest(CliTest):
    """Several solvers against one reference in one run, the tables for a paper, and `solutions
    compare` (spec/EVALUATION.md §4, §6)."""

    def setUp(self):
        super().setUp()
        w = lambda name, spec, eps="0": write_solution(self.path(name), SMALL, "Small_2", spec, eps)
        self.reference = w("ref.sol", REFERENCE)
        env = dict(os.environ, MOSB_TEST_SOLVER_NAME="exact_solver")
        self.exact = write_solution(self.path("exact.sol"), SMALL, "Small_2",
                                    "0 solved 40,10 20,20 10,40 t=2\n1 solved 30,30 t=4\n"
                                    "2 disconnected t=1\n", "0", env=env)
        env = dict(os.environ, MOSB_TEST_SOLVER_NAME="approx & co")
        # 10 % off on query 0, a timeout on query 1: only queries 0 and 2 are common.
        self.approx = write_solution(self.path("approx.sol"), SMALL, "Small_2",
                                     "0 solved 11,44 22,22 44,11 t=1\n1 timeout\n"
                                     "2 disconnected t=0.5\n", "0.1", env=env)

    def eval(self, *extra):
        return self.mosb("eval", "--reference", self.reference, "--solutions", self.exact,
                         self.approx, *extra)

    def test_one_report_per_solver_with_runtimes_on_common_queries(self):
        r = self.eval("--json", "--eps", "0,0.1")
        self.assertEqual(r.returncode, 1)  # approx fails at ε = 0 and on the timeout
        report = json.loads(r.stdout)
        self.assertFalse(report["ok"])
        self.assertEqual(report["common_queries"], 2)
        exact, approx = report["solvers"]
        self.assertEqual((exact["name"], approx["name"]), ("exact_solver", "approx & co"))
        self.assertTrue(exact["ok"])
        self.assertEqual([e["covered"] for e in exact["epsilons"]], [2, 2])
        self.assertEqual(exact["runtime_seconds"]["count"], 2)  # queries 0 and 2, not 1
        self.assertEqual(exact["runtime_seconds"]["median"], 1.5)
        self.assertEqual(exact["runtime_seconds"]["max"], 2)
        # exp(mean(ln(t + 1))) − 1 over t = 2, 1: sqrt(3·2) − 1
        self.assertAlmostEqual(exact["runtime_seconds"]["shifted_geometric_mean"], 6 ** 0.5 - 1)
        self.assertEqual(approx["statuses"]["timeout"], 1)
        self.assertEqual(approx["not_solved"], 1)
        self.assertEqual(approx["epsilons"],
                         [{"epsilon": "0", "covered": 0, "not_covered": 1, "dominated": 0,
                           "not_solved": 1},
                          {"epsilon": "0.1", "covered": 1, "not_covered": 0, "dominated": 0,
                           "not_solved": 1}])
        self.assertAlmostEqual(approx["achieved_epsilon"]["max"], 0.1)
        self.assertEqual(approx["size_ratio"]["median"], 1)
        self.assertEqual(approx["runtime_seconds"]["mean"], 0.75)
        self.assertEqual(len(approx["queries"]), 3)
        shifted = json.loads(self.eval("--json", "--runtime-shift", "0").stdout)
        self.assertAlmostEqual(shifted["solvers"][0]["runtime_seconds"]["shifted_geometric_mean"],
                               2 ** 0.5)

    def test_text_csv_and_latex(self):
        text = self.eval("--eps", "0.1").stdout
        self.assertIn("solver exact_solver (%s)\n" % self.exact, text)
        self.assertIn("  wall runtime over 2 queries every solver completed: median 1.5 s", text)
        self.assertIn("  statuses: 1 solved, 1 timeout, 1 disconnected; 1 solved by the reference "
                      "only\n", text)
        self.assertTrue(text.endswith("FAIL\n"))
        csv_text = self.eval("--csv", "--eps", "0.1").stdout
        rows = list(csv.DictReader(io.StringIO(csv_text)))
        self.assertEqual([row["solver"] for row in rows], ["exact_solver", "approx & co"])
        self.assertEqual((rows[1]["timeout"], rows[1]["covered@0.1"], rows[1]["runtime_mean"]),
                         ("1", "1", "0.75"))
        per_query = list(csv.DictReader(io.StringIO(self.eval("--csv", "--per-query").stdout)))
        self.assertEqual(len(per_query), 6)
        self.assertEqual(per_query[4]["status"], "timeout")
        self.assertEqual(per_query[4]["runtime_seconds"], "")
        latex = self.eval("--latex", "--eps", "0.1").stdout
        self.assertIn("\\begin{tabular}{l", latex)
        self.assertIn("\\toprule", latex)
        self.assertIn("\napprox \\& co & 1 & 1 & 0 & 0 & 1 & 0.1 & 0.1 & 1 & 0.75 & 1 & ", latex)
        self.assertTrue(latex.endswith("\\bottomrule\n\\end{tabular}\n"))
        usage = self.eval("--latex", "--per-query")
        self.assertEqual(usage.returncode, 2)
        self.assertEqual(self.eval("--json", "--csv").returncode, 2)

    def test_csv_and_latex_show_names_as_the_files_give_them(self):
        """Issue 36 §3-§4: a name is escaped for the file's language alone: no terminal escaping
        (a backslash stays one), a formula guarded in CSV, every LaTeX special escaped."""
        spec = "0 solved 10,40 20,20 40,10\n1 solved 30,30\n2 disconnected\n"
        names = ["=1+1", "a\\b", "@x", "\\end{tabular}\\input{/etc/passwd}"]
        files = [write_solution(self.path("n%d.sol" % k), SMALL, "Small_2", spec, "0",
                                env=dict(os.environ, MOSB_TEST_SOLVER_NAME=name))
                 for k, name in enumerate(names)]
        table = self.mosb("eval", "--reference", self.reference, "--solutions", *files, "--csv")
        self.assertEqual(table.returncode, 0, table.stderr)
        lines = table.stdout.splitlines()
        self.assertEqual([line.split(",")[0] for line in lines[1:5]],
                         ['"\'=1+1"', "a\\b", '"\'@x"', "\\end{tabular}\\input{/etc/passwd}"])
        rows = list(csv.DictReader(io.StringIO(table.stdout)))
        self.assertEqual(rows[1]["solver"], "a\\b")
        latex = self.mosb("eval", "--reference", self.reference, "--solutions", *files, "--latex")
        body = latex.stdout.split("\\midrule\n")[1]
        self.assertEqual([line.split(" & ")[0] for line in body.splitlines()[:4]],
                         ["=1+1", "a\\textbackslash{}b", "@x",
                          "\\textbackslash{}end\\{tabular\\}\\textbackslash{}input\\{/etc/passwd\\}"])
        self.assertEqual(latex.stdout.count("\\end{tabular}"), 1)

    def test_a_file_of_another_binding_is_named(self):
        grid = self.path("grid.mosb")
        run("generate", "grid", "--width", "3", "--height", "3", "-o", grid, check=True)
        other = write_solution(self.path("grid.sol"), grid, "Grid_2", "0 solved 1,2\n", "0")
        r = self.mosb("eval", "--reference", self.reference, "--solutions", self.exact, other)
        self.assertEqual(r.returncode, 1)
        self.assertIn("ref.sol has instance digest", r.stderr)
        self.assertIn("grid.sol has ", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1)

    def test_solutions_compare_cross_validates_two_solvers(self):
        r = self.mosb("solutions", "compare", self.reference, self.exact)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("summary: 3 queries, 3 equal, 0 different", r.stdout)
        r = self.mosb("solutions", "compare", self.exact, self.approx)
        self.assertEqual(r.returncode, 1)
        self.assertIn("query 0: DIFFERENT fronts: (10, 40) only in %s, runtime ratio 0.5" % self.exact,
                      r.stdout)
        self.assertIn("query 1: DIFFERENT: solved in %s, timeout in %s" % (self.exact, self.approx),
                      r.stdout)
        self.assertNotIn("query 2", r.stdout)  # equal: listed only with --per-query
        self.assertIn("query 2: equal (disconnected), runtime ratio 0.5",
                      self.mosb("solutions", "compare", self.exact, self.approx, "--per-query").stdout)
        report = json.loads(self.mosb("solutions", "compare", self.exact, self.approx,
                                      "--json").stdout)
        self.assertEqual((report["ok"], report["equal"], report["different"]), (False, 1, 2))
        self.assertEqual(report["queries"][0]["first_difference"], [10, 40])
        self.assertEqual(report["queries"][0]["only_in"], "a")
        self.assertEqual(report["runtime_ratio"]["count"], 2)


if __name__ == "__main__":
    mosbtest.main()
