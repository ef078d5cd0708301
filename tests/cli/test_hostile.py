#!/usr/bin/python3
"""`mosb run` against hostile and merely unusual solvers and journals (issue 33): every case is a
way a recorded front could have been silently wrong, or mosb run crash, and is checked to be
refused, isolated or recorded as what it is.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_hostile.py

It runs as root in CI, where each query's processes live in a PID namespace of their own; the
same cases run again as an unprivileged user (setpriv), where the query's launcher is a child
subreaper and memory is measured with rlimit-poll.
"""

import hashlib
import json
import os
import shutil
import signal
import stat
import subprocess
import time

import mosbtest
from mosbtest import CliTest, FINISHED, alive, assert_finished, setUpModule  # noqa: F401

# A solver script's `record FILE` appends the pid of the shell that runs it as this test sees it
# (/proc is the test's even inside a PID namespace; `read` is a builtin, so /proc/self is the
# shell itself).
RECORD = 'record() { read -r me rest < /proc/self/stat; echo "$me" >> "$1"; }\n'
NOBODY = 65534


class Hostile(CliTest):
    leaves_temporaries = True  # the kill -9 cases stop mosb run on purpose

    def setUp(self):
        super().setUp()
        os.chmod(self.dir, 0o777)  # the unprivileged runs write here
        self.ok("generate", "grid", "--width", "4", "--height", "4", "--objectives", "2", "-o",
                self.path("bare.mosb"))
        self.ok("queries", "generate", self.path("bare.mosb"), "--set", "q", "--count", "4",
                "-o", self.path("grid.mosb"))
        self.grid = self.path("grid.mosb")
        self.pids = self.path("pids")

    def script(self, name, body):
        path = self.write(name, "#!/bin/sh\n" + RECORD + body)
        os.chmod(path, 0o755)
        return path

    def run_mosb(self, *args, user=None, env=None):
        """mosb as root, or (user=NOBODY) as an unprivileged user from a copy of the program."""
        command = [mosbtest.MOSB, *args]
        if user is not None:
            program = self.path("mosb-copy")
            if not os.path.exists(program):
                shutil.copy(mosbtest.MOSB, program)
                os.chmod(program, 0o755)
            command = ["setpriv", "--reuid=%d" % user, "--regid=%d" % user, "--clear-groups",
                       program, *args]
        return subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=self.dir,
                              env=env)

    def run_solver(self, solver, *extra, output="out.sol", queries="q", user=None,
                   code=FINISHED):
        r = self.run_mosb("run", self.grid, "--view", "Grid_2", "--queries", queries, "--solver",
                          solver + " {query} {source} {target}", *extra, "-o",
                          self.path(output), user=user)
        assert_finished(self, r, code, [self.path(output)])
        return r

    def inspect(self, name="out.sol"):
        return json.loads(self.ok("solutions", "inspect", "--json", self.path(name)).stdout)

    def fronts(self, name="out.sol"):
        d = self.path(name + ".export")
        shutil.rmtree(d, ignore_errors=True)
        self.ok("solutions", "export", self.path(name), "--dir", d)
        return {f: mosbtest.read(os.path.join(d, f), "r") for f in sorted(os.listdir(d))}

    def journal_lines(self, name="out.sol"):
        return mosbtest.read(self.path(name + ".journal"), "r").splitlines()

    def assert_no_process_left(self):
        pids = [int(p) for p in mosbtest.read(self.pids, "r").split()]
        self.assertTrue(pids, "the solver recorded no pid")
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline and any(alive(p) for p in pids):
            time.sleep(0.05)
        self.assertEqual([p for p in pids if alive(p)], [], "processes outlived their query")

    # --- 1. isolation ---------------------------------------------------------------------------

    # Query 0 leaves a daemon (setsid plus a double fork: another session, another process group,
    # reparented) that, once query 0 has ended, keeps writing vectors to the stdout it inherited;
    # the later queries print their own front slowly. Nothing of the daemon may reach them, and it
    # may not outlive query 0.
    ESCAPE = ('if [ "$1" = 0 ]; then\n'
              "  setsid sh -c '(read -r me rest < /proc/self/stat; echo $me >> %s; sleep 0.2; "
              "while :; do echo 9 9; sleep 0.02; done) &' &\n"
              "  while [ ! -s %s ]; do sleep 0.01; done\n"
              "else\n"
              "  sleep 0.4\n"
              "fi\n"
              "record %s\n"
              'echo "$(($1 + 1)) 1"\n')

    def check_escape(self, user=None, measurement="auto"):
        if os.path.exists(self.pids):
            os.remove(self.pids)
        solver = self.script("escape", self.ESCAPE % (self.pids, self.pids, self.pids))
        self.run_solver(solver, "--measurement", measurement, user=user)
        fronts = self.fronts()
        self.assertEqual([fronts["%d.txt" % q] for q in range(4)],
                         ["1 1\n", "2 1\n", "3 1\n", "4 1\n"])
        self.assert_no_process_left()

    def test_escaped_descendants_die_with_their_query(self):
        for measurement in ("rlimit-poll", "cgroup-v1"):
            with self.subTest(measurement=measurement):
                self.check_escape(measurement=measurement)
        self.assertEqual(self.inspect()["parameters"]["run.isolation"], "pid-namespace")

    def test_escaped_descendants_die_with_their_query_unprivileged(self):
        self.check_escape(user=NOBODY, measurement="rlimit-poll")
        info = self.inspect()
        self.assertEqual(info["parameters"]["run.isolation"], "subreaper")

    def test_a_solver_that_leaves_its_memory_group_still_dies_with_its_query(self):
        # As root a solver can move itself out of its memory cgroup; the PID namespace holds it.
        body = ('echo $$ > /sys/fs/cgroup/memory/cgroup.procs 2>/dev/null\n' + self.ESCAPE)
        solver = self.script("leaver", body % (self.pids, self.pids, self.pids))
        self.run_solver(solver, "--measurement", "cgroup-v1")
        self.assertEqual(self.fronts()["1.txt"], "2 1\n")
        self.assert_no_process_left()

    # --- 2. a solver's own statement that it did not finish ---------------------------------------

    def test_example_log_status_lines_are_never_solved_or_disconnected(self):
        for stated, recorded in (("timeout", "timeout"), ("memory-limit", "memory-limit"),
                                 ("failed", "failed")):
            with self.subTest(stated=stated):
                solver = self.script("self-timeout",
                                     'mkdir -p "$4"\nprintf "status %s\\n" > "$4/0.txt"\n'
                                     'echo "$2 $3 0 0.5 10"\n' % stated)
                self.one()
                self.run_solver(solver + " {query} {source} {target} {fronts} #", "--output-format",
                                "example-log", queries="one")
                info = self.inspect()
                self.assertEqual(info["statuses"][recorded], 1, info["statuses"])
                self.assertEqual(info["statuses"]["disconnected"], 0)

    def test_a_json_log_that_says_failed_is_never_solved(self):
        # How the A*pex family logs its own time-out: finish_info.status "Failed" beside a
        # partial front.
        body = ("printf '[{\"source\": %s, \"target\": %s, \"finish_info\": {\"solutions\": "
                "[{\"cost_until_now\": [3, 4]}], \"status\": \"Failed\"}}]' \"$2\" \"$3\" > \"$4\"\n")
        self.one()
        solver = self.script("apex-like", body)
        r = self.run_solver(solver + " {query} {source} {target} {front} #", "--output-format",
                            "json-log", queries="one")
        info = self.inspect()
        self.assertEqual(info["statuses"]["failed"], 1, r.stderr)
        self.assertEqual(info["vectors"], 0)
        self.assertIn('finish_info.status "Failed"', r.stderr)

    def one(self):
        self.ok("queries", "generate", self.grid, "--set", "one", "--count", "1", "--in-place",
                "--replace")
        return True

    # --- 3, 4. fronts that break rule 1 ---------------------------------------------------------

    def one_query(self, body, *extra, user=None):
        self.one()
        solver = self.script("solver", body)
        r = self.run_solver(solver, *extra, queries="one", user=user)
        return self.inspect(), r

    def test_duplicate_and_dominated_vectors_fail_the_query(self):
        cases = [("echo '1 9'; echo '1 9'; echo '4 4'\n", (), "[duplicate] vector (1, 9)"),
                 ("echo '3 9'; echo '3 8'\n", (), "[dominated] vector (3, 9) is dominated by (3, 8)"),
                 # An approximate solver may return a vector its own others dominate; never twice.
                 ("echo '3 9'; echo '3 8'\n", ("--epsilon", "0.05"), None),
                 ("echo '3 8'; echo '3 8'\n", ("--epsilon", "0.05"), "[duplicate] vector (3, 8)")]
        for body, extra, message in cases:
            with self.subTest(body=body, extra=extra):
                info, r = self.one_query(body, *extra)
                if message is None:
                    self.assertEqual(info["statuses"]["solved"], 1, r.stderr)
                    self.assertEqual(info["epsilon"], "0.05")
                else:
                    self.assertEqual(info["statuses"]["failed"], 1, r.stderr)
                    self.assertIn(message, r.stderr)
        # PPA*'s pair log holds each vector twice: a json-log record with a repeated vector.
        body = ("printf '[{\"source\": %s, \"target\": %s, \"finish_info\": {\"solutions\": "
                "[{\"cost_until_now\": [3, 4]}, {\"cost_until_now\": [3, 4]}]}}]' \"$2\" \"$3\""
                " > \"$4\"\n")
        self.one()
        solver = self.script("ppa", body)
        r = self.run_solver(solver + " {query} {source} {target} {front} #", "--output-format",
                            "json-log", queries="one")
        self.assertEqual(self.inspect()["statuses"]["failed"], 1, r.stderr)
        self.assertIn("[duplicate] vector (3, 4)", r.stderr)

    def test_an_integer_above_2_53_is_refused_not_rounded(self):
        info, r = self.one_query("echo '9007199254740993 1'\n")
        self.assertEqual(info["statuses"]["failed"], 1)
        self.assertIn("'9007199254740993' is above 2^53", r.stderr)
        info, r = self.one_query("echo '9007199254740992 1'\n")  # 2^53 itself is exact
        self.assertEqual(info["statuses"]["solved"], 1, r.stderr)
        info, r = self.one_query("echo '12.5 1'\n")  # an integer objective takes integers only
        self.assertEqual(info["statuses"]["failed"], 1)
        self.assertIn("is not an unsigned integer", r.stderr)

    # --- 5. a journal that cannot lie quietly ---------------------------------------------------

    def forge(self, edit, *extra, resume_extra=(), change_program=False, slow_from=2):
        """Runs a solver over set q, SIGKILLed once two queries are recorded; applies
        `edit(lines) -> (lines, torn_tail)` to the journal; resumes with the same command (with
        `change_program` the solver's file is changed first). Returns the resume."""
        flag = self.path("slow-down")
        body = ('if [ "$1" -ge 2 ] && [ -e %s ]; then sleep 30; fi\nrecord %s\n'
                'echo "$(($1 + 1)) 1"\necho "mosb: expanded=5" >&2\n' % (flag, self.pids))
        body = body.replace("-ge 2", "-ge %d" % slow_from)
        solver = self.script("solver", body)
        with open(flag, "w"):
            pass
        for stale in (self.path("out.sol.journal"), self.path("out.sol"), self.pids):
            if os.path.exists(stale):
                os.remove(stale)
        args = ["run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                solver + " {query} {source} {target}", *extra, "-o", self.path("out.sol")]
        p = subprocess.Popen([mosbtest.MOSB, *args], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE)
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            if os.path.exists(self.path("out.sol.journal")) and len(self.journal_lines()) >= 3:
                break
            time.sleep(0.02)
        p.kill()
        p.communicate()
        # The kill reaches the solver through its launcher, asynchronously: under load the
        # solver of query 2 could still pass its flag test after the flag is gone and record a
        # pid as if the resume had run it.
        self.wait_until_no_process_mentions(solver)
        os.remove(flag)
        os.remove(self.pids)
        lines = self.journal_lines()
        self.assertEqual(len(lines), 3, lines)
        lines, torn = edit(lines)
        with open(self.path("out.sol.journal"), "w") as f:
            f.write("".join(line + "\n" for line in lines) + torn)
        if change_program:
            with open(solver, "a") as f:
                f.write("# a new version\n")
        return self.run_mosb(*args, "--resume", *resume_extra)

    def wait_until_no_process_mentions(self, path):
        """Waits (30 s at most) until no process has `path` in its command line: the solver's
        shells and the launchers forked from mosb (whose command line is mosb's)."""
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            mentions = False
            for pid in filter(str.isdigit, os.listdir("/proc")):
                try:
                    with open("/proc/%s/cmdline" % pid, "rb") as f:
                        mentions = mentions or path.encode() in f.read()
                except OSError:
                    pass
            if not mentions:
                return
            time.sleep(0.02)
        self.fail("processes of %s still running" % path)

    @staticmethod
    def resealed(record):
        """A journal line with its checksum computed as mosb run computes it (a forger who read
        the source): only the checks on the content can refuse it. mosb checks the line as its
        JSON writer prints it again, whose shortest digits of a double are not always Python's:
        the measured times are made short decimals that both print alike."""
        import xxhash
        record.pop("check", None)
        for fields in (record, record.get("statistics", {})):
            for key, value in fields.items():
                if isinstance(value, float) and key != "front":
                    fields[key] = round(value, 3)
        text = json.dumps(record, separators=(",", ":"), ensure_ascii=False)
        record["check"] = "%016x" % xxhash.xxh3_64_intdigest(text.encode())
        return json.dumps(record, separators=(",", ":"), ensure_ascii=False)

    def test_forged_journals_are_refused_before_anything_runs(self):
        def record(lines, k):
            return json.loads(lines[k])

        def change(k, **fields):
            def edit(lines):
                r = record(lines, k)
                for key, value in fields.items():
                    if value is None:
                        r.pop(key, None)
                    else:
                        r[key] = value
                return lines[:k] + [self.resealed(r)] + lines[k + 1:], ""
            return edit

        def statistics(k, **stats):
            def edit(lines):
                r = record(lines, k)
                r["statistics"].update(stats)
                return lines[:k] + [self.resealed(r)] + lines[k + 1:], ""
            return edit

        cases = [
            ("a hand edit", lambda lines: (lines[:1] + [lines[1].replace('"front":[1', '"front":[7')]
                                           + lines[2:], ""), ":2: its checksum does not match"),
            ("a line without a checksum",
             lambda lines: (lines[:1] + [json.dumps({k: v for k, v in record(lines, 1).items()
                                                     if k != "check"})] + lines[2:], ""),
             ":2: no checksum"),
            ("a duplicate record", lambda lines: (lines + [lines[1]], ""),
             ":4: a second record of query 0 (line 2 has the first)"),
            ("a not-run record", change(1, status="not-run", front=[], statistics={}),
             ":2: a record of a query that did not run"),
            ("expanded: 1e30", statistics(1, expanded=1e30),
             ":2: 'expanded' is not an unsigned integer"),
            ("query: 2.7", change(1, query=2.7), ":2: 'query' is not an unsigned integer"),
            ("a query out of range", change(1, query=9),
             ":2: query 9: not a query of set 'q' (4 queries)"),
            ("a front for a timeout", change(1, status="timeout"),
             ":2: query 0: timeout with a front"),
            ("a front of another width", change(1, front=[1, 2, 3]),
             ":2: query 0: 3 values are not a whole number of 2-objective vectors"),
            ("a dominated vector", change(1, front=[1, 9, 1, 8]), ":2: query 0: [dominated]"),
            ("a value above 2^53", change(1, front=[2.0 ** 60, 1]), ":2: query 0: vector 0"),
            ("the reserved count", statistics(1, expanded=2 ** 64 - 1),
             ":2: query 0: a statistic equals the reserved value"),
        ]
        for name, edit, message in cases:
            with self.subTest(case=name):
                r = self.forge(edit)
                self.assert_one_line_error(r, "out.sol.journal" + message)
                self.assertFalse(os.path.exists(self.pids), "a solver ran before the refusal")
                self.assertFalse(os.path.exists(self.path("out.sol")))

    def test_a_shard_journal_with_another_shards_query_is_refused(self):
        # Shard 1/2 of eight queries runs 0, 2, 4 and 6: records of 0 and 2, then a kill.
        self.ok("queries", "generate", self.grid, "--set", "q", "--count", "8", "--in-place",
                "--replace")

        def move(lines):  # a record of query 0 made to say query 1, of the other shard
            r = json.loads(lines[1])
            r["query"] = 1
            return lines[:1] + [self.resealed(r)] + lines[2:], ""
        r = self.forge(move, "--shard", "1/2", slow_from=4)
        self.assert_one_line_error(r, "out.sol.journal:2: query 1: not a query of shard 1/2")

    def test_a_torn_last_line_is_cut_and_the_counts_agree(self):
        r = self.forge(lambda lines: (lines[:2], lines[2][:-10]), resume_extra=("--json",))
        self.assertEqual(r.returncode, 0, r.stderr)
        result = json.loads(r.stdout)
        self.assertEqual((result["ran"], result["from_journal"]), (3, 1))
        self.assertEqual(result["statuses"]["solved"], 4)
        self.assertEqual(self.inspect()["statuses"]["solved"], 4)

    # --- 6. another executable on resume ----------------------------------------------------------

    def test_a_changed_executable_is_refused_on_resume_unless_allowed(self):
        r = self.forge(lambda lines: (lines, ""), change_program=True)
        self.assert_one_line_error(r, "the solver's executable changed")
        self.assertIn("--allow-new-executable", r.stderr)
        self.assertFalse(os.path.exists(self.pids), "a solver ran before the refusal")
        r = self.forge(lambda lines: (lines, ""), change_program=True,
                       resume_extra=("--allow-new-executable",))
        self.assertEqual(r.returncode, 0, r.stderr)
        digests = self.inspect()["parameters"]["run.executable_sha256"].split(" | ")
        self.assertEqual(len(digests), 2)
        with open(self.path("solver"), "rb") as f:
            self.assertEqual(digests[1], hashlib.sha256(f.read()).hexdigest())

    # --- 7. --epsilon -------------------------------------------------------------------------

    def test_epsilon_is_recorded_and_eval_judges_by_it(self):
        exact = self.script("exact", 'echo "1 9"\necho "3 4"\n')
        approx = self.script("approx", 'echo "1 9"\necho "3 5"\n')
        self.run_solver(exact, output="ref.sol")
        self.run_solver(approx, "--epsilon", "0.25", output="apx.sol")
        self.assertEqual(self.inspect("apx.sol")["epsilon"], "0.25")
        r = self.mosb("eval", "--reference", self.path("ref.sol"), "--solutions",
                      self.path("apx.sol"), "--eps", "0.25")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertNotIn("SOLVER BUG", r.stdout)

    # --- 9. an output that is an input --------------------------------------------------------

    def test_the_instance_is_never_the_output(self):
        before = mosbtest.read(self.grid)
        solver = self.script("solver", 'echo "1 1"\n')
        r = self.run_mosb("run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                          solver, "-o", self.grid)
        self.assert_one_line_error(r, "grid.mosb")
        self.assertIn("same file", r.stderr)
        self.assertEqual(mosbtest.read(self.grid), before)

    # --- 10. floods -------------------------------------------------------------------------------

    def test_an_output_flood_fails_the_query_within_the_limit(self):
        info, r = self.one_query("yes '1 1' | head -c 300000000\n", "--max-output", "1M",
                                 "--time-limit", "60s")
        self.assertEqual(info["statuses"]["failed"], 1)
        self.assertIn("output limit of 1048576 bytes", r.stderr)
        # A compressed log may not decode past it either.
        body = ("head -c 50000000 /dev/zero | gzip -1 > \"$4\"\n")
        self.one()
        solver = self.script("bomb", body)
        r = self.run_solver(solver + " {query} {source} {target} {front} #", "--output-format",
                            "json-log", "--max-output", "1M", queries="one")
        self.assertEqual(self.inspect()["statuses"]["failed"], 1)
        self.assertIn("more than 1048576 bytes of text (the output limit)", r.stderr)

    # --- 11. one bad statistic fails its query, not the run -----------------------------------

    def test_a_reserved_statistic_fails_that_query_only(self):
        solver = self.script("solver", 'echo "$(($1 + 1)) 1"\nif [ "$1" = 1 ]; then '
                                       'echo "mosb: expanded=18446744073709551615" >&2; fi\n')
        r = self.run_solver(solver)
        info = self.inspect()
        self.assertEqual((info["statuses"]["solved"], info["statuses"]["failed"]), (3, 1))
        self.assertIn("query 1", r.stderr)
        self.assertIn("below 2^64 - 1", r.stderr)

    # --- 13. packed instances -----------------------------------------------------------------

    def test_a_packed_instance_is_refused_before_any_solver_starts(self):
        self.ok("pack", self.grid, "-o", self.path("packed.mosb"))
        solver = self.script("solver", 'record %s\necho "1 1"\n' % self.pids)
        r = self.run_mosb("run", self.path("packed.mosb"), "--view", "Grid_2", "--queries", "q",
                          "--solver", solver, "-o", self.path("out.sol"))
        self.assert_one_line_error(r, "a packed instance")
        self.assertIn("mosb unpack", r.stderr)
        self.assertIn("mosb store instance", r.stderr)
        self.assertFalse(os.path.exists(self.pids))

    # --- 14. temporaries ------------------------------------------------------------------------

    def temporaries(self):
        return sorted(n for n in os.listdir(self.path("tmp")) if n.startswith("mosb-run-"))

    def test_temporaries_of_a_killed_run_are_swept_and_a_closed_pipe_leaves_none(self):
        os.makedirs(self.path("tmp"))
        env = dict(os.environ, TMPDIR=self.path("tmp"))
        slow = self.script("slow", 'sleep 30\n')
        p = subprocess.Popen([mosbtest.MOSB, "run", self.grid, "--view", "Grid_2", "--queries", "q",
                              "--solver", slow, "-o", self.path("killed.sol")], env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and not self.temporaries():
            time.sleep(0.02)
        time.sleep(0.2)
        p.kill()
        p.wait()
        self.assertEqual(len(self.temporaries()), 1)
        quick = self.script("quick", 'echo "1 1"\n')
        # The next run sweeps it; its output through a pipe closed early leaves none either.
        r = subprocess.run("%s run %s --view Grid_2 --queries q --solver %s -o %s | head -c 1" %
                           (mosbtest.MOSB, self.grid, quick, self.path("piped.sol")), shell=True,
                           env=env, capture_output=True, text=True, timeout=120)
        self.assertEqual(self.temporaries(), [], r.stderr)

    # --- 15. messages -------------------------------------------------------------------------

    def test_a_solver_name_that_is_not_utf8_is_escaped_or_refused_before_anything_runs(self):
        # The solution file's metadata is UTF-8: an executable named by bytes that are not is
        # recorded escaped (the file reads back); a --solver-name that is not is refused at once.
        solver = self.script("na\udce9ve", 'record %s\necho "$(($1 + 1)) 1"\n' % self.pids)
        self.run_solver(solver)
        self.assertEqual(self.inspect()["solver"], "na\\xe9ve")
        os.remove(self.pids)
        r = self.run_mosb("run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                          solver + " {query}", "--solver-name", "x\udcff", "-o",
                          self.path("named.sol"))
        self.assert_one_line_error(r, "the solver's name or version is not valid UTF-8")
        self.assertFalse(os.path.exists(self.pids), "a solver ran before the refusal")
        self.assertFalse(os.path.exists(self.path("named.sol.journal")))

    def test_messages_say_what_happened(self):
        r = self.run_mosb("run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                          "{instance} x", "-o", self.path("out.sol"))
        self.assert_one_line_error(r, "is a placeholder", code=2)
        # A solver refused by rlimit-poll's address-space backstop: the message names the limit.
        info, r = self.one_query(
            "exec /usr/bin/python3 -c 'x = bytearray(3 << 30)'\n", "--measurement", "rlimit-poll",
            "--memory-limit", "1G")
        self.assertEqual(info["statuses"]["failed"], 1)
        self.assertIn("address space is limited to twice the memory limit", r.stderr)


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
