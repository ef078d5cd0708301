#!/usr/bin/python3
"""End-to-end tests of `mosb solutions import | inspect | verify` (spec/SOLUTIONS.md).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_solutions.py

Instances come from `mosb generate grid`; solution files from `mosb solutions import` of text,
table and JSON inputs written here.
"""

import csv
import functools
import json
import os

import mosbtest
from mosbtest import CliTest, setUpModule  # noqa: F401

QUERIES = [(0, 8), (1, 5), (8, 0), (1, 5)]  # a repeated pair: endpoint matching takes them in order
# How an import refusing a front that is no front ends (issue 33 §4).
NONDOMINATED = "; give --nondominated to keep each front's non-dominated vectors"


# Every run here must succeed unless it says check=False.
run = functools.partial(mosbtest.run, check=True)


class SolutionsTest(CliTest):
    def setUp(self):
        super().setUp()
        self.grid = self.path("grid.mosb")
        run("generate", "grid", "--width", "3", "--height", "3", "--objectives", "2", "-o",
            self.path("bare.mosb"))
        self.write("queries.txt", "".join("%d %d\n" % q for q in QUERIES))
        run("queries", "import", self.path("bare.mosb"), self.path("queries.txt"), "--set", "s",
            "-o", self.grid)
        self.other = self.path("other.mosb")
        run("generate", "grid", "--width", "3", "--height", "3", "--objectives", "2", "--seed", "7",
            "-o", self.path("bare7.mosb"))
        run("queries", "import", self.path("bare7.mosb"), self.path("queries.txt"), "--set", "s",
            "-o", self.other)

    def digest(self, instance):
        return json.loads(run("inspect", instance, "--json").stdout)["digest"]

    def import_(self, *args, check=True, output="out.sol"):
        return run("solutions", "import", "--instance", self.grid, "--view", "Grid_2", "--queries",
                   "s", *args, "-o", self.path(output), check=check)

    def inspect(self, name="out.sol"):
        return json.loads(run("solutions", "inspect", "--json", self.path(name)).stdout)

    def assert_refused(self, args, message, output="bad.sol"):
        self.assert_error(self.import_(*args, check=False, output=output), message)
        self.assertFalse(os.path.exists(self.path(output)), "a refused import wrote its output")

    # --- per-query directory --------------------------------------------------------------------

    def front_dir(self, files):
        d = self.path("fronts")
        for name, text in files.items():
            self.write(os.path.join("fronts", name), text)
        return d

    def test_inspect_eval_and_report_summarise_a_file_alike(self):
        # One summary of the paper's Table 1 (spec/EVALUATION.md §4): the same file gives the same
        # front sizes in `solutions inspect`, in `eval` (the solver's own) and in `report`'s
        # suite table, over its completed queries (a disconnected one counts with size 0), and is
        # shown under one name (the file name without its extension when it records none).
        d = self.front_dir({"0.txt": "1 9\n2 7\n3 5\n", "1.txt": "4 4\n", "2.txt": "",
                            "3.txt": "5 5\n6 1\n"})
        self.import_("--dir", d, "--status-for-empty", "disconnected", output="boa.sol")
        sol = self.path("boa.sol")
        inspected = json.loads(run("solutions", "inspect", "--json", sol).stdout)["front_size"]
        self.assertEqual(inspected, {"count": 4, "min": 0, "median": 1.5, "mean": 1.5, "max": 3})
        evaluated = json.loads(run("eval", "--reference", sol, "--solutions", sol, "--json")
                               .stdout)["solvers"][0]
        self.assertEqual(evaluated["name"], "boa")
        self.assertEqual(evaluated["front_size"], inspected)
        run("report", self.grid, "--solutions", sol, "-o", self.path("r.html"), "--csv",
            self.path("tables"))
        with open(self.path(os.path.join("tables", "suite.csv")), newline="") as f:
            row = next(csv.DictReader(f))
        self.assertEqual(row["fronts_of"], "boa")
        self.assertEqual([float(row["front_" + k]) for k in ("min", "median", "mean", "max")],
                         [inspected[k] for k in ("min", "median", "mean", "max")])

    def test_import_reads_integers_exactly_and_never_keeps_a_failed_search(self):
        # 2^53 + 1 would be rounded to 2^53 as a double: refused, in text and in JSON.
        d = self.front_dir({"0.txt": "9007199254740993 1\n"})
        self.assert_refused(["--dir", d], "%s/0.txt:1:1: the integer '9007199254740993' is above "
                            "2^53, the largest exact integer cost" % d)
        log = self.write("big.json", '[{"source": %d, "target": %d, "finish_info": {"solutions": '
                                     '[{"cost_until_now": [9007199254740993, 1]}]}}]' % QUERIES[0])
        self.assert_refused(["--json-log", log], "%s: /0/finish_info/solutions/0/cost_until_now/0: "
                            "the integer 9007199254740993 is above 2^53, the largest exact integer "
                            "cost" % log)
        # Written with a point or an exponent, it would be rounded just the same: refused too.
        for text in ("9007199254740993.0", "9.007199254740993e15"):
            d = self.front_dir({"0.txt": text + " 1\n"})
            self.assert_refused(["--dir", d], "%s/0.txt:1:1: the cost '%s' is read as 2^53, to "
                                "which a point or an exponent may have rounded it: write an "
                                "integer cost as digits alone" % (d, text))
            log = self.write("big.json", '[{"source": %d, "target": %d, "finish_info": '
                             '{"solutions": [{"cost_until_now": [%s, 1]}]}}]'
                             % (QUERIES[0][0], QUERIES[0][1], text))
            self.assert_refused(["--json-log", log], "%s: /0/finish_info/solutions/0/cost_until_now"
                                "/0: the cost 9.007199254740992e+15 is read as 2^53, to which a point "
                                "or an exponent may have rounded it: write an integer cost as "
                                "digits alone" % log)
        # A record whose search says it did not succeed: failed, its partial front dropped.
        log = self.write("failed.json", '[{"source": %d, "target": %d, "finish_info": {"solutions":'
                                        ' [{"cost_until_now": [1, 9]}], "status": "Failed"}}]'
                                        % QUERIES[0])
        self.import_("--json-log", log)
        info = self.inspect()
        self.assertEqual((info["statuses"]["failed"], info["vectors"]), (1, 0))
        # The failure wins over a "status": "solved" beside it, in either order.
        for record in ('"status": "solved", "finish_info": {"solutions": [{"cost_until_now": '
                       '[1, 9]}], "status": "Failed"}',
                       '"finish_info": {"status": "Timeout", "solutions": []}, "status": "solved"'):
            log = self.write("contradiction.json", '[{"source": %d, "target": %d, %s}]'
                             % (QUERIES[0][0], QUERIES[0][1], record))
            self.import_("--json-log", log)
            info = self.inspect()
            self.assertEqual((info["statuses"]["failed"], info["vectors"]), (1, 0), record)
        # A key twice in one object is refused, naming where: never the last one silently.
        log = self.write("twice.json", '[{"source": %d, "target": %d,\n "status": "failed", '
                         '"status": "solved", "finish_info": {"solutions": []}}]' % QUERIES[0])
        self.assert_refused(["--json-log", log], '%s:2:22: invalid JSON: the key "status" twice in '
                            'one object' % log)

    def test_directory_import_and_inspect(self):
        d = self.front_dir({"0.txt": "# a comment\n1 9\n[2, 7]\n\n3;5\r\n", "q1.front": "4,4\n",
                            "query-2.txt": ""})
        self.import_("--dir", d, "--solver", "brute", "--solver-version", "1")
        info = self.inspect()
        self.assertEqual(info["instance_digest"], self.digest(self.grid))
        self.assertEqual((info["view"], info["query_set"]), ("Grid_2", "s"))
        self.assertEqual([o["name"] for o in info["objectives"]], ["c1", "c2"])
        self.assertEqual((info["solver"], info["solver_version"], info["epsilon"]), ("brute", "1", "0"))
        self.assertEqual((info["queries"], info["vectors"]), (4, 4))
        # An empty front file is `failed` unless the user says otherwise (--status-for-empty).
        self.assertEqual(info["statuses"], {"solved": 2, "timeout": 0, "memory-limit": 0,
                                            "disconnected": 0, "not-run": 1, "failed": 1})
        # Front sizes 3 and 1 over the two completed queries: the median of an even count is the
        # middle pair's mean (spec/EVALUATION.md §4, as eval and report say it).
        self.assertEqual(info["front_size"], {"count": 2, "min": 1, "median": 2, "mean": 2, "max": 3})
        self.assertIsNone(info["runtime_seconds"])
        self.assertFalse(info["paths"])
        text = run("solutions", "inspect", self.path("out.sol")).stdout
        self.assertIn("4 queries: 2 solved, 0 timeout, 0 memory-limit, 0 disconnected, 1 not-run, "
                      "1 failed", text)
        self.assertIn("front size over 2 completed queries (solved or disconnected): min 1, median 2, "
                      "mean 2, max 3 (4 vectors)", text)
        ok = run("solutions", "verify", self.path("out.sol"), "--instance", self.grid)
        self.assertIn("OK", ok.stdout)
        self.assertTrue(json.loads(run("solutions", "verify", self.path("out.sol"), "--json").stdout)["ok"])

    def test_import_is_deterministic(self):
        d = self.front_dir({"0.txt": "1 9\n2 7\n", "1.txt": "4 4\n"})
        self.import_("--dir", d, output="a.sol")
        self.import_("--dir", d, output="b.sol")
        with open(self.path("a.sol"), "rb") as a, open(self.path("b.sol"), "rb") as b:
            self.assertEqual(a.read(), b.read())

    def test_columns_pick_values(self):
        d = self.front_dir({"0.txt": "99 1 9\n99 2 7\n"})
        self.assert_refused(["--dir", d],
                            "%s/0.txt:1:1: 3 values, the view has 2 objectives (--columns picks values)" % d)
        self.import_("--dir", d, "--columns", "1,2")
        self.assertEqual(self.inspect()["vectors"], 2)
        # Picked the wrong way round, (9, 1) and (7, 2) are still a front; (99, 1), (99, 2) is not,
        # and the import refuses it (issue 33 §4), naming both vectors and their lines.
        self.assert_refused(["--dir", d, "--columns", "0,1"],
                            "%s/0.txt:2: query 0: [dominated] vector (99, 2) is dominated by "
                            "(99, 1) (at %s/0.txt:1)%s" % (d, d, NONDOMINATED))

    def test_directory_errors_are_located(self):
        d = self.front_dir({"0.txt": "1 9\n2 -7\n"})
        self.assert_refused(["--dir", d], "%s/0.txt:2:3: negative cost '-7'" % d)
        self.write("fronts/0.txt", "1 9\n  2 inf\n")
        self.assert_refused(["--dir", d], "%s/0.txt:2:5: non-finite cost 'inf'" % d)
        self.write("fronts/0.txt", "1 x9\n")
        self.assert_refused(["--dir", d], "%s/0.txt:1:3: expected a cost, found 'x9'" % d)
        self.write("fronts/0.txt", "1 9 3\n")
        self.assert_refused(["--dir", d],
                            "%s/0.txt:1:1: 3 values, the view has 2 objectives (--columns picks values)" % d)
        self.write("fronts/0.txt", "[1, 9\n")
        self.assert_refused(["--dir", d], "%s/0.txt:1:6: '[' without a closing ']'" % d)
        os.remove(self.path("fronts/0.txt"))
        self.write("fronts/7.txt", "1 9\n")
        self.assert_refused(["--dir", d],
                            "%s/7.txt: query id 7 outside 0..3 (the set has 4 queries)" % d)
        os.remove(self.path("fronts/7.txt"))
        self.write("fronts/4.txt", "1 9\n")
        # The grid records id_base 0: 1-based solver output needs --force-id-base (exit 2 without).
        r = self.import_("--dir", d, "--id-base", "1", check=False)
        self.assertEqual(r.returncode, 2, r)
        self.assertIn("--id-base 1 contradicts", r.stderr)
        self.import_("--dir", d, "--id-base", "1", "--force-id-base")  # 1-based: 4 is the last query
        self.write("fronts/q04.txt", "1 9\n")
        self.assert_refused(["--dir", d, "--id-base", "1", "--force-id-base"],
                            "%s/q04.txt: a second result for query 3 (the first: %s/4.txt)" % (d, d))

    # --- CSV/TSV table --------------------------------------------------------------------------

    def test_table_import(self):
        t = self.write("t.csv", "query,c2,c1\n0,9,1\n1, 4 ,4\n0,7,2\n")
        self.import_("--table", t)
        info = self.inspect()
        self.assertEqual((info["vectors"], info["statuses"]["solved"]), (3, 2))
        run("solutions", "verify", self.path("out.sol"), "--instance", self.grid)
        # Columns by name: c1 is the third column, so query 0 holds (1, 9) and (2, 9), which is no
        # front: refused naming both rows.
        t = self.write("t.tsv", "query\tc2\tc1\n0\t9\t1\n0\t9\t2\n")
        self.assert_refused(["--table", t], "%s:3: query 0: [dominated] vector (2, 9) is dominated "
                            "by (1, 9) (at %s:2)%s" % (t, t, NONDOMINATED))
        t = self.write("p.csv", "query,a,b\n0,9,1\n")
        self.import_("--table", t, "--columns", "2,1")
        self.assertEqual(self.inspect()["vectors"], 1)

    def test_table_errors_are_located(self):
        t = self.write("t.csv", "q,c1,c2\n")
        self.assert_refused(["--table", t], "%s:1:1: no 'query' column in the header" % t)
        t = self.write("t.csv", "query,c1,x\n")
        self.assert_refused(["--table", t], "%s:1:1: no column 'c2' (an objective of the view; "
                            "--columns picks columns by position)" % t)
        t = self.write("t.csv", "query,c1,c2\n0,1,2\n0,1\n")
        self.assert_refused(["--table", t], "%s:3:4: 2 fields, the header has 3" % t)
        t = self.write("t.csv", "query,c1,c2\n9,1,2\n")
        self.assert_refused(["--table", t], "%s:2:1: query id 9 outside 0..3 (the set has 4 queries)" % t)
        t = self.write("t.csv", "query,c1,c2\n0,1,nan\n")
        self.assert_refused(["--table", t], "%s:2:5: non-finite cost 'nan'" % t)
        t = self.write("t.csv", "query,c1,c2\n0,-1,2\n")
        self.assert_refused(["--table", t], "%s:2:3: negative cost '-1'" % t)
        # A cost that is no path sum of the u8 objective: refused naming the input line.
        t = self.write("t.csv", "query,c1,c2\n0,1,2\n0,1.5,2\n")
        self.assert_refused(["--table", t], "%s:3: query 0, objective 'c1': cost is not an integer "
                            "(the objective's arc costs are u8)" % t)

    # --- JSON logs ------------------------------------------------------------------------------

    def log(self, records):
        return self.write("log.json", json.dumps(records, indent=1))

    @staticmethod
    def record(source, target, costs, ms=12.5):
        return {"source": source, "target": target, "total_runtime(ms)": ms,
                "finish_info": {"solutions": [{"cost_until_now": c} for c in costs]}}

    def test_json_log_by_position_and_endpoints(self):
        records = [self.record(s, t, [[1, 9], [2, 7]] if k == 0 else [[4, 4]])
                   for k, (s, t) in enumerate(QUERIES)]
        self.import_("--json-log", self.log(records))
        info = self.inspect()
        self.assertEqual((info["vectors"], info["statuses"]["solved"]), (5, 4))
        run("solutions", "verify", self.path("out.sol"), "--instance", self.grid)
        # 1-based endpoints, in another order, matched by endpoints; the repeated pair (1, 5)
        # takes queries 1 and 3 in record order; a record without solutions is disconnected.
        shuffled = [self.record(9, 1, []), self.record(2, 6, [[4, 4]]), self.record(2, 6, [[5, 5]])]
        self.import_("--json-log", self.log(shuffled), "--match", "endpoints", "--id-base", "1", "--force-id-base")
        info = self.inspect()
        self.assertEqual(info["statuses"], {"solved": 2, "timeout": 0, "memory-limit": 0,
                                            "disconnected": 1, "not-run": 1, "failed": 0})
        # By position, the same records do not fit query 0.
        self.assert_refused(["--json-log", self.path("log.json"), "--id-base", "1", "--force-id-base"],
                            "%s: /0: source 9 and target 1, but query 0 runs from 1 to 9"
                            % self.path("log.json"))

    def test_json_log_errors(self):
        name = self.path("log.json")
        self.write("log.json", '[{"source": 0,\n  "target": 8,, }]')
        self.assert_refused(["--json-log", name], "%s:2:15: invalid JSON: syntax error while parsing "
                            "object key - unexpected ','; expected string literal" % name)
        self.log([self.record(0, 99, [[1, 2]])])
        self.assert_refused(["--json-log", name], "%s: /0/target: vertex id 99 outside 0..10" % name)
        self.log([self.record(0, 5, [[1, 2]])])
        self.assert_refused(["--json-log", name, "--match", "endpoints"],
                            "%s: /0: source 0 and target 5 are no query of the set (or every such "
                            "query has a record)" % name)
        self.log([self.record(0, 8, [[1, 2], [1, -2]])])
        self.assert_refused(["--json-log", name],
                            "%s: /0/finish_info/solutions/1/cost_until_now/1: negative cost -2" % name)
        self.log([self.record(0, 8, [[1, 2, 3]])])
        self.assert_refused(["--json-log", name],
                            "%s: /0/finish_info/solutions/0/cost_until_now: 3 values, the view has 2 "
                            "objectives (--columns picks values)" % name)
        self.log([self.record(0, 8, [[1, "2"]])])
        self.assert_refused(["--json-log", name],
                            '%s: /0/finish_info/solutions/0/cost_until_now/1: expected a cost, found "2"'
                            % name)
        self.log([self.record(s, t, [[1, 1]]) for s, t in QUERIES + [(0, 8)]])
        self.assert_refused(["--json-log", name], "%s: /4: record 4, but the set has 4 queries" % name)
        self.log({"source": 0})
        self.assert_refused(["--json-log", name], "%s: /: expected an array of records" % name)
        # A number no JSON number type holds (found by the fuzzer: it escaped as an uncaught
        # exception, std::terminate).
        self.write("log.json", '[{"source": 0,\n  "target": 1e999}]')
        self.assert_refused(["--json-log", name],
                            "%s:2:13: invalid JSON: number overflow parsing '1e999'" % name)

    # --- export -------------------------------------------------------------------------------

    def read(self, name):
        with open(self.path(name), "rb") as f:
            return f.read()

    def test_export_round_trips(self):
        d = self.front_dir({"0.txt": "1 9\n[2, 7]\n", "2.txt": "", "3.txt": "4;4\n"})
        self.import_("--dir", d, output="a.sol")
        out = run("solutions", "export", self.path("a.sol"), "--dir", self.path("exported"))
        self.assertIn("wrote 3 front files", out.stdout)
        with open(self.path("exported/0.txt")) as f:
            self.assertEqual(f.read(), "1 9\n2 7\n")
        with open(self.path("exported/2.txt")) as f:
            self.assertEqual(f.read(), "status failed\n")  # the empty input file, stated
        self.assertFalse(os.path.exists(self.path("exported/1.txt")))  # not-run
        self.import_("--dir", self.path("exported"), output="b.sol")
        self.assertEqual(self.read("a.sol"), self.read("b.sol"))
        records = [self.record(s + 1, t + 1, [[1, 9], [2, 7]] if k == 0 else [[4, 4]], ms=12.5)
                   for k, (s, t) in enumerate(QUERIES)]
        self.import_("--json-log", self.log(records), "--id-base", "1", "--force-id-base", output="c.sol")
        run("solutions", "export", self.path("c.sol"), "--instance", self.grid, "--json-log",
            self.path("exported.json"), "--id-base", "1")
        with open(self.path("exported.json")) as f:
            self.assertEqual(json.load(f), records)
        self.import_("--json-log", self.path("exported.json"), "--id-base", "1", "--force-id-base", output="d.sol")
        self.assertEqual(self.read("c.sol"), self.read("d.sol"))
        bad = run("solutions", "export", self.path("c.sol"), "--instance", self.other, "--json-log",
                  self.path("x.json"), check=False)
        self.assertEqual(bad.returncode, 1)
        self.assertIn(self.digest(self.other), bad.stderr)
        self.assertFalse(os.path.exists(self.path("x.json")))


    # --- path sums (spec/SOLUTIONS.md §3) -------------------------------------------------------

    def test_sums_above_the_arc_type_are_stored(self):
        # c1 and c2 are u8 arc costs; a path's sum is not: 300 and 70000 are stored as u64.
        d = self.front_dir({"0.txt": "300 70000\n"})
        self.import_("--dir", d)
        info = self.inspect()
        self.assertEqual([o["type"] for o in info["objectives"]], ["u64", "u64"])
        run("solutions", "export", self.path("out.sol"), "--dir", self.path("exported"))
        with open(self.path("exported/0.txt")) as f:
            self.assertEqual(f.read(), "300 70000\n")
        self.assertEqual(mosbtest.header(self.read("out.sol"))["version_minor"], 3)
        # Above 2^53 a sum is refused, naming the file and line, never wrapped.
        self.write("fronts/0.txt", "1 1\n9007199254740994 1\n")
        self.assert_refused(["--dir", d], "%s/0.txt:2:1: the integer '9007199254740994' is above "
                            "2^53, the largest exact integer cost" % d)
        records = [self.record(1, 9, [[1, 1], [2, 1e300]])]
        self.assert_refused(["--json-log", self.log(records), "--id-base", "1", "--force-id-base"],
                            "%s: /0/finish_info/solutions/1/cost_until_now: query 0, objective 'c2': "
                            "path sum above 2^53, the largest integer a solution file stores exactly"
                            % self.path("log.json"))

    def test_ppa_json_log_on_u16_costs_with_sums_in_millions(self):
        # A chain 1 -> 2 -> ... -> 101 of arcs costing 50000 and 60000 (u16 columns): the path sums
        # are 5,000,000 and 6,000,000.
        n = 101
        arcs = "".join("a %d %d %%d\n" % (v, v + 1) for v in range(1, n))
        self.write("chain-distance.gr", "p sp %d %d\n" % (n, n - 1) + arcs.replace("%d\n", "50000\n"))
        self.write("chain-time.gr", "p sp %d %d\n" % (n, n - 1) + arcs.replace("%d\n", "60000\n"))
        run("convert", "dimacs", "--gr", self.path("chain-distance.gr"), "--gr",
            self.path("chain-time.gr"), "--view", "PP=c1,c2", "-o", self.path("chain0.mosb"))
        objectives = json.loads(run("inspect", "--json", self.path("chain0.mosb")).stdout)["objectives"]
        self.assertEqual([(o["name"], o["type"]) for o in objectives],
                         [("c1", "u16"), ("c2", "u16")])
        self.write("pairs.txt", "1 101\n101 1\n")  # DIMACS ids are 1-based
        run("queries", "import", self.path("chain0.mosb"), self.path("pairs.txt"), "--set", "s",
            "-o", self.path("chain.mosb"))
        # PPA*'s log: 1-based ids, the front in finish_info.solutions[].cost_until_now.
        log = self.write("ppa.json", json.dumps([
            {"source": 1, "target": 101, "total_runtime(ms)": 3.5,
             "finish_info": {"solutions": [{"cost_until_now": [5000000, 6000000]}]}},
            {"source": 101, "target": 1, "finish_info": {"solutions": []}}]))
        r = run("solutions", "import", "--instance", self.path("chain.mosb"), "--view", "PP",
                "--queries", "s", "--json-log", log, "--id-base", "1", "-o", self.path("chain.sol"))
        self.assertIn("2 of 2 queries imported, 1 vectors", r.stdout)
        # 101 cannot reach 1 (the chain runs one way): the disconnected claim holds.
        run("solutions", "verify", self.path("chain.sol"), "--instance", self.path("chain.mosb"))
        run("solutions", "export", self.path("chain.sol"), "--dir", self.path("chain-out"))
        with open(self.path("chain-out/0.txt")) as f:
            self.assertEqual(f.read(), "5000000 6000000\n")

    # --- statuses (spec/SOLUTIONS.md §4, §7) ----------------------------------------------------

    def test_status_for_empty_front_files(self):
        d = self.front_dir({"0.txt": "1 9\n", "2.txt": "", "3.txt": "# nothing\n"})
        self.import_("--dir", d)
        self.assertEqual(self.inspect()["statuses"]["failed"], 2)
        for status in ("disconnected", "timeout", "failed"):
            self.import_("--dir", d, "--status-for-empty", status)
            self.assertEqual(self.inspect()["statuses"][status], 2, status)
        bad = self.import_("--dir", d, "--status-for-empty", "solved", check=False)
        self.assertEqual(bad.returncode, 2)

    def test_stated_statuses_in_front_files(self):
        d = self.front_dir({"0.txt": "1 9\n", "1.txt": "status timeout\n",
                            "2.txt": "status failed\nexit_status 139\n",
                            "3.txt": "# killed\nstatus memory-limit\n"})
        self.import_("--dir", d)
        info = self.inspect()
        self.assertEqual(info["statuses"], {"solved": 1, "timeout": 1, "memory-limit": 1,
                                            "disconnected": 0, "not-run": 0, "failed": 1})
        self.assertEqual(info["statistics"]["exit_status"], {"queries": 1, "total": 139, "max": 139})
        run("solutions", "verify", self.path("out.sol"), "--instance", self.grid)
        # Exported and imported again: the same file.
        run("solutions", "export", self.path("out.sol"), "--dir", self.path("exported"))
        with open(self.path("exported/2.txt")) as f:
            self.assertEqual(f.read(), "status failed\nexit_status 139\n")
        self.import_("--dir", self.path("exported"), output="again.sol")
        self.assertEqual(self.read("out.sol"), self.read("again.sol"))
        self.write("fronts/1.txt", "status timeout\n1 2\n")
        self.assert_refused(["--dir", d], "%s/1.txt: status timeout with vectors (only a solved "
                            "query has a front)" % d)
        self.write("fronts/1.txt", "status crashed\n")
        self.assert_refused(["--dir", d], "%s/1.txt:1:8: unknown status 'crashed' (solved, timeout, "
                            "memory-limit, disconnected, failed)" % d)
        self.write("fronts/1.txt", "status timeout\nexit_status 1\n")
        self.assert_refused(["--dir", d], "%s/1.txt: an exit status for a timeout query (only "
                            "failed ones carry it)" % d)

    def test_table_status_columns(self):
        t = self.write("t.csv", "query,status,exit_status,c1,c2\n0,,,1,9\n0,solved,,2,7\n"
                       "1,timeout,,,\n2,failed,6,,\n3,disconnected,,,\n")
        self.import_("--table", t)
        info = self.inspect()
        self.assertEqual(info["statuses"], {"solved": 1, "timeout": 1, "memory-limit": 0,
                                            "disconnected": 1, "not-run": 0, "failed": 1})
        self.assertEqual(info["statistics"]["exit_status"]["max"], 6)
        t = self.write("t.csv", "query,status,c1,c2\n1,timeout,1,2\n")
        self.assert_refused(["--table", t], "%s:2:11: a cost for a timeout query (only a solved "
                            "query has a front; leave the field empty)" % t)
        t = self.write("t.csv", "query,status,c1,c2\n0,,1,2\n0,failed,,\n")
        self.assert_refused(["--table", t], "%s:3:3: a second row for query 0 with status failed "
                            "(an earlier row says solved; only a solved query has several rows)" % t)

    def test_json_log_statuses(self):
        records = [self.record(1, 9, [[1, 9]]), {"source": 2, "target": 6, "status": "timeout",
                                                 "total_runtime(ms)": 60000},
                   {"source": 9, "target": 1, "status": "failed", "exit_status": 134},
                   {"source": 2, "target": 6, "status": "memory-limit"}]
        self.import_("--json-log", self.log(records), "--id-base", "1", "--force-id-base")
        info = self.inspect()
        self.assertEqual(info["statuses"], {"solved": 1, "timeout": 1, "memory-limit": 1,
                                            "disconnected": 0, "not-run": 0, "failed": 1})
        # A timeout's runtime is not kept (an interrupted run carries no statistics).
        self.assertEqual(info["statistics"]["runtime_seconds"]["queries"], 1)
        run("solutions", "export", self.path("out.sol"), "--instance", self.grid, "--json-log",
            self.path("exported.json"), "--id-base", "1")
        with open(self.path("exported.json")) as f:
            self.assertEqual(json.load(f)[2], {"source": 9, "target": 1, "status": "failed",
                                               "exit_status": 134})
        records[1]["status"] = "finished"
        self.assert_refused(["--json-log", self.log(records), "--id-base", "1", "--force-id-base"],
                            "%s: /1/status: unknown status 'finished' (solved, timeout, "
                            "memory-limit, disconnected, failed)" % self.path("log.json"))

    def test_verify_checks_disconnected_claims(self):
        # The 3x3 grid is strongly connected: a disconnected claim is a wrong answer.
        d = self.front_dir({"0.txt": "1 9\n", "2.txt": "status disconnected\n"})
        self.import_("--dir", d)
        bad = run("solutions", "verify", self.path("out.sol"), "--instance", self.grid, check=False)
        self.assertEqual(bad.returncode, 1)
        self.assertEqual(bad.stderr.strip(), "mosb: %s: query 2: [disconnected] the goal 0 is "
                         "reachable from the start 8 (a wrong answer)" % self.path("out.sol"))

    # --- verify ---------------------------------------------------------------------------------

    def test_verify_names_dominated_and_duplicate_vectors(self):
        # `solutions import` refuses such fronts, so the files are written by the library's writer.
        write = functools.partial(mosbtest.write_solution, self.path("out.sol"), self.grid,
                                  "Grid_2")
        write("0 solved 1,9 2,7\n1 solved 4,4 5,3 4,4\n", "0", "s")
        bad = run("solutions", "verify", self.path("out.sol"), "--instance", self.grid, check=False)
        self.assertEqual(bad.returncode, 1)
        self.assertEqual(bad.stderr.strip(), "mosb: %s: query 1: [duplicate] vector (4, 4) appears twice"
                         % self.path("out.sol"))
        write("0 solved 1,9 2,7\n1 solved 4,4 3,9 3,8\n", "0", "s")
        bad = run("solutions", "verify", self.path("out.sol"), "--instance", self.grid, check=False)
        self.assertEqual(bad.returncode, 1)
        self.assertEqual(bad.stderr.strip(),
                         "mosb: %s: query 1: [dominated] vector (3, 9) is dominated by (3, 8)"
                         % self.path("out.sol"))
        # Without the instance only the payload is checked: the same file passes.
        self.assertEqual(run("solutions", "verify", self.path("out.sol")).returncode, 0)

    def test_verify_against_another_instance_names_both_digests(self):
        d = self.front_dir({"0.txt": "1 9\n"})
        self.import_("--dir", d)
        bad = run("solutions", "verify", self.path("out.sol"), "--instance", self.other, check=False)
        self.assertEqual(bad.returncode, 1)
        self.assertIn(self.digest(self.grid), bad.stderr)
        self.assertIn(self.digest(self.other), bad.stderr)
        self.assertNotEqual(self.digest(self.grid), self.digest(self.other))
        report = json.loads(run("solutions", "verify", self.path("out.sol"), "--instance", self.other,
                                "--json", check=False).stdout)
        self.assertFalse(report["ok"])
        self.assertIn(self.digest(self.other), report["problem"])

    # --- issue 33: fronts that are no fronts, outputs that are inputs -----------------------------

    def test_import_refuses_dominated_and_repeated_vectors_unless_nondominated(self):
        # Query 0 repeats (1, 9) (PPA* pair logs hold each vector twice), query 1 holds (4, 5)
        # beside (4, 4) (as the published PPA* BAY log holds (955620, 1890862) beside
        # (955620, 1890092)), query 2 is a front.
        d = self.front_dir({"0.txt": "1 9\n2 7\n1 9\n", "1.txt": "4 5\n4 4\n3 9\n",
                            "2.txt": "5 5\n"})
        self.assert_refused(["--dir", d], "%s/0.txt:3: query 0: [duplicate] vector (1, 9) appears "
                            "twice (at %s/0.txt:1)%s" % (d, d, NONDOMINATED))
        records = [self.record(0, 8, [[1, 9], [2, 7], [1, 9]]),
                   self.record(1, 5, [[4, 5], [4, 4], [3, 9]])]
        log = self.log(records)
        self.assert_refused(["--json-log", log],
                            "%s: /0/finish_info/solutions/2/cost_until_now: query 0: [duplicate] "
                            "vector (1, 9) appears twice (at %s: /0/finish_info/solutions/0/"
                            "cost_until_now)%s" % (log, log, NONDOMINATED))
        log = self.log(records[1:])
        self.assert_refused(["--json-log", log, "--match", "endpoints"],
                            "%s: /0/finish_info/solutions/0/cost_until_now: query 1: [dominated] "
                            "vector (4, 5) is dominated by (4, 4) (at %s: /0/finish_info/solutions/"
                            "1/cost_until_now)%s" % (log, log, NONDOMINATED))
        # --nondominated keeps the first of equal vectors and the non-dominated ones, and the
        # file says what was dropped.
        r = self.import_("--dir", d, "--nondominated")
        self.assertIn("5 vectors (2 dominated or repeated vectors dropped from 2 queries)", r.stdout)
        info = self.inspect()
        self.assertEqual(info["vectors"], 5)
        self.assertEqual(info["dropped_vectors"], {"vectors": 2, "queries": 2})
        self.assertIn("imported with --nondominated: 2 dominated or repeated vectors dropped from 2 "
                      "queries", run("solutions", "inspect", self.path("out.sol")).stdout)
        run("solutions", "verify", self.path("out.sol"), "--instance", self.grid)
        run("solutions", "export", self.path("out.sol"), "--dir", self.path("back"))
        self.assertEqual(mosbtest.read(self.path("back/0.txt"), "r"), "1 9\n2 7\n")
        self.assertEqual(mosbtest.read(self.path("back/1.txt"), "r"), "4 4\n3 9\n")
        # A clean input imported with --nondominated records that nothing was dropped; without
        # the flag, nothing is recorded.
        self.import_("--dir", self.path("back"), "--nondominated", "--json", output="clean.sol")
        self.assertEqual(self.inspect("clean.sol")["dropped_vectors"], {"vectors": 0, "queries": 0})
        self.import_("--dir", self.path("back"), output="plain.sol")
        self.assertIsNone(self.inspect("plain.sol")["dropped_vectors"])

    def test_every_writing_command_refuses_to_overwrite_an_input(self):
        # Issue 33 §5: each of these destroyed its input before. The refusal is one line naming
        # both files, and the input keeps its bytes.
        d = self.front_dir({"0.txt": "1 9\n2 7\n", "1.txt": "4 4\n"})
        self.import_("--dir", d, output="a.sol")

        def refused(command, victim):
            before = mosbtest.read(victim)
            r = run(*command, check=False)
            self.assert_one_line_error(r, victim, "is the same file as the input",
                                       "refusing to overwrite an input")
            self.assertEqual(mosbtest.read(victim), before)

        importing = ["solutions", "import", "--instance", self.grid, "--view", "Grid_2",
                     "--queries", "s"]
        # import: -o the instance, the log, the table, the example log, a front file of --dir.
        refused(importing + ["--dir", d, "-o", self.grid], self.grid)
        log = self.log([self.record(0, 8, [[1, 9]])])
        refused(importing + ["--json-log", log, "-o", log], log)
        table = self.write("t.csv", "query,c1,c2\n0,1,9\n")
        refused(importing + ["--table", table, "-o", table], table)
        front = os.path.join(d, "0.txt")
        refused(importing + ["--dir", d, "-o", front], front)
        example = self.write("run.log", "0 8 2 0.5 10\n1 5 1 0.5 10\n")
        refused(importing + ["--dir", d, "--example-log", example, "-o", example], example)
        # export: --json-log onto the solution file or the instance, --dir onto the solution file.
        sol = self.path("a.sol")
        refused(["solutions", "export", sol, "--json-log", sol, "--instance", self.grid], sol)
        refused(["solutions", "export", sol, "--json-log", self.grid, "--instance", self.grid],
                self.grid)
        os.makedirs(self.path("out"))
        inside = self.path("out", "1.txt")  # export --dir out writes out/0.txt and out/1.txt
        os.rename(sol, inside)
        refused(["solutions", "export", inside, "--dir", self.path("out")], inside)
        self.assertFalse(os.path.exists(self.path("out", "0.txt")), "export wrote before refusing")
        # merge: -o one of the parts.
        self.write("q0/0.txt", "1 9\n")
        self.write("q1/1.txt", "4 4\n")
        self.import_("--dir", self.path("q0"), output="m0.sol")
        self.import_("--dir", self.path("q1"), output="m1.sol")
        parts = [self.path("m0.sol"), self.path("m1.sol")]
        refused(["solutions", "merge", *parts, "-o", parts[0], "--allow-missing"], parts[0])
        run("solutions", "merge", *parts, "-o", self.path("m.sol"), "--allow-missing")

    # --- issue 20: strict ε, header counts, packed instances, large fronts, FIFOs ----------------

    def test_import_refuses_an_epsilon_that_is_not_a_non_negative_decimal(self):
        d = self.front_dir({"0.txt": "1 9\n"})
        for bad in ("abc", "-1", "nan", "inf", "1e-3", ""):
            r = self.import_("--dir", d, "--epsilon", bad, check=False, output="eps.sol")
            self.assert_one_line_error(r, "--epsilon", "invalid epsilon", code=2)
            self.assertFalse(os.path.exists(self.path("eps.sol")))
        self.import_("--dir", d, "--epsilon", "0.05")
        self.assertEqual(self.inspect()["epsilon"], "0.05")

    def test_verify_refuses_header_counts_other_than_the_instance(self):
        d = self.front_dir({"0.txt": "1 9\n"})
        self.import_("--dir", d)
        data = bytearray(mosbtest.read(self.path("out.sol")))
        n = mosbtest.header(data)["vertex_count"]
        mosbtest.set_header(data, vertex_count=n + 1)
        mosbtest.reseal(data)
        self.write("forged.sol", bytes(data))
        r = run("solutions", "verify", self.path("forged.sol"), "--instance", self.grid, check=False)
        line = self.assert_one_line_error(r, self.path("forged.sol"), self.grid,
                                          "n = %d" % (n + 1), "n = %d" % n)
        self.assertIn("header", line)
        # eval: the same digest, other counts; the message names both files.
        r = run("eval", "--reference", self.path("out.sol"), "--solutions", self.path("forged.sol"),
                check=False)
        self.assert_one_line_error(r, self.path("out.sol"), self.path("forged.sol"), "header")

    def test_solutions_commands_read_packed_instances(self):
        packed = self.path("grid.packed.mosb")
        run("pack", self.grid, "-o", packed)
        d = self.front_dir({"0.txt": "1 9\n2 7\n"})
        run("solutions", "import", "--instance", packed, "--view", "Grid_2", "--queries", "s",
            "--dir", d, "-o", self.path("p.sol"))
        self.assertIn("OK", run("solutions", "verify", self.path("p.sol"), "--instance",
                                packed).stdout)
        run("solutions", "export", self.path("p.sol"), "--instance", packed, "--json-log",
            self.path("p.json"))
        self.assertTrue(os.path.exists(self.path("p.json")))

    def test_text_output_escapes_what_files_and_names_carry(self):
        # A solver name from a forged file, and a file name, may hold a newline or an escape
        # sequence: printed escaped, so that neither fakes a line nor drives the terminal.
        name = "fake\nOK   forged.sol\x1b[2J"
        out = self.path("odd\nname.sol")
        mosbtest.write_solution(out, self.grid, "Grid_2", "0 solved 1,9\n", "0", "s",
                                env=dict(os.environ, MOSB_TEST_SOLVER_NAME=name))
        text = run("solutions", "inspect", out).stdout
        self.assertNotIn("\x1b", text)
        self.assertIn("solver fake\\nOK   forged.sol\\x1b[2J", text)
        self.assertIn("odd\\nname.sol: solutions of instance", text)
        self.assertEqual(len(text.splitlines()), 7, text)
        verified = run("solutions", "verify", out).stdout
        self.assertEqual(verified.count("\n"), 1, verified)
        r = run("verify", self.path("missing\n\x1b[31mfile.mosb"), check=False)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stdout.count("\n"), 1, r.stdout)
        self.assertIn("missing\\n\\x1b[31mfile.mosb: cannot open", r.stdout)
        r = run("solutions", "inspect", self.path("missing\n\x1b[31mfile.sol"), check=False)
        self.assert_one_line_error(r, "missing\\n\\x1b[31mfile.sol")


if __name__ == "__main__":
    mosbtest.main()
