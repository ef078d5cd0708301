#!/usr/bin/python3
"""End-to-end tests of `mosb run` (spec/RUN.md).

    MOSB=build/release/tools/mosb EXAMPLES=build/release/examples /usr/bin/python3 tests/cli/test_run.py

Solvers are small sh and Python scripts written here: each records its pid (and its children's)
in a file, and every test checks that none of them is still alive afterwards. The example solvers
(EXAMPLES) are the real ones.
"""

import json
import os
import resource
import signal
import stat
import subprocess
import time

import mosbtest
from mosbtest import CliTest, FINISHED, alive, assert_finished, setUpModule  # noqa: F401

EXAMPLES = os.path.abspath(os.environ.get("EXAMPLES", ""))
MEASUREMENTS = ["auto", "rlimit-poll"]

# A Python allocation of 8 MiB every 5 ms, each page written, up to 1 GiB: past any limit here,
# gradually enough for the 20 ms poll of rlimit-poll to see it.
ALLOCATE = ("import time\nchunks = []\nfor i in range(128):\n"
            "    chunks.append(b'x' * (8 << 20))\n    time.sleep(0.005)\n")


def memory_cgroup():
    """This process's cgroup v1 memory directory (mosb run's groups are made in it), or None."""
    with open("/proc/self/cgroup") as f:
        for line in f:
            _, controllers, path = line.rstrip("\n").split(":", 2)
            if "memory" in controllers.split(","):
                d = "/sys/fs/cgroup/memory" + ("" if path == "/" else path)
                return d if os.path.isdir(d) else None
    return None


# A solver script's `record FILE` appends the pid of the shell that runs it, as this test sees it:
# a solver may run in a PID namespace of its own, where $$ and $! are that namespace's numbers,
# while /proc is still the test's (the builtin `read` runs in the shell itself).
RECORD = 'record() { read -r me rest < /proc/self/stat; echo "$me" >> "$1"; }\n'


class RunTest(CliTest):
    leaves_temporaries = True  # the kill -9 test stops mosb run on purpose

    def setUp(self):
        super().setUp()
        self.ok("generate", "grid", "--width", "4", "--height", "4", "--objectives", "2", "-o",
                self.path("bare.mosb"))
        self.ok("queries", "generate", self.path("bare.mosb"), "--set", "q", "--count", "6",
                "-o", self.path("grid.mosb"))
        self.grid = self.path("grid.mosb")
        self.pids = self.path("pids")

    def script(self, name, body, interpreter="/bin/sh"):
        if interpreter == "/bin/sh":
            body = RECORD + body
        path = self.write(name, "#!%s\n%s" % (interpreter, body))
        os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
        return path

    def run_solver(self, template, *extra, output="out.sol", queries="q", code=FINISHED,
                   timeout=120):
        r = self.mosb("run", self.grid, "--view", "Grid_2", "--queries", queries, "--solver",
                      template, *extra, "-o", self.path(output), timeout=timeout)
        assert_finished(self, r, code, [self.path(output)])
        return r

    def inspect(self, name="out.sol"):
        return json.loads(self.ok("solutions", "inspect", "--json", self.path(name)).stdout)

    def assert_no_process_left(self):
        """Every pid a solver recorded (itself, its children) is gone."""
        pids = [int(p) for p in mosbtest.read(self.pids, "r").split()]
        self.assertTrue(pids, "the solver recorded no pid")
        left = [p for p in pids if alive(p)]
        self.assertEqual(left, [], "processes left behind")

    def one_query(self, body, *extra, interpreter="/bin/sh", code=FINISHED):
        """Runs a one-query set with the solver `body`; returns (inspect, stderr)."""
        self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1", "--in-place",
                "--replace")
        solver = self.script("solver", body, interpreter)
        r = self.run_solver(solver + " {source} {target}", *extra, queries="one", code=code)
        return self.inspect(), r

    def assert_status(self, info, status):
        statuses = {k: v for k, v in info["statuses"].items() if v}
        self.assertEqual(statuses, {status: 1})

    # --- statuses ---------------------------------------------------------------------------

    def test_timeout_kills_the_tree(self):
        started = time.monotonic()
        info, _ = self.one_query("record %s\n(record %s; exec sleep 30) &\nwait\n" %
                                 (self.pids, self.pids), "--time-limit", "1s", "--grace", "0.2")
        self.assertLess(time.monotonic() - started, 15)
        self.assert_status(info, "timeout")
        self.assertNotIn("runtime_seconds", info["statistics"])
        self.assert_no_process_left()

    def test_a_descendant_that_leaves_the_process_group_is_killed(self):
        # setsid takes the child out of the solver's process group and session: the query's
        # launcher (a PID namespace's init, or a subreaper) still kills it when the solver ends,
        # under either measurement (spec/RUN.md §4; tests/cli/test_hostile.py has the rest).
        for measurement in ("rlimit-poll", "cgroup-v1"):
            with self.subTest(measurement=measurement):
                if os.path.exists(self.pids):
                    os.remove(self.pids)
                info, _ = self.one_query(
                    "setsid sh -c 'read -r me rest < /proc/self/stat; echo $me >> %s; "
                    "exec sleep 30' &\nwhile [ ! -s %s ]; do sleep 0.01; done\necho 1 1\n" %
                    (self.pids, self.pids), "--measurement", measurement)
                self.assert_status(info, "solved")
                self.assert_no_process_left()

    def test_cpu_limit_counts_the_whole_tree(self):
        # Two busy processes: 1.5 s of CPU time in about 0.75 s on two cores, far below the
        # wall-clock limit; a sleeping solver passes the same CPU limit untouched.
        started = time.monotonic()
        info, _ = self.one_query("record %s\n(record %s; while :; do :; done) &\n"
                                 "while :; do :; done\n" % (self.pids, self.pids),
                                 "--cpu-limit", "1500ms", "--time-limit", "60s", "--grace", "0.2")
        self.assertLess(time.monotonic() - started, 30)
        self.assert_status(info, "timeout")
        self.assertEqual(info["parameters"]["run.cpu_limit_seconds"], "1.5")
        self.assert_no_process_left()
        info, _ = self.one_query("record %s\nsleep 2\necho 1 1\n" % self.pids,
                                 "--cpu-limit", "1s")
        self.assert_status(info, "solved")

    def test_cpu_time_counts_what_the_solver_left(self):
        # The solver ends once its busy child has used 0.5 s of CPU (however loaded the machine);
        # the child, still running then, is killed by the query's launcher: its CPU time is the
        # query's too (spec/RUN.md §4, CPU time).
        busy = ("import os, time\n"
                "def record():\n"
                "    with open(%r, 'a') as f:\n"
                "        f.write(open('/proc/self/stat').read().split()[0] + '\\n')\n"
                "r, w = os.pipe()\n"
                "if os.fork() == 0:\n"
                "    record()\n"
                "    while time.process_time() < 0.5:\n"
                "        pass\n"
                "    os.write(w, b'x')\n"
                "    while True:\n"
                "        pass\n"
                "record()\n"
                "os.read(r, 1)\n"
                "print('1 1')\n" % self.pids)
        for measurement in MEASUREMENTS:
            with self.subTest(measurement=measurement):
                if os.path.exists(self.pids):
                    os.remove(self.pids)
                self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1",
                        "--in-place", "--replace")
                solver = self.script("busy", busy, "/usr/bin/python3")
                r = self.run_solver(solver + " {source} {target}", "--measurement", measurement,
                                    "--json", queries="one")
                summary = json.loads(r.stdout)
                self.assertEqual(summary["statuses"]["solved"], 1)
                self.assertGreaterEqual(summary["solver_cpu_seconds"], 0.5, summary)
                self.assertLess(summary["solver_cpu_seconds"],
                                2 * summary["solver_wall_seconds"] + 0.1, summary)
                self.assert_no_process_left()

    def test_memory_limit_in_the_solver_and_in_a_forked_child(self):
        # The child that calls setsid has left the solver's process group and session: still one
        # of the query's processes, its memory counts (spec/RUN.md §4).
        for measurement in MEASUREMENTS:
            for child in ("none", "forked", "setsid"):
                with self.subTest(measurement=measurement, child=child):
                    self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1",
                            "--in-place", "--replace")
                    self.write("alloc.py", ALLOCATE)
                    if child != "none":
                        body = ("record %s\n(record %s; exec %s/usr/bin/python3 %s) &\nwait\n"
                                "exit 0\n" % (self.pids, self.pids,
                                               "setsid " if child == "setsid" else "",
                                               self.path("alloc.py")))
                    else:
                        body = "record %s\nexec /usr/bin/python3 %s\n" % (
                            self.pids, self.path("alloc.py"))
                    solver = self.script("solver", body)
                    r = self.run_solver(solver, "--memory-limit", "100M", "--measurement",
                                        measurement, "--json", queries="one",
                                        output="mem.sol", timeout=60)
                    summary = json.loads(r.stdout)
                    self.assertEqual(summary["statuses"]["memory-limit"], 1, r)
                    self.assert_no_process_left()

    def test_many_jobs_under_a_low_open_file_limit(self):
        # Each job holds some thirty descriptors (the queries forked ahead, running and ending):
        # mosb run raises its own soft limit to the hard one, and every solver still starts with
        # the limit mosb was started with (spec/RUN.md §4).
        _, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
        self.assertGreater(hard, 200, "the test needs a hard open-file limit above the soft one")
        self.write("alloc.py", ALLOCATE)
        limits = self.path("limits")
        solver = self.script("solver", "ulimit -Sn >> %s\nexec /usr/bin/python3 %s\n" % (
            limits, self.path("alloc.py")))
        for measurement in MEASUREMENTS:
            with self.subTest(measurement=measurement):
                r = self.mosb("run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                              solver, "--jobs", "4", "--memory-limit", "100M", "--measurement",
                              measurement, "--json", "-o", self.path("fd-%s.sol" % measurement),
                              timeout=120, preexec_fn=lambda: resource.setrlimit(
                                  resource.RLIMIT_NOFILE, (40, hard)))
                # Every query over its memory limit: none completed (exit 3).
                self.assertEqual(r.returncode, 3, r)
                self.assertIn("most often, 6 of 6: memory-limit", r.stderr)
                self.assertEqual(json.loads(r.stdout)["statuses"]["memory-limit"], 6, r)
                self.assertEqual(mosbtest.read(limits, "r").split(), ["40"] * 6)
                os.remove(limits)

    def test_crash_is_failed_with_the_signal(self):
        info, r = self.one_query("record %s\necho dying >&2\nkill -SEGV $$\n" % self.pids)
        self.assert_status(info, "failed")
        self.assertEqual(info["statistics"]["exit_status"]["max"], 139)
        self.assertIn("failed: killed by signal 11: dying", r.stderr)
        self.assertTrue(r.stderr.startswith("mosb: query 0 ("), r.stderr)
        self.assert_no_process_left()

    def test_non_zero_exit_is_failed_with_its_status(self):
        info, r = self.one_query("record %s\necho '1 2'\necho 'out of luck' >&2\nexit 3\n" %
                                 self.pids)
        self.assert_status(info, "failed")
        self.assertEqual(info["statistics"]["exit_status"]["max"], 3)
        self.assertIn("exit status 3: out of luck", r.stderr)
        self.assert_no_process_left()

    def test_unparsable_output_is_failed(self):
        info, r = self.one_query("record %s\necho '1 x'\n" % self.pids)
        self.assert_status(info, "failed")
        # The run's line names the reason without the location: one cause counts once.
        self.assertIn("mosb: no query completed (1 failed); most often, 1 of 1: unreadable "
                      "output: 'x' is not an unsigned integer", r.stderr)
        self.assertEqual(info["statistics"]["exit_status"]["max"], 0)
        self.assertIn("unreadable output: stdout:1:3: 'x' is not an unsigned integer (objective 2 "
                      "is an integer one)", r.stderr)
        self.assert_no_process_left()

    def test_empty_front_with_exit_0_is_disconnected(self):
        info, _ = self.one_query("record %s\necho 'mosb: expanded=7' >&2\n" % self.pids)
        self.assert_status(info, "disconnected")
        self.assertEqual(info["statistics"]["expanded"]["total"], 7)
        self.assertIn("runtime_seconds", info["statistics"])
        self.assert_no_process_left()

    def test_front_in_a_file_and_statistics(self):
        body = ("record %s\nprintf '3 4\\n1 9\\n' > \"$3\"\necho noise\n"
                "echo 'mosb: generated=11' >&2\necho 'mosb: runtime_seconds=0.125' >&2\n"
                % self.pids)
        self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1", "--in-place",
                "--replace")
        solver = self.script("solver", body)
        self.run_solver(solver + " {source} {target} {front}", queries="one")
        info = self.inspect()
        self.assert_status(info, "solved")
        self.assertEqual(info["vectors"], 2)
        self.assertEqual(info["statistics"]["generated"]["total"], 11)
        # The solver's own runtime beside mosb's wall clock (format 1.5).
        self.assertEqual(info["statistics"]["reported_runtime_seconds"]["total"], 0.125)
        self.assertEqual(mosbtest.header(mosbtest.read(self.path("out.sol")))["version_minor"], 5)
        self.assert_no_process_left()

    def test_json_log_adapter_reads_ppa_style_logs(self):
        # The record shape of PPA*'s Logger: the front under finish_info, runtime in ms.
        body = ("record %s\nprintf '[{\"source\": %%s, \"target\": %%s, \"finish_info\": "
                "{\"solutions\": [{\"cost_until_now\": [3, 4]}, {\"cost_until_now\": [1, 9]}]},"
                " \"total_runtime(ms)\": 2.5}]' \"$1\" \"$%s\" > \"$3\"\n")
        solver = self.script("solver", body % (self.pids, 2))
        self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1", "--in-place",
                "--replace")
        self.run_solver(solver + " {source} {target} {front}", "--output-format", "json-log",
                        queries="one")
        info = self.inspect()
        self.assert_status(info, "solved")
        self.assertEqual(info["vectors"], 2)
        self.assertEqual(info["statistics"]["reported_runtime_seconds"]["total"], 0.0025)
        # A record for other endpoints (source in place of the target) is not this query's.
        solver = self.script("solver", body % (self.pids, 1))
        self.run_solver(solver + " {source} {target} {front}", "--output-format", "json-log",
                        queries="one", output="wrong.sol")
        self.assert_status(self.inspect("wrong.sol"), "failed")
        self.assert_no_process_left()

    def test_a_program_that_cannot_execute_is_failed_with_127(self):
        self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1", "--in-place",
                "--replace")
        solver = self.write("noshebang", "echo 1 2\n")  # executable, but no #! line: ENOEXEC
        os.chmod(solver, 0o755)
        r = self.run_solver(solver, queries="one")
        info = self.inspect()
        self.assert_status(info, "failed")
        self.assertEqual(info["statistics"]["exit_status"]["max"], 127)
        self.assertIn("cannot run: Exec format error", r.stderr)

    def test_objectives_instead_of_a_view(self):
        self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1", "--in-place",
                "--replace")
        solver = self.script("solver", "record %s\necho \"$1\" > %s\necho 0 7\n" %
                             (self.pids, self.path("objectives")))
        r = self.mosb("run", self.grid, "--objectives", "c1,c2", "--queries", "one", "--solver",
                      solver + " {objectives}", "-o", self.path("out.sol"))
        self.assertEqual(r.returncode, 0, r)
        info = self.inspect()
        self.assertEqual(info["view"], "Grid_2")
        self.assertEqual(info["vectors"], 1)
        self.assertEqual(mosbtest.read(self.path("objectives"), "r"), "c1,c2\n")
        # No view has c2,c1: the file is bound to the objective list alone (format 1.4).
        r = self.mosb("run", self.grid, "--objectives", "c2,c1", "--queries", "one", "--solver",
                      solver + " {objectives}", "-o", self.path("swapped.sol"))
        self.assertEqual(r.returncode, 0, r)
        info = json.loads(self.ok("solutions", "inspect", "--json", self.path("swapped.sol")).stdout)
        self.assertIsNone(info["view"])
        self.assertEqual([o["name"] for o in info["objectives"]], ["c2", "c1"])
        self.assertEqual(mosbtest.read(self.path("objectives"), "r"), "c2,c1\n")
        self.ok("solutions", "verify", self.path("swapped.sol"), "--instance", self.grid)
        r = self.mosb("run", self.grid, "--objectives", "c2,c1", "--solver", solver, "-o",
                      self.path("other.sol"))
        self.assert_one_line_error(r, "grid.mosb: no query set for these objectives (no view has "
                                      "them); give --queries SET", code=2)
        r = self.mosb("run", self.grid, "--view", "Grid_2", "--queries", "one", "--solver",
                      "no-such-solver-anywhere {query}", "-o", self.path("other.sol"))
        self.assert_one_line_error(r, "no-such-solver-anywhere: no such executable in PATH", code=2)
        self.assertFalse(os.path.exists(self.path("other.sol.journal")))

    # --- templates --------------------------------------------------------------------------

    def test_template_quoting_passes_one_argument(self):
        directory = self.path("a dir; rm -rf x")
        os.makedirs(directory)
        args = self.path("args")
        solver = os.path.join(directory, "solve me.sh")
        with open(solver, "w") as f:
            f.write("#!/bin/sh\n" + RECORD + "record %s\nprintf '%%s|' \"$#\" \"$@\" > '%s'\n" %
                    (self.pids, args))
        os.chmod(solver, 0o755)
        os.rename(self.grid, self.path("g $x;y.mosb"))
        self.grid = self.path("g $x;y.mosb")
        self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1", "--in-place",
                "--replace")
        quoted = "'" + solver + "'"
        self.run_solver(quoted + ' {instance} "a b" c\\ d {{x}}', queries="one")
        self.assertEqual(mosbtest.read(args, "r"), "4|%s|a b|c d|{x}|" % self.grid)
        self.assert_no_process_left()

    def test_template_errors_are_usage_errors(self):
        r = self.run_solver("/bin/true {nope}", code=2)
        self.assertIn("unknown placeholder {nope}", r.stderr)
        r = self.run_solver("/bin/true 'open", code=2)
        self.assertIn("unterminated single quote", r.stderr)
        self.assertFalse(os.path.exists(self.path("out.sol.journal")))

    # --- journal, resume, interrupts --------------------------------------------------------

    def slow_boa(self, marker_dir):
        """A solver that counts its runs per query, sleeps a little, then is the example BOA*."""
        os.makedirs(marker_dir, exist_ok=True)
        return self.script("slow", "echo x >> %s/$1\nsleep 0.4\nshift\nexec %s \"$@\" --protocol\n"
                           % (marker_dir, os.path.join(EXAMPLES, "boa_star")))

    def exported(self, name):
        out = self.path(name + ".fronts")
        self.ok("solutions", "export", self.path(name), "--dir", out)
        fronts = {f: mosbtest.read(os.path.join(out, f), "r") for f in sorted(os.listdir(out))}
        return fronts, self.inspect(name)["statuses"]

    def test_kill_9_then_resume_runs_only_what_is_missing(self):
        self.require_examples()
        markers = self.path("markers")
        template = self.slow_boa(markers) + " {query} {instance} --view {view} --query {source} {target}"
        args = [mosbtest.MOSB, "run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                template, "-o", self.path("out.sol")]
        p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        journal = self.path("out.sol.journal")
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            if os.path.exists(journal) and mosbtest.read(journal, "r").count("\n") >= 3:
                break
            time.sleep(0.05)
        p.kill()
        p.communicate()
        done_before = [json.loads(line)["query"]
                       for line in mosbtest.read(journal, "r").splitlines()[1:]]
        self.assertGreaterEqual(len(done_before), 2)
        self.assertLess(len(done_before), 6)
        self.assertFalse(os.path.exists(self.path("out.sol")))
        missing = min(set(range(6)) - set(done_before))
        with open(journal, "a") as f:  # a record torn by the kill: ignored
            f.write('{"query": %d, "status": "solved", "fro' % missing)
        r = self.run_solver(template, code=1)
        self.assertIn("continue it with --resume or remove it", r.stderr)
        r = self.run_solver(template + " --extra", "--resume", code=1)
        self.assertIn("the journal is of another run (solver", r.stderr)
        self.run_solver(template, "--resume")
        group = memory_cgroup()
        if group:  # the killed run's group is removed by the next run once empty
            self.assertFalse(os.path.exists(os.path.join(group, "mosb-run-%d-0" % p.pid)))
        for q in done_before:
            self.assertEqual(mosbtest.read(os.path.join(markers, str(q)), "r"), "x\n", q)
        self.assertEqual(sorted(os.listdir(markers)), [str(q) for q in range(6)])
        self.assertFalse(os.path.exists(journal))
        self.run_solver(os.path.join(EXAMPLES, "boa_star") +
                        " {instance} --view {view} --query {source} {target} --protocol",
                        output="straight.sol")
        self.assertEqual(self.exported("out.sol"), self.exported("straight.sol"))

    def test_sigint_stops_the_solvers_and_keeps_the_journal(self):
        """SIGHUP (a closed terminal) stops a run as SIGINT does."""
        solver = self.script("solver", "record %s\n(record %s; exec sleep 30) &\nwait\n" %
                             (self.pids, self.pids))
        args = [mosbtest.MOSB, "run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                solver, "--jobs", "2", "-o", self.path("out.sol")]
        for stop in (signal.SIGHUP, signal.SIGINT):
            if os.path.exists(self.pids):
                os.remove(self.pids)
            p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            deadline = time.monotonic() + 20
            while time.monotonic() < deadline:
                if os.path.exists(self.pids) and len(mosbtest.read(self.pids, "r").split()) >= 4:
                    break
                time.sleep(0.05)
            p.send_signal(stop)
            _, err = p.communicate(timeout=30)
            self.assertEqual(p.returncode, 130, (stop, err))
            self.assertIn("continue with --resume", err)
            self.assertTrue(os.path.exists(self.path("out.sol.journal")))
            self.assertFalse(os.path.exists(self.path("out.sol")))
            self.assert_no_process_left()
            if stop == signal.SIGHUP:
                os.remove(self.path("out.sol.journal"))
        lines = mosbtest.read(self.path("out.sol.journal"), "r").count("\n")
        with open(self.path("out.sol.journal"), "a") as f:  # a whole line, not a torn one
            f.write("not json\n")
        r = self.mosb("run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver", solver,
                      "--jobs", "2", "-o", self.path("out.sol"), "--resume")
        self.assert_one_line_error(r, "out.sol.journal:%d: not a journal line" % (lines + 1))

    # --- the example solvers ----------------------------------------------------------------

    def require_examples(self):
        if not os.path.isfile(os.path.join(EXAMPLES, "boa_star")):
            raise mosbtest.missing("EXAMPLES (the example solvers' directory) is not set")

    def test_example_solvers_verify_and_evaluate(self):
        self.require_examples()
        self.ok("generate", "grid", "--width", "12", "--height", "12", "--objectives", "2", "-o",
                self.path("g12.mosb"))
        self.ok("queries", "generate", self.path("g12.mosb"), "--set", "q", "--count", "8",
                "--in-place")
        self.grid = self.path("g12.mosb")
        boa = os.path.join(EXAMPLES, "boa_star")
        namoa = os.path.join(EXAMPLES, "namoa")
        self.run_solver(boa + " {instance} --view {view} --query {source} {target} --protocol",
                        "--time-limit", "60s", "--memory-limit", "1G", "--jobs", "2", "--pin",
                        output="boa.sol")
        self.ok("solutions", "verify", "--instance", self.grid, self.path("boa.sol"))
        self.run_solver(namoa + " {instance} --view {view} --query {source} {target} --fronts "
                        "{fronts}", "--output-format", "example-log", output="namoa.sol")
        self.ok("solutions", "verify", "--instance", self.grid, self.path("namoa.sol"))
        r = self.ok("eval", "--reference", self.path("namoa.sol"), "--solutions",
                    self.path("boa.sol"), "--eps", "0", "--json")
        self.assertTrue(json.loads(r.stdout)["ok"], r.stdout)
        info = self.inspect("boa.sol")
        self.assertEqual(info["statuses"]["solved"], 8)
        self.assertEqual(info["parameters"]["run.measurement"] in ("cgroup-v1", "rlimit-poll"),
                         True)
        self.assertEqual(len(info["parameters"]["run.executable_sha256"]), 64)
        self.assertEqual(info["parameters"]["run.pin"], "yes")
        self.assertEqual(info["parameters"]["run.jobs"], "2")
        self.assertEqual(info["statistics"]["expanded"]["queries"], 8)
        self.assertEqual(info["statistics"]["peak_memory_bytes"]["queries"], 8)


if __name__ == "__main__":
    mosbtest.main()
