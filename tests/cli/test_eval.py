#!/usr/bin/python3
"""End-to-end tests of `mosb eval` (spec/EVALUATION.md §4).

    MOSB=build/release/tools/mosb WRITE_SOLUTION=build/release/tests/cli/mosb_test_write_solution \
        /usr/bin/python3 tests/cli/test_eval.py

Reference and solver solution files are written with SolutionWriter (the helper program) for the
golden instance spec/golden/1.0/valid/small.mosb, view Small_2 (3 queries, 2 objectives).
"""

import json
import os
import unittest

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
        result = self.eval(solutions, "--json", *extra)
        return result.returncode, json.loads(result.stdout)

    def test_exact_solution_passes_at_every_epsilon(self):
        rc, report = self.eval_json(self.solution("exact", "0 solved 40,10 20,20 10,40\n"
                                               "1 solved 30,30\n2 disconnected\n"), "--eps", "0,0.1")
        self.assertEqual(rc, 0, report)
        self.assertTrue(report["ok"])
        self.assertEqual([s["covered"] for s in report["summary"]], [2, 2])
        self.assertEqual(report["queries"][0]["achieved_epsilon"], "0")
        self.assertFalse(report["queries"][2]["failed"])

    def test_epsilon_approximate_set(self):
        # (21,21) covers (20,20) at 0.05; (10,40) and (40,10) exactly; 30,31 covers 30,30 at 1/30.
        # The solver declares ε = 0.05, so its dominated vectors are expected, not a bug.
        approx = "0 solved 10,40 21,21 40,10\n1 solved 30,31\n2 disconnected\n"
        rc, report = self.eval_json(self.solution("approx", approx, solver_epsilon="0.05"),
                                    "--eps", "0.01,0.05,0.1")
        self.assertEqual(rc, 1)  # fails at 0.01
        q0, q1 = report["queries"][0], report["queries"][1]
        self.assertEqual([c["covered"] for c in q0["coverage"]], [False, True, True])
        self.assertEqual(q0["achieved_epsilon"], "0.05")
        self.assertEqual(q0["worst_reference"], [20, 20])
        self.assertEqual([c["covered"] for c in q1["coverage"]], [False, True, True])
        self.assertAlmostEqual(q1["achieved_epsilon_value"], 1 / 30)
        self.assertEqual([s["covered"] for s in report["summary"]], [0, 2, 2])
        self.assertEqual(q0["dominated_by_reference"], [1])
        rc, report = self.eval_json(self.solution("approx2", approx, solver_epsilon="0.05"),
                                    "--eps", "0.05,0.1")
        self.assertEqual(rc, 0, report)
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
        text = self.eval(sol, "--eps", "0.1")
        self.assertEqual(text.returncode, 1)
        self.assertIn("query 0: SOLVER BUG: 1 returned vector(s) strictly dominated", text.stdout)

    def test_vector_covered_only_at_tenth(self):
        # (22,22) covers (20,20) at exactly ε = 0.1 and not below.
        rc, report = self.eval_json(self.solution("tenth", "0 solved 10,40 22,22 40,10\n"
                                               "1 solved 30,30\n2 disconnected\n", solver_epsilon="0.1"),
                                    "--eps", "0.05,0.0999,0.1")
        self.assertEqual(rc, 1)
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
        self.assertEqual([s["covered"] for s in report["summary"]], [1, 1, 1])
        self.assertIn("query 1: timeout (not solved", self.eval(sol).stdout)

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
        self.assertEqual(rc, 1, report)
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
        text = self.eval(sol, "--eps", "0.1").stdout
        self.assertIn("query 0: solved, |S| 2, |R| 2, |S|/|R| 1, achieved ε 0.142857143, "
                      "ε=0.1 NOT covered (1 uncovered), worst reference vector (7, 30, 100) FAIL",
                      text)

    def test_bad_epsilon_is_a_usage_error(self):
        result = self.eval(self.reference, "--eps", "0.1,-1")
        self.assertEqual(result.returncode, 2)
        self.assertIn("--eps", result.stderr)


if __name__ == "__main__":
    unittest.main()
