#!/usr/bin/python3
"""End-to-end tests of `mosb experiment run|status` (spec/EXPERIMENT.md) and `mosb solutions
reference` (spec/EVALUATION.md §6.1): a store of two 30x30 Grid views, a 1,000-vertex NetMaker and
(with arena2 in the shared data) a GUARDS map, solved by the example NAMOA* and BOA* and by a
third solver that is wrong on one query on purpose.

    MOSB=build/release/tools/mosb EXAMPLES=build/release/examples /usr/bin/python3 tests/cli/test_experiment.py
"""

import csv
import io
import json
import os
import re
import signal
import subprocess
import time
import unittest

import mosbtest
import test_report
import test_slurm
from mosbtest import DATA, MOSB, CliTest, read, run, setUpModule  # noqa: F401

EXAMPLES = os.path.abspath(os.environ.get("EXAMPLES", ""))
ARENA = os.path.join(DATA, "movingai", "arena2.map")
TEMPLATE = "%s {instance} --view {view} --query {source} {target} --protocol"


class ExperimentFixture(CliTest):
    """The store, the three solvers and the experiment file every test here starts from."""

    def setUp(self):
        super().setUp()
        if not os.path.isfile(os.path.join(EXAMPLES, "namoa")):
            raise mosbtest.missing("EXAMPLES (the example solvers' directory) is not set")
        self.ok("generate", "grid", "--width", "30", "--height", "30", "--objectives", "3", "-o",
                self.path("grid.mosb"))
        self.ok("generate", "netmaker", "--vertices", "1000", "--amin", "1", "--amax", "10",
                "--locality", "20", "-o", self.path("netmaker.mosb"))
        instances = ["grid.mosb", "netmaker.mosb"]
        self.benchmarks = ["Grid_2", "Grid_3", "NetMaker-1k_3"]
        self.bi_objective = ["Grid_2"]
        if os.path.exists(ARENA):
            self.write("guards.txt", "120 100 25\n")
            self.ok("convert", "guards", "--map", ARENA, "--guards", self.path("guards.txt"),
                    "-o", self.path("arena.mosb"))
            instances.append("arena.mosb")
            self.benchmarks.append("Games-GUARDS_2")
            self.bi_objective.append("Games-GUARDS_2")
        for instance in instances:
            self.ok("queries", "generate", self.path(instance), "--set", "default", "--count",
                    "5", "--seed", "3", "--in-place", "--replace")
        self.ok("store", "init", self.path("store"))
        self.ok("store", "add", self.path("store"), *[self.path(i) for i in instances], "--pack")
        # The wrong solver: NAMOA* with the last vector of the grid's query 2 dropped, and slow
        # (0.3 s a query), so that a run can be killed in the middle of its cells.
        source, target = mosbtest.mosb_reader.open_instance(
            self.path("grid.mosb")).queries()["default"][2]
        self.wrong_query = 2
        self.write("wrong.sh", "#!/bin/sh\nsleep 0.3\n"
                   "if [ \"$5 $6\" = \"%d %d\" ]; then %s \"$@\" | sed '$d'; exit 0; fi\n"
                   "exec %s \"$@\"\n" % (source, target, os.path.join(EXAMPLES, "namoa"),
                                         os.path.join(EXAMPLES, "namoa")))
        os.chmod(self.path("wrong.sh"), 0o755)
        self.experiment = self.write_experiment("exp.toml")

    def write_experiment(self, name, limits='{ time = "30s", memory = "2G" }', extra=""):
        text = ('name = "ci"\nstore = "%s"\nbenchmarks = %s\nlimits = %s\n'
                '[[solver]]\nname = "namoa"\ntemplate = "%s"\n'
                '[[solver]]\nname = "boa"\ntemplate = "%s"\nbenchmarks = %s\n'
                '[[solver]]\nname = "wrong"\ntemplate = "%s"\n'
                '[reference]\nsolvers = ["namoa", "boa", "wrong"]\n%s'
                % (self.path("store"), json.dumps(self.benchmarks), limits,
                   TEMPLATE % os.path.join(EXAMPLES, "namoa"),
                   TEMPLATE % os.path.join(EXAMPLES, "boa_star"), json.dumps(self.bi_objective),
                   TEMPLATE % self.path("wrong.sh"), extra))
        return self.write(name, text)

    def cells(self, results):
        lines = read(os.path.join(results, "MANIFEST")).decode().splitlines()
        self.assertEqual(json.loads(lines[0])["format"], "mosb-experiment-results")
        return {r["file"]: r for r in map(json.loads, lines[1:])}

    def run_experiment(self, results, *more):
        return json.loads(self.ok("experiment", "run", self.experiment, "-o", results, "--json",
                                  *more).stdout)

    def expected_cells(self):
        per_solver = {"namoa": len(self.benchmarks), "boa": len(self.bi_objective),
                      "wrong": len(self.benchmarks)}
        return sum(per_solver.values())

    def same_fronts(self, expected, actual):
        """Every cell of `expected` in `actual`, with the same fronts and statuses."""
        listed = self.cells(actual)
        self.assertEqual(sorted(listed), sorted(self.cells(expected)))
        for f, record in listed.items():
            self.ok("solutions", "compare", os.path.join(expected, f), os.path.join(actual, f))
            self.assertEqual(record["counts"], self.cells(expected)[f]["counts"], f)
        status = json.loads(self.ok("experiment", "status", actual, "--json").stdout)
        self.assertTrue(status["complete"])


class ExperimentTest(ExperimentFixture):
    def test_slurm_array_run_by_hand_merges_into_the_local_results(self):
        """The array's script run task by task here (as SLURM would, SLURM_ARRAY_TASK_ID set),
        then --resume merges the tasks' cells into RESULTS: the local run's fronts."""
        local = self.path("local")
        self.run_experiment(local)
        array, results = self.path("array"), self.path("results")
        r = self.ok("experiment", "run", self.experiment, "-o", results, "--slurm", array,
                    "--queries-per-task", "10", "--throttle", "2")
        cells = self.expected_cells()
        tasks = (cells + 1) // 2  # cells of 5 queries, two a task
        self.assertIn("%d tasks of the %d cells" % (tasks, cells), r.stdout)
        self.assertIn("submit it: sbatch --parsable %s/run.sbatch" % array, r.stdout)
        script = read(os.path.join(array, "run.sbatch")).decode()
        self.assertIn("#SBATCH --array=1-%d%%2\n" % tasks, script)
        self.assertIn('experiment run %s --queries-per-task 10' % self.experiment, script)
        self.assertIn('--task "$shard"/%d -o %s/task-"$shard"' % (tasks, array), script)
        status = json.loads(self.ok("experiment", "run", self.experiment, "-o", results,
                                    "--slurm", array, "--status", "--json").stdout)
        self.assertEqual([t["file"] for t in status["task_states"]], ["missing"] * tasks)
        for task in range(1, tasks):  # the last task left out: resume must say so
            subprocess.run(["sh", os.path.join(array, "run.sbatch")], check=True,
                           env=dict(os.environ, SLURM_ARRAY_TASK_ID=str(task)),
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        r = json.loads(self.ok("experiment", "run", self.experiment, "-o", results, "--slurm",
                               array, "--resume", "--json").stdout)
        self.assertEqual(r["resubmit"], str(tasks))
        self.assertEqual(r["merged"], 2 * (tasks - 1))
        subprocess.run(["sh", os.path.join(array, "run.sbatch")], check=True,
                       env=dict(os.environ, SLURM_ARRAY_TASK_ID=str(tasks)),
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        status = json.loads(self.ok("experiment", "run", self.experiment, "-o", results,
                                    "--slurm", array, "--status", "--json").stdout)
        self.assertTrue(status["complete"])
        text = self.ok("experiment", "run", self.experiment, "-o", results, "--slurm", array,
                       "--resume").stdout
        self.assertIn("merged %d cells" % (cells - 2 * (tasks - 1)), text)
        self.assertIn("nothing to resubmit", text)
        self.same_fronts(local, results)
        self.assertEqual(self.run_experiment(results)["ran"], 0)  # nothing left to run here
        # Refusals, one line each: a task count the file no longer makes, the array given to
        # `mosb run` (its run.json is of another kind: bad input), an array option without
        # --slurm.
        for args, code in ((["experiment", "run", self.experiment, "-o", self.path("t"), "--task",
                             "1/99", "--queries-per-task", "10"], 2),
                           (["run", "--slurm", array, "--status"], 1),
                           (["experiment", "run", self.experiment, "-o", results, "--submit"], 2)):
            r = run(*args)
            self.assertEqual(r.returncode, code, (args, r.stderr))
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("(made by mosb experiment run)",
                      run("run", "--slurm", array, "--status").stderr)

    def test_killed_and_rerun_is_the_uninterrupted_run(self):
        full = self.path("full")
        summary = self.run_experiment(full)
        self.assertEqual(summary["cells"], self.expected_cells())
        self.assertEqual(summary["ran"], summary["cells"])
        self.assertEqual(len(self.cells(full)), summary["cells"])

        part = self.path("part")
        p = subprocess.Popen([MOSB, "experiment", "run", self.experiment, "-o", part],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        # Killed once every namoa and boa cell is finished and the slow wrong solver has begun.
        first = len(self.benchmarks) + len(self.bi_objective)
        deadline = time.time() + 120
        while time.time() < deadline:
            listed = self.cells(part) if os.path.exists(os.path.join(part, "MANIFEST")) else {}
            journals = [f for f in os.listdir(os.path.join(part, "cells", "wrong"))] \
                if os.path.isdir(os.path.join(part, "cells", "wrong")) else []
            if len(listed) >= first and any(f.endswith(".journal") for f in journals):
                break
            time.sleep(0.05)
        p.send_signal(signal.SIGKILL)
        p.wait()
        finished = self.cells(part)
        self.assertGreaterEqual(len(finished), first)
        self.assertLess(len(finished), summary["cells"])  # killed midway
        status = json.loads(self.ok("experiment", "status", part, "--json").stdout)
        states = [c["state"] for c in status["cells"]]
        self.assertEqual(states.count("done"), len(finished))
        self.assertIn("stopped", states)  # the killed cell's journal is kept
        self.assertFalse(status["complete"])
        mtimes = {f: os.stat(os.path.join(part, f)).st_mtime_ns for f in finished}
        journaled = sum(c["journaled"] for c in status["cells"] if c["state"] == "stopped")
        text = self.ok("experiment", "status", part).stdout
        self.assertIn("`mosb experiment run %s -o %s` runs the missing and stopped ones"
                      % (self.experiment, part), text)  # the file the run read, to copy

        again = self.run_experiment(part)
        self.assertEqual(again["skipped"], len(finished))
        # The stopped cell resumed from its journal, and the summary says so.
        self.assertEqual((again["resumed"], again["queries_from_journal"]),
                         (1 if journaled else 0, journaled))
        self.assertEqual(again["ran"], summary["cells"] - len(finished))
        for f, mtime in mtimes.items():  # no finished cell ran again
            self.assertEqual(os.stat(os.path.join(part, f)).st_mtime_ns, mtime, f)
        listed = self.cells(part)
        self.assertEqual(sorted(listed), sorted(self.cells(full)))
        for f, record in listed.items():
            self.ok("solutions", "compare", os.path.join(full, f), os.path.join(part, f))
            self.assertEqual(record["counts"], self.cells(full)[f]["counts"], f)
        status = json.loads(self.ok("experiment", "status", part, "--json").stdout)
        self.assertTrue(status["complete"])
        # A third run runs nothing.
        self.assertEqual(self.run_experiment(part)["ran"], 0)

        # The reference lists the wrong solver's query, and only it.
        r = json.loads(self.ok("solutions", "reference", part, "--solvers", "namoa,boa,wrong",
                               "-o", self.path("refs"), "--json").stdout)
        grid = [x for x in r["references"] if x["file"].endswith("grid.Grid_2.sol")][0]
        self.assertEqual([(d["query"], d["solvers"]) for d in grid["disagreements"]],
                         [(self.wrong_query, ["namoa", "wrong"])])
        self.assertEqual(grid["agreed"], 4)
        for x in r["references"]:  # the grid's other view has the same queries: the same query
            wrong = [self.wrong_query] if "/grid." in x["file"] else []
            self.assertEqual([d["query"] for d in x["disagreements"]], wrong, x["file"])
        info = self.ok("solutions", "inspect", self.path("refs", "grid.Grid_2.sol")).stdout
        self.assertIn("parameter disagreement = %d" % self.wrong_query, info)
        self.assertIn("parameter agreed.1 = 0-1,3-4", info)  # boa agreed everywhere but query 2
        text = self.ok("solutions", "reference", part, "--solvers", "namoa,wrong", "--prefer",
                       "namoa", "-o", self.path("refs2")).stdout
        self.assertIn("query %d: namoa and wrong disagree" % self.wrong_query, text)
        self.assertIn("kept namoa's (--prefer)", text)

        # The report of the results: every benchmark and solver named.
        out = self.path("csv")
        self.ok("report", part, "--reference", self.path("refs"), "-o", self.path("r.html"),
                "--csv", out)
        # Table 1: the references' fronts with the first reference solver's statistics.
        suite = {r["benchmark"]: r for r in csv.DictReader(
            io.StringIO(read(os.path.join(out, "suite.csv")).decode()))}
        for name in self.benchmarks:
            # The solvers that gave its fronts: boa runs the bi-objective benchmarks only.
            self.assertEqual(suite[name]["fronts_of"], "reference (namoa, boa, wrong)"
                             if name in self.bi_objective else "reference (namoa, wrong)")
            self.assertEqual(suite[name]["statistics_of"], "namoa")
            self.assertGreater(float(suite[name]["runtime_max"]), 0)
            self.assertGreater(float(suite[name]["memory_max"]), 0)
        # Where every query agreed, the reference's statistics are namoa's, query for query.
        for name in os.listdir(self.path("refs")):
            if name.startswith("grid."):
                continue  # the wrong query is left out there, with its statistics
            ref, own = (json.loads(self.ok("solutions", "inspect", f, "--json").stdout)
                        for f in (self.path("refs", name), os.path.join(part, "cells", "namoa",
                                                                        name)))
            self.assertEqual(ref["parameters"]["statistics"], "namoa")
            self.assertEqual(ref["statistics"], own["statistics"], name)
        comparison = read(os.path.join(out, "comparison.csv")).decode()
        for name in self.benchmarks:
            self.assertIn(name, comparison)
        # One row per benchmark and solver, the solvers in the experiment file's order.
        rows = [line.split(",") for line in comparison.splitlines()[1:]]
        grid = [r[2] for r in rows if r[1] == "Grid_2"]
        self.assertEqual(grid, ["namoa", "boa", "wrong"])
        page = read(self.path("r.html")).decode()
        for name in self.benchmarks + ["namoa", "boa", "wrong"]:
            self.assertIn(name, page)
        self.check_solver_table(read(os.path.join(out, "solvers.csv")).decode())
        self.check_page_in_chromium(self.path("r.html"))
        self.check_eval(part, self.path("refs"))

    def solver_pairs(self):
        return ({(b, s) for b in self.benchmarks for s in ("namoa", "wrong")}
                | {(b, "boa") for b in self.bi_objective})

    def check_solver_table(self, text):
        """The paper's Table 5 as CSV: one row per benchmark and solver."""
        rows = list(csv.DictReader(io.StringIO(text)))
        self.assertEqual({(r["benchmark"], r["solver"]) for r in rows}, self.solver_pairs())
        for r in rows:
            self.assertEqual((r["queries"], r["completed"], r["timeout"], r["memory_limit"]),
                             ("5", "5", "0", "0"), r)
            self.assertGreater(float(r["runtime_max"]), 0, r)
            self.assertLessEqual(float(r["runtime_median"]), float(r["runtime_max"]), r)

    def check_page_in_chromium(self, html):
        """The report's solver table as headless Chromium shows it (script off, so the table is
        the page's own, not what a script made of it): every benchmark and solver named."""
        if test_report.CHROMIUM is None:
            raise mosbtest.missing("chromium")
        copy = self.path("noscript.html")
        with open(copy, "w", encoding="utf-8") as f:
            f.write(re.sub(r"<script>.*?</script>", "", read(html).decode(), flags=re.S))
        r = test_report.chromium("--dump-dom", "file://" + copy)
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        table = test_report.parse(r.stdout).tables["solvers-table"]
        headings = [c[1] for c in table[0]]
        for column in ("benchmark", "solver", "completed", "timeout", "memory limit",
                       "median runtime [s]", "max runtime [s]", "covered at ε = 0.01"):
            self.assertIn(column, headings)
        # Every solver here reports its runtime, so that is the one shown, and said.
        self.assertIn("runtime as each solver reported it", r.stdout)
        shown = {(row[headings.index("benchmark")][1], row[headings.index("solver")][1])
                 for row in table[1:]}
        self.assertEqual(shown, self.solver_pairs())

    def check_eval(self, results, refs):
        """`mosb eval RESULTS --reference REFS`: the same table, with the ε-coverage."""
        table = json.loads(self.ok("eval", results, "--reference", refs, "--json").stdout)
        rows = {(r["benchmark"], r["solver"]): r for r in table["rows"]}
        self.assertEqual(set(rows), self.solver_pairs())
        for (benchmark, solver), r in rows.items():
            # The grid's query 2 is a disagreement: left out of its references.
            evaluated = 4 if benchmark.startswith("Grid") else 5
            self.assertEqual(r["evaluated"], evaluated, (benchmark, solver))
            self.assertEqual(r["covered@0.01"], evaluated, (benchmark, solver))
            self.assertEqual(r["completed"], 5)
        text = self.ok("eval", results, "--reference", refs, "--csv").stdout
        self.check_solver_table(text)
        # The runtime kind is the user's choice, named in the caption; both are in the files.
        by_kind = {kind: json.loads(self.ok("eval", results, "--runtime", kind, "--json").stdout)
                   for kind in ("wall", "reported")}
        self.assertIn("wall-clock runtime", by_kind["wall"]["caption"])
        self.assertIn("runtime as each solver reported it", by_kind["reported"]["caption"])
        self.assertNotEqual([r["runtime_median"] for r in by_kind["wall"]["rows"]],
                            [r["runtime_median"] for r in by_kind["reported"]["rows"]])
        common = json.loads(self.ok("eval", results, "--common-queries", "--json").stdout)
        grid = [r for r in common["rows"] if r["benchmark"] == "Grid_2"]
        self.assertEqual([r["solver"] for r in grid], ["namoa", "boa", "wrong"])
        self.assertEqual({r["common"] for r in grid}, {5})
        self.assertIn("covered@0.05", text.splitlines()[0])
        latex = self.ok("eval", results, "--latex").stdout
        self.assertIn("\\toprule", latex)
        self.assertNotIn("covered", latex)  # no references, no coverage
        plain = self.ok("eval", results).stdout
        for benchmark, solver in self.solver_pairs():
            self.assertIn(benchmark, plain)
            self.assertIn(solver, plain)
        for bad, code in ((["eval", results, "--solutions", os.path.join(results, "MANIFEST")], 1),
                          (["eval", "--reference", refs, "--solutions",
                            os.path.join(refs, os.listdir(refs)[0])], 2)):
            r = run(*bad)
            self.assertEqual(r.returncode, code, r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)

    def test_changed_limits_or_executable_refuse_the_cells_they_touch(self):
        results = self.path("r")
        self.run_experiment(results)
        before = read(os.path.join(results, "MANIFEST"))
        self.experiment = self.write_experiment("exp.toml", limits='{ time = "31s" }')
        r = run("experiment", "run", self.experiment, "-o", results)
        self.assertNotEqual(r.returncode, 0)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("namoa/grid/Grid_2: the limits changed", r.stderr)
        self.assertIn("wrong/netmaker/NetMaker-1k_3", r.stderr)
        self.assertEqual(read(os.path.join(results, "MANIFEST")), before)
        # Other limits for one benchmark ([[benchmark_limits]]) touch its cells only.
        grid3 = '[[benchmark_limits]]\nbenchmarks = ["Grid_3"]\ntime = 31\n'
        self.experiment = self.write_experiment("exp.toml", extra=grid3)
        r = run("experiment", "run", self.experiment, "-o", results)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("namoa/grid/Grid_3: the limits changed (time=30s memory=2147483648B, now "
                      "time=31s memory=2147483648B)", r.stderr)
        self.assertNotIn("Grid_2:", r.stderr)
        self.assertEqual(read(os.path.join(results, "MANIFEST")), before)
        fresh = self.path("r-grid3")
        self.run_experiment(fresh)
        limits = {f: c["limits"] for f, c in self.cells(fresh).items()}
        self.assertEqual(limits["cells/namoa/grid.Grid_3.sol"], "time=31s memory=2147483648B")
        self.assertEqual(limits["cells/namoa/grid.Grid_2.sol"], "time=30s memory=2147483648B")
        self.experiment = self.write_experiment("exp.toml")
        with open(self.path("wrong.sh"), "a") as f:
            f.write("# changed\n")
        r = run("experiment", "run", self.experiment, "-o", results)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("wrong/grid/Grid_2: the solver's executable changed", r.stderr)
        self.assertNotIn("namoa/", r.stderr)

    def test_a_bad_file_is_one_line_naming_file_line_and_key(self):
        cases = [
            ('name = "x"\nstore = "%s"\ntypo = 1\n' % self.path("store"),
             ":3:1: key 'typo': unknown key"),
            ('name = "x"\nstore = "%s"\nlimits = { time = "1 hour" }\n'
             '[[solver]]\nname = "a"\ntemplate = "%s"\n' % (self.path("store"), self.path("wrong.sh")),
             ":3:19: key 'limits.time': '1 hour' is not a duration"),
            ('name = "x"\nstore = "%s"\nbenchmarks = ["Grid_2",\n  "Nope_*"]\n'
             '[[solver]]\nname = "a"\ntemplate = "%s"\n' % (self.path("store"), self.path("wrong.sh")),
             ":4:3: key 'benchmarks': 'Nope_*' matches no view or benchmark"),
            ('name = "x"\nstore = "%s"\n[[solver]]\nname = "apex"\nprofile = "apex"\n'
             'executable = "/nonexistent/multiobj"\noptions = { algorithm = "Apex" }\n'
             % self.path("store"),
             ":3:1: key 'solver[1]': solver 'apex': executable /nonexistent/multiobj: "
             "no such executable"),
            ('name = "x"\nstore = "%s"\n[[solver]]\nname = "apex"\nprofile = "apex"\n'
             'executable = "/bin/true"\noptions = { algorithm = "Dijkstra" }\n'
             % self.path("store"),
             ":3:1: key 'solver[1]': solver 'apex': option algorithm=Dijkstra: algorithm is one of"),
            ('name = "x"\nstore = "%s"\n[[solver]]\nname = "tmda"\nprofile = "tmda"\n'
             'executable = "/bin/true"\nepsilon = 0.1\n' % self.path("store"),
             ":3:1: key 'solver[1]': solver 'tmda': epsilon 0.1: profile tmda gives its solver "
             "no epsilon"),
            ('name = "x"\nstore = "%s"\n[[solver]]\nname = "a"\ntempalte = "x"\n' % self.path("store"),
             ":5:1: key 'solver[1].tempalte': unknown key"),
            ('name = "x"\nstore = "%s"\n[[solver]]\nname = "a"\ntemplate = "%s"\n'
             '[reference]\nsolvers = ["b"]\n' % (self.path("store"), self.path("wrong.sh")),
             ":7:11: key 'reference.solvers': 'b' is none of the [[solver]] names"),
            ('name = "x"\nstore = [\n', ":2:11: "),
            ('name = "x"\nstore = "%s"\n[[solver]]\nname = "a"\ntemplate = "%s"\n'
             '[[benchmark_limits]]\nbenchmarks = ["Grid_2",\n "Nope"]\nmemory = "1G"\n'
             % (self.path("store"), self.path("wrong.sh")),
             ":8:2: key 'benchmark_limits[1].benchmarks': 'Nope' matches no cell of the experiment"),
            ('name = "x"\nstore = "%s"\n[[solver]]\nname = "a"\ntemplate = "%s"\n'
             '[[benchmark_limits]]\nbenchmarks = ["Grid_2"]\nmem = "1G"\n'
             % (self.path("store"), self.path("wrong.sh")),
             ":8:1: key 'benchmark_limits[1].mem': unknown key"),
        ]
        for text, expected in cases:
            with self.subTest(expected=expected):
                path = self.write("bad.toml", text)
                r = run("experiment", "run", path, "-o", self.path("never"))
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
                self.assertIn(path + expected, r.stderr)
                self.assertFalse(os.path.exists(self.path("never")))

    def test_a_narrowed_run_is_recorded_and_its_idle_solvers_said(self):
        results = self.path("narrow")
        r = run("experiment", "run", self.experiment, "-o", results, "--benchmarks",
                "NetMaker-1k_3", "--time-limit", "20s", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("mosb: note: solver 'boa' runs no cell: its benchmarks match none of those "
                      "run", r.stderr)
        self.assertEqual(json.loads(r.stdout)["cells"], 2)  # namoa and wrong on NetMaker-1k_3
        plan = json.loads(read(os.path.join(results, "experiment.json")))
        self.assertEqual(plan["arguments"], ["--benchmarks", "NetMaker-1k_3", "--time-limit", "20s"])
        self.assertEqual({c["limits"] for c in self.cells(results).values()},
                         {"time=20s memory=2147483648B"})

    def test_float_costs_for_an_integer_solver_are_refused_before_any_cell_runs(self):
        """A cell whose objectives the solver cannot take is refused at planning (exit 2,
        nothing made), not when its turn comes after other cells ran; `scale` makes it run."""
        graphml = os.path.join(DATA, "roadmap-graphml", "roadmap.xml")
        if not os.path.exists(graphml):
            raise mosbtest.missing("shared/data/roadmap-graphml")
        roadmap = self.path("roadmap.mosb")
        self.ok("convert", "roadmap", "--graphml", graphml, "--weight", "--clearance", "none",
                "--view", "Roadmap_2=length,weight", "-o", roadmap)
        self.ok("queries", "generate", roadmap, "--set", "default", "--count", "2", "--in-place")
        text = ('name = "x"\ninstances = ["%s", "%s"]\n[[solver]]\nname = "apex"\n'
                'profile = "apex"\nexecutable = "/bin/true"\n' % (self.path("grid.mosb"), roadmap))
        r = run("experiment", "run", self.write("float.toml", text), "-o", self.path("never"))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("float.toml:3:1: key 'solver[1]': solver 'apex', cell roadmap/Roadmap_2: "
                      "objective 'length' holds float costs and profile apex's solver reads "
                      "integers only: give a scale K", r.stderr)
        self.assertFalse(os.path.exists(self.path("never")))
        # With a scale, the cells are planned (a scale where no cost is a float is refused).
        scaled = self.write("scaled.toml", text + "scale = 1000\n")
        r = run("experiment", "run", scaled, "-o", self.path("never"))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("cell grid/Grid_2: scale: no objective of the run holds float costs",
                      r.stderr)
        scaled = self.write("scaled.toml", text.replace('"%s", ' % self.path("grid.mosb"), "")
                            + "scale = 1000\n")
        r = run("experiment", "run", scaled, "-o", self.path("scaled"), "--time-limit", "5s")
        # The cells ran; /bin/true writes no front, so no query completed: exit 3, the reason said.
        self.assertEqual(r.returncode, 3, r.stderr)
        self.assertIn("mosb: no query completed (2 failed); most often, 2 of 2: ", r.stderr)

    def test_an_experiment_file_that_is_no_regular_file_is_refused_at_once(self):
        # A FIFO would block the read for ever, /dev/zero never end.
        fifo = self.path("exp.fifo")
        os.mkfifo(fifo)
        for path in (fifo, "/dev/zero"):
            with self.subTest(path=path):
                r = run("experiment", "run", path, "-o", self.path("never"), timeout=60)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
                self.assertIn(path + ": not a regular file", r.stderr)
                self.assertFalse(os.path.exists(self.path("never")))
        # Past the 16 MiB cap (a sparse file of 1 TiB): refused from its size, nothing read.
        huge = self.path("huge.toml")
        with open(huge, "w") as f:
            f.truncate(1 << 40)
        r = run("experiment", "run", huge, "-o", self.path("never"), timeout=60)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn(huge + ": more than 16777216 bytes", r.stderr)
        self.assertFalse(os.path.exists(self.path("never")))

    def test_a_directory_it_did_not_make_is_never_written(self):
        # The user's files: refused before anything (the lock included) is made there.
        mine = self.path("mine")
        self.write("mine/notes.txt", "mine\n")
        r = run("experiment", "run", self.experiment, "-o", mine)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("not empty and not an experiment's results directory", r.stderr)
        self.assertEqual(os.listdir(mine), ["notes.txt"])
        os.symlink(mine, self.path("link"))
        r = run("experiment", "run", self.experiment, "-o", self.path("link"))
        self.assertIn("a symbolic link", r.stderr)
        # A link planted where a solver's cells go is not followed.
        results = self.path("planted")
        os.makedirs(os.path.join(results, "cells"))
        self.write("planted/experiment.json",
                   json.dumps({"format": "mosb-experiment-plan", "name": "ci"}))
        os.symlink(self.path("elsewhere"), os.path.join(results, "cells", "namoa"))
        os.makedirs(self.path("elsewhere"))
        r = run("experiment", "run", self.experiment, "-o", results)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("cells/namoa: not a directory of the results", r.stderr)
        self.assertEqual(os.listdir(self.path("elsewhere")), [])

    def test_published_solvers_by_profile_with_an_epsilon_sweep(self):
        """The paper's protocol as one file: an exact solver by template and one by profile
        (cross-validated), an approximate one by profile at two ε; stand-ins of the published
        programs (standin_solvers.py)."""
        standin = os.path.join(os.path.dirname(os.path.abspath(__file__)), "standin_solvers.py")
        bins = {}
        for solver in ("apex", "mohs"):
            bins[solver] = self.write("bin/" + solver, "#!/bin/sh\nexec /usr/bin/python3 %s %s "
                                      "\"$@\"\n" % (standin, solver))
            os.chmod(bins[solver], 0o755)
        env = dict(os.environ, MOSB_EXPORT_CACHE=self.path("cache"))
        # A grid small enough for the stand-ins' plain Python search.
        self.ok("generate", "grid", "--width", "6", "--height", "6", "--objectives", "3", "-o",
                self.path("small-bare.mosb"))
        self.ok("queries", "generate", self.path("small-bare.mosb"), "--set", "default",
                "--count", "5", "--seed", "3", "--replace", "-o", self.path("small.mosb"))
        text = ('name = "paper"\ninstances = ["%s"]\nbenchmarks = ["Grid_2", "Grid_3"]\n'
                'limits = { time = 60, memory = "2g" }\n'
                '[[solver]]\nname = "namoa"\ntemplate = "%s"\n'
                '[[solver]]\nname = "ltmoa"\nprofile = "mohs"\nexecutable = "/nonexistent"\n'
                'options = { algorithm = "LTMOA" }\n'
                '[[solver]]\nname = "apex"\nprofile = "apex"\nexecutable = "${MOSB_TEST_APEX}"\n'
                'options = { merge = "RANDOM" }\nepsilon = [0.01, "0.1"]\n'
                '[reference]\nsolvers = ["namoa", "ltmoa"]\n'
                % (self.path("small.mosb"), TEMPLATE % os.path.join(EXAMPLES, "namoa")))
        exp = self.write("paper.toml", text)
        results = self.path("paper")
        # A machine's path from its environment.
        env.pop("MOSB_TEST_APEX", None)
        r = run("experiment", "run", exp, "-o", results, env=env)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("paper.toml:13:1: key 'solver[3]': solver 'apex-eps0.01': executable "
                      "${MOSB_TEST_APEX}: the environment variable MOSB_TEST_APEX is not set",
                      r.stderr)
        env["MOSB_TEST_APEX"] = bins["apex"]
        # The file's executable is this machine's; --executable gives another's.
        r = run("experiment", "run", exp, "-o", results, env=env)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("solver 'ltmoa': executable /nonexistent: no such executable", r.stderr)
        self.assertFalse(os.path.exists(results))
        argv = ["experiment", "run", exp, "-o", results, "--executable", "ltmoa=" + bins["mohs"],
                "--json"]
        r = run(*argv, env=env)
        self.assertEqual(r.returncode, 0, r.stderr)
        summary = json.loads(r.stdout)
        self.assertEqual((summary["cells"], summary["ran"]), (8, 8))  # 2 views x 4 solvers
        self.assertEqual(summary["statuses"]["solved"], 40, r.stderr)
        cells = self.cells(results)
        self.assertEqual(sorted({f.split("/")[1] for f in cells}),
                         ["apex-eps0.01", "apex-eps0.1", "ltmoa", "namoa"])
        sol = os.path.join(results, "cells", "apex-eps0.1", "small.Grid_3.sol")
        info = json.loads(self.ok("solutions", "inspect", "--json", sol).stdout)
        self.assertEqual(info["solver"], "apex-eps0.1")  # the experiment's name
        self.assertEqual(info["epsilon"], "0.1")
        self.assertEqual(info["parameters"]["profile.option.merge"], "RANDOM")
        self.assertEqual(info["parameters"]["profile.name"], "apex")
        # The exact solvers agree on every query; the approximate ones are covered at their ε.
        refs = json.loads(self.ok("solutions", "reference", results, "--solvers", "namoa,ltmoa",
                                  "-o", self.path("refs"), "--json").stdout)
        for x in refs["references"]:
            self.assertEqual((x["agreed"], x["disagreements"]), (5, []), x["file"])
        # A name that matches no file (a typo) and an approximate solver are refused.
        for solvers, expected in (("namoa,ltmao", "solver 'ltmao' has no file among the inputs"),
                                  ("namoa,apex-eps0.01",
                                   "solver 'apex-eps0.01' claims epsilon 0.01; a reference "
                                   "takes exact solvers (epsilon 0) only")):
            r = run("solutions", "reference", results, "--solvers", solvers, "-o",
                    self.path("bad-refs"))
            self.assertNotEqual(r.returncode, 0, r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertIn(expected, r.stderr)
            self.assertFalse(os.path.exists(self.path("bad-refs")))
        # Its outputs never replace its inputs.
        namoa = os.path.join(results, "cells", "namoa")
        before = read(os.path.join(namoa, "small.Grid_2.sol"))
        r = run("solutions", "reference", os.path.join(namoa, "small.Grid_2.sol"),
                os.path.join(results, "cells", "ltmoa", "small.Grid_2.sol"), "--solvers",
                "namoa,ltmoa", "-o", namoa)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("is one of the inputs", r.stderr)
        self.assertEqual(read(os.path.join(namoa, "small.Grid_2.sol")), before)
        # A solver run by hand on the experiment's instance joins its table.
        self.ok("run", self.path("small.mosb"), "--view", "Grid_2", "--solver",
                TEMPLATE % os.path.join(EXAMPLES, "boa_star"), "--solver-name", "by-hand",
                "-o", self.path("by-hand.sol"))
        table = json.loads(self.ok("eval", results, "--reference", self.path("refs"),
                                   "--solutions", self.path("by-hand.sol"), "--json").stdout)
        for row in table["rows"]:
            self.assertEqual(row["covered@0.1"], 5, row)
        self.assertIn(("Grid_2", "by-hand"), {(r["benchmark"], r["solver"]) for r in table["rows"]})
        # A rerun runs nothing; another merge strategy is another solver: its cells are refused.
        self.assertEqual(json.loads(run(*argv, env=env).stdout)["ran"], 0)
        self.write("paper.toml", text.replace('"RANDOM"', '"MORE_SLACK"'))
        r = run(*argv, env=env)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("apex-eps0.01/small/Grid_2: the solver's command changed", r.stderr)
        self.assertNotIn("ltmoa/", r.stderr)
        # A solver and a benchmark removed from the file: their finished cells stay listed but
        # are no longer the experiment's, so eval and report leave them out, and say so; the
        # view the experiment no longer runs is no benchmark of its report.
        start = text.index('[[solver]]\nname = "apex"')
        narrowed = text[:start] + text[text.index("[reference]"):]
        self.write("paper.toml", narrowed.replace('["Grid_2", "Grid_3"]', '["Grid_2"]'))
        self.assertEqual(json.loads(run(*argv, env=env).stdout)["ran"], 0)
        r = run("eval", results, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("6 finished cells no longer in the experiment, left out: "
                      "apex-eps0.01/small/Grid_2, apex-eps0.01/small/Grid_3, "
                      "apex-eps0.1/small/Grid_2, apex-eps0.1/small/Grid_3, ltmoa/small/Grid_3, "
                      "namoa/small/Grid_3\n", r.stderr)
        self.assertEqual({(row["benchmark"], row["solver"]) for row in
                          json.loads(r.stdout)["rows"]}, {("Grid_2", "namoa"), ("Grid_2", "ltmoa")})
        out = self.path("narrowed-csv")
        r = run("report", results, "-o", self.path("narrowed.html"), "--csv", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        suite = read(os.path.join(out, "suite.csv")).decode()
        self.assertEqual([row["benchmark"] for row in csv.DictReader(io.StringIO(suite))],
                         ["Grid_2"])


class ExperimentOnSlurm(ExperimentFixture, test_slurm.SlurmCluster):
    """The same experiment as one job array on the one-node cluster tools/slurm-cluster.sh
    starts (test_slurm.SlurmCluster's machinery): the same fronts as the local run."""

    test_readme_then_a_cancelled_shard_resumed = None  # test_slurm's own test, run there

    def test_one_array_for_the_matrix_has_the_local_fronts(self):
        local = self.path("local")
        self.run_experiment(local)
        self.start_cluster()
        array, results = self.path("array"), self.path("results")
        r = self.m("experiment", "run", self.experiment, "-o", results, "--slurm", array,
                   "--queries-per-task", "10", "--submit")
        self.assertIn("submitted array job", r.stdout)
        self.assertEqual(len(read(os.path.join(array, "jobs")).decode().split()), 1)
        self.wait_until("the array's tasks finish",
                        lambda: self.squeue().returncode == 0 and not self.squeue().stdout.strip(),
                        array, seconds=300)
        status = json.loads(self.m("experiment", "run", self.experiment, "-o", results,
                                   "--slurm", array, "--status", "--json").stdout)
        self.assertTrue(status["complete"], status)
        self.assertTrue(set(status["scheduler"]) & {"squeue", "sacct"}, status)
        self.assertEqual({t["state"] for t in status["task_states"]} - {"COMPLETED"}, set(),
                         status)
        r = json.loads(self.m("experiment", "run", self.experiment, "-o", results, "--slurm",
                              array, "--resume", "--submit", "--json").stdout)
        self.assertEqual((r["merged"], r["resubmit"], r["job"]),
                         (self.expected_cells(), "", None))
        self.same_fronts(local, results)


if __name__ == "__main__":
    mosbtest.main()
