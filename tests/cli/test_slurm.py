#!/usr/bin/python3
"""`mosb run --shard`, `mosb solutions merge` and `mosb run --slurm` (spec/RUN.md §7-8), the last on
a real single-node SLURM cluster that tools/slurm-cluster.sh starts on this machine.

    MOSB=build/release/tools/mosb EXAMPLES=build/release/examples /usr/bin/python3 tests/cli/test_slurm.py

ShardsAndMerge runs everywhere. SlurmCluster needs root and Debian's slurm-wlm and munge
(tools/install-deps.sh installs them; CI runs as root) and skips, saying so, only without them. It
runs the README's "The same on SLURM" block as written (its `sudo` dropped, as root), then starts
the cluster again for a run whose shard 3 is cancelled midway by `scancel`: merge must report
exactly shard 3's queries missing, `--resume` must resubmit only shard 3, whose task continues the
journal the cancelled one left, and the final merge must equal a local run. Every daemon is
stopped by its PID (`slurm-cluster.sh stop`, then whatever a pid file still names) whatever
happens.
"""

import glob
import json
import os
import re
import shutil
import signal
import stat
import subprocess
import time

import mosbtest
from mosbtest import CliTest, setUpModule  # noqa: F401

EXAMPLES = os.path.abspath(os.environ.get("EXAMPLES", ""))
BOA = os.path.join(EXAMPLES, "boa_star")
SCRIPT = os.path.join(mosbtest.REPOSITORY, "tools", "slurm-cluster.sh")
README_SECTION = "The same on SLURM"
WAIT_SECONDS = 60  # for an array of four small shards on one node


def require_examples(test):
    if not os.path.isfile(BOA):
        raise mosbtest.missing("EXAMPLES (the example solvers' directory) is not set")


def readme_block(heading):
    """The ```sh block under the README heading `heading`."""
    current, block, blocks = None, None, {}
    with open(os.path.join(mosbtest.REPOSITORY, "README.md"), encoding="utf-8") as f:
        for line in f:
            if block is not None:
                if line.startswith("```"):
                    blocks.setdefault(current, "".join(block))
                    block = None
                else:
                    block.append(line)
            elif line.startswith("```sh"):
                block = []
            elif line.startswith("#"):
                current = line.lstrip("#").strip()
    return blocks[heading]


class ShardsAndMerge(CliTest):
    """--shard and merge on this machine, and --slurm up to (not including) sbatch."""

    def setUp(self):
        super().setUp()
        require_examples(self)
        self.ok("generate", "grid", "--width", "12", "--height", "12", "--objectives", "2", "-o",
                self.path("grid.mosb"))
        self.ok("queries", "generate", self.path("grid.mosb"), "--set", "q", "--count", "10",
                "--in-place")
        self.grid = self.path("grid.mosb")
        self.template = BOA + " {instance} --view {view} --query {source} {target} --protocol"

    def run_boa(self, output, *extra, code=0, limit="60s"):
        r = self.mosb("run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                      self.template, "--time-limit", limit, *extra, "-o", self.path(output))
        self.assertEqual(r.returncode, code, r)
        return r

    def inspect(self, name):
        return json.loads(self.ok("solutions", "inspect", "--json", self.path(name)).stdout)

    def merge(self, *names, output="all.sol", code=0, extra=()):
        r = self.mosb("solutions", "merge", *[self.path(n) for n in names], "-o",
                      self.path(output), *extra)
        self.assertEqual(r.returncode, code, r)
        return r

    def test_shards_partition_the_queries_and_merge_into_the_full_run(self):
        for i in (1, 2, 3):
            r = self.run_boa("s%d.sol" % i, "--shard", "%d/3" % i, "--json")
            self.assertEqual(json.loads(r.stdout)["shard"], "%d/3" % i)
            info = self.inspect("s%d.sol" % i)
            self.assertEqual(info["parameters"]["run.shard"], "%d/3" % i)
            self.assertEqual(info["queries"], 10)  # the same binding: the whole query set
            shard_size = len(range(i - 1, 10, 3))
            self.assertEqual(info["statuses"]["solved"], shard_size)
            self.assertEqual(info["statuses"]["not-run"], 10 - shard_size)
        self.run_boa("full.sol")
        self.merge("s2.sol", "s3.sol", "s1.sol")
        self.merge("s1.sol", "s2.sol", "s3.sol", output="again.sol")
        self.assertEqual(mosbtest.read(self.path("all.sol")), mosbtest.read(self.path("again.sol")),
                         "the merged bytes depend on the input order")
        self.ok("solutions", "compare", self.path("full.sol"), self.path("all.sol"))
        self.ok("solutions", "verify", "--instance", self.grid, self.path("all.sol"))
        merged, full = self.inspect("all.sol"), self.inspect("full.sol")
        self.assertEqual(merged["statuses"], full["statuses"])
        self.assertEqual(merged["parameters"]["run.shards"], "3")
        self.assertNotIn("run.shard", merged["parameters"])
        self.assertEqual(merged["parameters"]["run.template"], full["parameters"]["run.template"])

    def test_merge_says_what_is_missing(self):
        self.run_boa("s1.sol", "--shard", "1/3")
        self.run_boa("s3.sol", "--shard", "3/3")
        r = self.merge("s1.sol", "s3.sol", code=1)
        self.assertIn("missing: 3 of 10 queries", r.stdout)
        self.assertIn("shard 2/3 (no input): 3 queries: 1, 4, 7", r.stdout)
        self.assertIn("not written", r.stderr)
        self.assertFalse(os.path.exists(self.path("all.sol")))
        r = self.merge("s1.sol", "s3.sol", code=1, extra=("--json",))
        report = json.loads(r.stdout)
        self.assertEqual((report["written"], report["missing"], report["absent_shards"]),
                         (False, [1, 4, 7], [2]))
        r = self.merge("s1.sol", "s3.sol", extra=("--allow-missing", "--json"))
        self.assertTrue(json.loads(r.stdout)["written"])
        self.assertEqual(self.inspect("all.sol")["statuses"]["not-run"], 3)

    def test_merge_refuses_parts_that_do_not_belong_together(self):
        self.run_boa("s1.sol", "--shard", "1/2")
        self.run_boa("s2-30s.sol", "--shard", "2/2", limit="30s")
        r = self.merge("s1.sol", "s2-30s.sol", code=2)
        self.assert_one_line_error(r, "s2-30s.sol: differs from ", "s1.sol in "
                                   "solution.solver.param.run.time_limit_seconds '30', not '60'",
                                   code=2)
        self.run_boa("s2of3.sol", "--shard", "2/3")
        r = self.merge("s1.sol", "s2of3.sol", code=2)
        self.assert_one_line_error(r, "s2of3.sol: is shard 2/3, but ", "is one of 2 shards", code=2)
        self.run_boa("full.sol")
        self.run_boa("full2.sol")
        r = self.merge("full.sol", "full2.sol", code=2)
        self.assert_one_line_error(r, "full2.sol: query 0 is also in", "the inputs overlap",
                                   code=2)
        self.ok("generate", "grid", "--width", "12", "--height", "12", "--objectives", "2",
                "--seed", "2", "-o", self.path("other.mosb"))
        self.ok("queries", "generate", self.path("other.mosb"), "--set", "q", "--count", "10",
                "--in-place")
        self.grid = self.path("other.mosb")
        self.run_boa("s2-other.sol", "--shard", "2/2")
        r = self.merge("s1.sol", "s2-other.sol", code=2)
        self.assert_one_line_error(r, "s2-other.sol: another instance (digest", code=2)
        self.assertFalse(os.path.exists(self.path("all.sol")))

    def test_bad_shards_are_usage_errors(self):
        for bad in ("0/2", "3/2", "1/0", "x", "1/2/3"):
            r = self.run_boa("s.sol", "--shard", bad, code=2)
            self.assertIn("--shard %s: not i/N with 1 <= i <= N" % bad, r.stderr)
        r = self.run_boa("s.sol", "--shards", "2", code=2)
        self.assertIn("--shards: only with --slurm DIR", r.stderr)
        self.assertFalse(os.path.exists(self.path("s.sol.journal")))

    def test_slurm_directory_without_a_cluster(self):
        base = ["run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver", self.template,
                "--time-limit", "60s", "--memory-limit", "1G"]
        r = self.mosb(*base, "--slurm", self.path("job"))
        self.assert_one_line_error(r, "give --shards N or --queries-per-task K", code=2)
        r = self.mosb(*base, "--slurm", self.path("job"), "--shards", "11")
        self.assert_one_line_error(r, "--shards 11: the query set has only 10 queries", code=2)
        r = self.mosb(*base, "--slurm", self.path("job"), "--shards", "2", "-o", "x.sol")
        self.assert_one_line_error(r, "--output: not with --slurm DIR", code=2)
        r = self.ok(*base, "--slurm", self.path("job"), "--queries-per-task", "3", "--throttle",
                    "2", "--partition", "short")
        self.assertIn("4 shards of the 10 queries", r.stdout)
        self.assertIn("submit with: sbatch --parsable %s/run.sbatch >> %s/jobs"
                      % (self.path("job"), self.path("job")), r.stdout)
        script = mosbtest.read(self.path("job", "run.sbatch"), "r")
        for line in ("#SBATCH --array=1-4%2", "#SBATCH --time=0-00:09:00", "#SBATCH --mem=1536M",
                     "#SBATCH --partition=short", "--shard \"$shard\"/4 --resume -o "):
            self.assertIn(line, script)
        self.assertIn(os.path.realpath(mosbtest.MOSB), script)
        r = self.mosb(*base, "--slurm", self.path("job"), "--shards", "2")
        self.assert_one_line_error(r, "holds a run already")
        # A run.json whose kind was edited: refused, naming it (escaped for the terminal).
        shutil.copy(self.path("job", "run.json"), self.path("run.json.kept"))
        with open(self.path("job", "run.json")) as f:
            edited = json.load(f)
        edited["kind"] = "other\x1b"
        with open(self.path("job", "run.json"), "w") as f:
            json.dump(edited, f)
        r = self.mosb("run", "--slurm", self.path("job"), "--status")
        self.assert_one_line_error(r, "run.json: a job array of kind 'other\\x1b' (made by mosb "
                                   "run), not of kind 'run'")
        # Another kind's array names the command that made it.
        edited["kind"] = "experiment"
        edited["command"] = ["experiment", "run"]
        with open(self.path("job", "run.json"), "w") as f:
            json.dump(edited, f)
        r = self.mosb("run", "--slurm", self.path("job"), "--status")
        self.assert_one_line_error(r, "a job array of kind 'experiment' (made by mosb experiment "
                                   "run), not of kind 'run'; continue it with the command that "
                                   "made it")
        shutil.copy(self.path("run.json.kept"), self.path("job", "run.json"))
        # The same command writes the same script.
        shutil.rmtree(self.path("job"))
        self.ok(*base, "--slurm", self.path("job"), "--queries-per-task", "3", "--throttle", "2",
                "--partition", "short")
        self.assertEqual(mosbtest.read(self.path("job", "run.sbatch"), "r"), script)
        status = json.loads(self.ok("run", "--slurm", self.path("job"), "--status",
                                    "--json").stdout)
        self.assertEqual([s["file"] for s in status["shard_states"]], ["missing"] * 4)
        self.assertEqual([s["queries"] for s in status["shard_states"]], [3, 3, 2, 2])
        # A shard run by hand counts as done; resuming would resubmit the others.
        r = self.mosb("run", self.grid, "--view", "Grid_2", "--queries", "q", "--solver",
                      self.template, "--time-limit", "60s", "--memory-limit", "1G", "--shard",
                      "2/4", "-o", self.path("job", "shard-2.sol"))
        self.assertEqual(r.returncode, 0, r)
        resume = json.loads(self.ok("run", "--slurm", self.path("job"), "--resume",
                                    "--json").stdout)
        self.assertEqual(resume["resubmit"], [1, 3, 4])
        self.assertEqual(resume["sbatch"], "sbatch --parsable --array=1,3-4%%2 %s/run.sbatch >> "
                         "%s/jobs" % (self.path("job"), self.path("job")))
        r = self.mosb("run", "--slurm", self.path("job"), "--resume", "--time-limit", "1s")
        self.assert_one_line_error(r, "--time-limit: not with --slurm DIR --resume", code=2)
        r = self.mosb("run", "--slurm", self.path("nothing"), "--status")
        self.assert_one_line_error(r, "run.json: no such file")
        # No sbatch: the directory is kept, and the message says how to submit it later.
        r = self.mosb(*base, "--slurm", self.path("later"), "--shards", "2", "--submit",
                      env=dict(os.environ, PATH=self.path("no-such-dir")))
        self.assert_one_line_error(r, "sbatch: no such program in PATH", "is written: submit it "
                                   "with mosb run --slurm %s --resume --submit" % self.path("later"))
        self.assertTrue(os.path.exists(self.path("later", "run.sbatch")))

    # A value for every option of `mosb run` (other than the defaults), by what it is to a SLURM
    # run: `run` options define the run and must reach every task (run.json's run_arguments) and be
    # refused by --slurm DIR --resume and --status; `local` ones are refused with --slurm DIR;
    # `plan` ones are recorded in run.json and refused on --resume; `action` ones are accepted.
    # An option missing here fails the test: a new option must say which it is.
    OPTIONS = {
        "--view": ("run", ["Grid_2"]), "--objectives": ("run", ["c2,c1"]),
        "--queries": ("run", ["q"]), "--solver": ("run", None),
        "--time-limit": ("run", ["7s"]), "--cpu-limit": ("run", ["5"]),
        "--memory-limit": ("run", ["3G"]), "--grace": ("run", ["2.5"]), "--jobs": ("run", ["2"]),
        "--pin": ("run", []), "--threads": ("run", ["3"]),
        "--output-format": ("run", ["json-log"]), "--measurement": ("run", ["rlimit-poll"]),
        "--isolation": ("run", ["none"]),
        "--solver-name": ("run", ["boa-x"]), "--solver-version": ("run", ["v9"]),
        "--epsilon": ("run", ["0.05"]), "--max-output": ("run", ["2G"]),
        "--allow-new-executable": ("run", []),
        # With --profile only (not with --solver): test_profiles.py checks that tasks get them.
        "--profile": ("run", None), "--executable": ("run", None),
        "--profile-option": ("run", None), "--scale": ("run", None),
        "--export-cache": ("run", None), "--list-profiles": ("action", None),
        "--output": ("local", ["x.sol"]), "--shard": ("local", ["1/2"]),
        "--shards": ("plan", ["2"]), "--queries-per-task": ("plan", ["3"]),
        "--throttle": ("plan", ["1"]), "--account": ("plan", ["acct"]),
        "--partition": ("plan", ["part"]),
        "--submit": ("action", []), "--resume": ("action", []), "--status": ("action", []),
        "--json": ("action", []), "--slurm": ("action", None), "--help": ("action", None),
    }

    def test_every_option_is_passed_on_or_refused_with_slurm(self):
        help_text = self.ok("run", "--help").stdout
        listed = set(re.findall(r"^  (?:-\w,)?(--[a-z-]+)", help_text, re.M))
        self.assertEqual(listed, set(self.OPTIONS), "mosb run's options and this test's table")
        base = ["run", self.grid, "--solver", self.template]
        for option, (role, value) in sorted(self.OPTIONS.items()):
            # --slurm and --help take no part; --resume and --status are the other mode of
            # --slurm DIR, which every other option meets below.
            if value is None or option in ("--resume", "--status"):
                continue
            with self.subTest(option=option):
                job = self.path("job" + option)
                given = [option] + value
                # --view excludes --objectives; --queries-per-task excludes --shards.
                choice = [] if option in ("--view", "--objectives") else ["--view", "Grid_2"]
                choice += [] if option == "--queries" else ["--queries", "q"]
                shards = [] if option in ("--shards", "--queries-per-task") else ["--shards", "2"]
                r = self.mosb(*base, *choice, *shards, *given, "--slurm", job,
                              env=dict(os.environ, PATH=self.path("no-sbatch-here")))
                if role == "local":
                    self.assert_one_line_error(r, "%s: not with --slurm DIR" % option, code=2)
                    continue
                if option == "--submit":
                    self.assert_one_line_error(r, "sbatch: no such program in PATH")
                else:
                    self.assertEqual(r.returncode, 0, r)
                run_json = json.loads(mosbtest.read(os.path.join(job, "run.json"), "r"))
                arguments = run_json["run_arguments"]
                if role == "run":
                    at = arguments.index(option)
                    # Sizes reach the tasks in bytes.
                    passed = {"--memory-limit": [str(3 << 30)], "--max-output": [str(2 << 30)]}
                    self.assertEqual(arguments[at + 1:at + 1 + len(value)],
                                     passed.get(option, value))
                elif role == "plan":
                    self.assertNotIn(option, arguments)
                for action in ("--resume", "--status"):
                    r = self.mosb("run", "--slurm", job, action, *given,
                                  env=dict(os.environ, PATH=self.path("no-sbatch-here")))
                    if role in ("run", "plan"):
                        self.assert_one_line_error(
                            r, "%s: not with --slurm DIR --resume or --status" % option, code=2)
                    elif option == "--submit" and action == "--status":
                        self.assert_one_line_error(r, "--submit: not with --status", code=2)
                    elif option in ("--resume", "--status") and option != action:
                        self.assert_one_line_error(r, "--status: not with --resume", code=2)
                    elif option == "--submit":
                        self.assert_one_line_error(r, "sbatch: no such program in PATH")
                    else:
                        self.assertEqual(r.returncode, 0, r)


# --- the cluster ----------------------------------------------------------------------------

def tail(path, lines=25):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError as e:
        return "(%s)\n" % e


class SlurmCluster(CliTest):
    leaves_temporaries = True  # a task cancelled on purpose

    def setUp(self):
        super().setUp()
        if os.geteuid() != 0:
            raise mosbtest.missing("not root: slurmd must run as root (CI runs as root)")
        missing = [p for p in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "scancel",
                               "sinfo") if not shutil.which(p, path=os.environ.get("PATH", "") +
                                                            ":/usr/sbin:/sbin")]
        if missing:
            raise mosbtest.missing("SLURM is not installed (no %s; apt-get install slurm-wlm munge)"
                          % ", ".join(missing))
        require_examples(self)
        self.state = self.path("cluster")
        self.env = dict(os.environ, MOSB_SLURM_DIR=self.state,
                        SLURM_CONF=os.path.join(self.state, "slurm.conf"),
                        PATH=os.environ.get("PATH", "/usr/bin:/bin") + ":/usr/sbin:/sbin")
        # The README's paths: build/release and tools/ as seen from the repository root.
        os.makedirs(self.path("build"))
        os.symlink(os.path.dirname(os.path.dirname(mosbtest.MOSB)), self.path("build", "release"))
        os.symlink(os.path.join(mosbtest.REPOSITORY, "tools"), self.path("tools"))
        self.addCleanup(self.stop_cluster)

    # -- helpers ------------------------------------------------------------------------------

    def cluster(self, command, timeout=120):
        return subprocess.run(["bash", SCRIPT, command], env=self.env, cwd=self.dir, text=True,
                              capture_output=True, timeout=timeout)

    def stop_cluster(self):
        """`slurm-cluster.sh stop`; then any daemon a pid file still names, by that PID."""
        try:
            self.cluster("stop")
        finally:
            for pidfile in glob.glob(os.path.join(self.state, "pids", "*.pid")):
                try:
                    pid = int(mosbtest.read(pidfile, "r").split()[0])
                    os.kill(pid, signal.SIGKILL)
                except (OSError, ValueError, IndexError):
                    pass

    def logs(self, directory=None):
        text = ""
        for name in ("slurmctld.log", "slurmd.log", "munged.log"):
            text += "--- %s\n%s" % (name, tail(os.path.join(self.state, "log", name)))
        for log in sorted(glob.glob(os.path.join(directory or self.dir, "shard-*.log"))):
            text += "--- %s\n%s" % (log, tail(log, 10))
        return text

    def start_cluster(self):
        r = self.cluster("start")
        self.assertEqual(r.returncode, 0, "slurm-cluster.sh start failed:\n%s%s\n%s"
                         % (r.stdout, r.stderr, self.logs()))

    def squeue(self, *args):
        return subprocess.run(["squeue", "-h", *args], env=self.env, text=True,
                              capture_output=True, timeout=30)

    def wait_until(self, what, done, directory=None, seconds=WAIT_SECONDS):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            if done():
                return
            time.sleep(0.25)
        self.fail("%s: not within %d s\nsqueue:\n%s\n%s"
                  % (what, seconds, self.squeue("-t", "all").stdout, self.logs(directory)))

    def wait_for_queue_to_empty(self, directory):
        self.wait_until("the array's tasks finish",
                        lambda: self.squeue().returncode == 0 and not self.squeue().stdout.strip(),
                        directory)

    def m(self, *args, code=0):
        r = self.mosb(*args, env=self.env)
        self.assertEqual(r.returncode, code, r)
        return r

    def statuses(self, name):
        return json.loads(self.m("solutions", "inspect", "--json", self.path(name)).stdout)[
            "statuses"]

    # -- the test -----------------------------------------------------------------------------

    def test_readme_then_a_cancelled_shard_resumed(self):
        started = time.monotonic()
        # 1. The README's block, as written (as root, without sudo).
        block = readme_block(README_SECTION)
        self.assertIn("tools/slurm-cluster.sh start", block)
        self.assertIn("--slurm boa-slurm --shards 4 --submit", block)
        script = re.sub(r"\bsudo ", "", block)
        done = subprocess.run(["bash", "-euo", "pipefail", "-c", script], cwd=self.dir,
                              env=self.env, text=True, capture_output=True,
                              timeout=WAIT_SECONDS + 60)
        self.assertEqual(done.returncode, 0, "README's '%s' block failed:\n%s\n--- stdout\n%s\n"
                         "--- stderr\n%s\n%s" % (README_SECTION, script, done.stdout[-3000:],
                                                 done.stderr[-3000:],
                                                 self.logs(self.path("boa-slurm"))))
        self.assertIn("summary: 4 done", done.stdout)
        self.assertIn("wrote boa-slurm.sol: 40 queries from 4 files", done.stdout)
        self.m("run", self.path("grid40.mosb"), "--view", "Grid_2", "--queries", "q", "--solver",
               BOA + " {instance} --view {view} --query {source} {target} --protocol",
               "--time-limit", "60s", "-o", self.path("local.sol"))
        self.m("solutions", "compare", self.path("local.sol"), self.path("boa-slurm.sol"))
        self.assertEqual(self.statuses("boa-slurm.sol"), self.statuses("local.sol"))
        self.assertEqual(self.statuses("local.sol")["solved"], 40)
        self.assertNotIn("running, PID", self.cluster("status").stdout)  # the block stopped it

        # 2. A shard cancelled midway: its second query hangs until the test lets it go.
        self.start_cluster()
        marks, hold = self.path("marks"), self.path("hold")
        os.makedirs(marks)
        open(hold, "w").close()
        solver = self.write("solver.sh", "#!/bin/sh\necho x >> %s/$1\n"
                            "if [ -e %s ] && [ \"$1\" = 6 ]; then sleep 300; fi\n"
                            "shift\nexec %s \"$@\" --protocol\n" % (marks, hold, BOA))
        os.chmod(solver, os.stat(solver).st_mode | stat.S_IXUSR)
        job_dir = self.path("job")
        r = self.m("run", self.path("grid40.mosb"), "--view", "Grid_2", "--queries", "q",
                   "--solver", solver + " {query} {instance} --view {view} --query {source} "
                   "{target}", "--time-limit", "60s", "--memory-limit", "1G", "--slurm", job_dir,
                   "--shards", "4", "--throttle", "4", "--submit", "--json")
        job = json.loads(r.stdout)["job"]
        journal = os.path.join(job_dir, "shard-3.sol.journal")

        def hanging():  # query 2 recorded, query 6 started
            return (os.path.exists(os.path.join(marks, "6")) and os.path.exists(journal)
                    and mosbtest.read(journal, "r").count("\n") >= 2)
        self.wait_until("shard 3 reaches its hanging query", hanging, job_dir)
        subprocess.run(["scancel", "%s_3" % job], env=self.env, check=True, timeout=30)
        self.wait_for_queue_to_empty(job_dir)
        self.assertFalse(os.path.exists(os.path.join(job_dir, "shard-3.sol")))

        status = json.loads(self.m("run", "--slurm", job_dir, "--status", "--json").stdout)
        files = {s["shard"]: (s["file"], s["recorded"]) for s in status["shard_states"]}
        self.assertEqual(files, {1: ("done", 10), 2: ("done", 10), 3: ("partial", 1),
                                 4: ("done", 10)}, status)
        self.assertIn("squeue", status["scheduler"])
        self.assertEqual(status["shard_states"][2]["state"], "CANCELLED", status)
        self.assertEqual(status["shard_states"][0]["state"], "COMPLETED", status)

        shards = sorted(glob.glob(os.path.join(job_dir, "shard-*.sol")))
        r = self.m("solutions", "merge", *shards, "-o", self.path("all.sol"), code=1)
        self.assertIn("shard 3/4 (no input): 10 queries: 2, 6, 10, 14, 18, 22, 26, 30, 34, 38",
                      r.stdout)
        r = self.m("solutions", "merge", *shards, "-o", self.path("all.sol"), "--json", code=1)
        report = json.loads(r.stdout)
        self.assertEqual(report["missing"], list(range(2, 40, 4)))
        self.assertEqual(report["absent_shards"], [3])

        # 3. --resume resubmits shard 3 alone; its task continues the journal.
        os.remove(hold)
        r = self.m("run", "--slurm", job_dir, "--resume", "--submit", "--json")
        resumed = json.loads(r.stdout)
        self.assertEqual(resumed["resubmit"], [3])
        self.assertIsNotNone(resumed["job"])
        self.wait_for_queue_to_empty(job_dir)
        self.assertEqual(mosbtest.read(os.path.join(marks, "2"), "r"), "x\n",
                         "the query the cancelled task finished ran again")
        self.assertEqual(mosbtest.read(os.path.join(marks, "6"), "r"), "x\nx\n")
        self.assertEqual(mosbtest.read(os.path.join(marks, "0"), "r"), "x\n")
        r = self.m("run", "--slurm", job_dir, "--resume", "--json")
        self.assertEqual(json.loads(r.stdout)["resubmit"], [])
        shards = sorted(glob.glob(os.path.join(job_dir, "shard-*.sol")))
        self.m("solutions", "merge", *shards, "-o", self.path("all.sol"))
        self.m("solutions", "compare", self.path("local.sol"), self.path("all.sol"))
        self.assertEqual(self.statuses("all.sol"), self.statuses("local.sol"))
        self.m("solutions", "verify", "--instance", self.path("grid40.mosb"), self.path("all.sol"))

        r = self.cluster("stop")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(glob.glob(os.path.join(self.state, "pids", "*.pid")), [],
                         "pid files left after stop")
        print("cluster test: %.1f s" % (time.monotonic() - started))


if __name__ == "__main__":
    mosbtest.main()
