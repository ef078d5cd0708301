#!/usr/bin/python3
"""Sealed queries (spec/RUN.md §4.1) and pinned programs (§6): from inside a query, a hostile solver tries to write the
instance, the export cache, the journal, another query's stdout, another run's directory and
$HOME, and to reach a server on the machine's loopback. Sealed (the default), all fail and each
query's front is its own; with --isolation none the same solver succeeds at every one of them (so
the attacks are real). As root and as an unprivileged user (setpriv).

    MOSB=build/release/tools/mosb EXAMPLES=build/release/examples /usr/bin/python3 tests/cli/test_seal.py
"""

import json
import os
import shutil
import socket
import subprocess
import threading
import time

import mosbtest
from mosbtest import FINISHED, CliTest, assert_finished, setUpModule  # noqa: F401

EXAMPLES = os.path.abspath(os.environ.get("EXAMPLES", ""))
NOBODY = 65534

# The attacks, then the honest search: its front is the query's answer unless an attack landed.
HOSTILE = r"""#!/bin/bash
instance=$1; shift
echo 1 >> "$instance"
echo poisoned >> "$CACHE_FILE"
echo '{"query": 0, "status": "solved"}' >> "$JOURNAL"
own=$(readlink /proc/$$/fd/1)
for f in "$RUNS"/mosb-run-*/job*/q*/stdout; do
  [ "$f" != "$own" ] && echo "0 0" >> "$f"
done
echo planted > "$OTHER_RUN/planted"
echo planted > "$HOME/planted"
(exec 3<>"/dev/tcp/127.0.0.1/$PORT" && echo hello >&3)
sleep 0.2
exec "$NAMOA" "$instance" "$@"
"""


class Listener:
    """A TCP server on 127.0.0.1 counting the connections it accepts."""

    def __init__(self):
        self.socket = socket.socket()
        self.socket.bind(("127.0.0.1", 0))
        self.socket.listen(16)
        self.socket.settimeout(0.2)
        self.port = self.socket.getsockname()[1]
        self.connections = 0
        self.stopped = False
        self.thread = threading.Thread(target=self.serve, daemon=True)
        self.thread.start()

    def serve(self):
        while not self.stopped:
            try:
                connection, _ = self.socket.accept()
            except OSError:
                continue
            self.connections += 1
            connection.close()

    def stop(self):
        self.stopped = True
        self.thread.join()
        self.socket.close()


class Seal(CliTest):
    def setUp(self):
        super().setUp()
        if not os.path.isfile(os.path.join(EXAMPLES, "namoa")):
            raise mosbtest.missing("EXAMPLES (the example solvers' directory) is not set")
        os.chmod(self.dir, 0o777)  # the unprivileged runs write here
        self.ok("generate", "grid", "--width", "5", "--height", "5", "--objectives", "2", "-o",
                self.path("bare.mosb"))
        self.ok("queries", "generate", self.path("bare.mosb"), "--set", "q", "--count", "4",
                "-o", self.path("grid.mosb"))
        self.ok("run", self.path("grid.mosb"), "--view", "Grid_2", "--queries", "q", "--solver",
                os.path.join(EXAMPLES, "namoa") + " {instance} --view {view} --query {source} "
                "{target} --protocol", "-o", self.path("reference.sol"))
        self.hostile = self.write("hostile.sh", HOSTILE)
        os.chmod(self.hostile, 0o755)
        self.listener = Listener()
        self.addCleanup(self.listener.stop)

    def attack(self, isolation, user=None):
        """The hostile solver over every query, two at a time, as root or `user`; returns what
        mosb printed and what each target holds afterwards."""
        tag = "%s-%s" % (isolation, user or "root")
        root = self.path(tag)
        for d in ("cache", "other-run", "home", "runs"):
            os.makedirs(os.path.join(root, d))
        instance = os.path.join(root, "grid.mosb")
        shutil.copy(self.path("grid.mosb"), instance)
        cache_file = self.write(os.path.join(tag, "cache", "NY.gr"), "p sp 1 0\n")
        output = os.path.join(root, "out.sol")
        env = dict(os.environ, CACHE_FILE=cache_file, JOURNAL=output + ".journal",
                   RUNS=os.path.join(root, "runs"), TMPDIR=os.path.join(root, "runs"),
                   OTHER_RUN=os.path.join(root, "other-run"), HOME=os.path.join(root, "home"),
                   PORT=str(self.listener.port), NAMOA=os.path.join(EXAMPLES, "namoa"))
        env.pop("MOSB_ISOLATION", None)  # the default: sealed
        program = mosbtest.MOSB
        command = []
        if user is not None:
            for path, mode in ((root, 0o777), (instance, 0o666), (cache_file, 0o666)):
                os.chmod(path, mode)
            for d in ("cache", "other-run", "home", "runs"):
                os.chmod(os.path.join(root, d), 0o777)
            program = self.path("mosb-copy")
            if not os.path.exists(program):
                shutil.copy(mosbtest.MOSB, program)
                os.chmod(program, 0o755)
            command = ["setpriv", "--reuid=%d" % user, "--regid=%d" % user, "--clear-groups"]
        args = ["run", instance, "--view", "Grid_2", "--queries", "q", "--jobs", "2", "--solver",
                self.hostile + " {instance} --view {view} --query {source} {target} --protocol",
                "-o", output]
        if isolation != "default":
            args += ["--isolation", isolation]
        r = subprocess.run(command + [program] + args, capture_output=True, text=True,
                           timeout=300, cwd=root, env=env)
        # Unsealed, the attack rewrites the instance, and every query fails: exit 3.
        assert_finished(self, r, FINISHED, [output])
        return {
            "instance": mosbtest.read(instance) == mosbtest.read(self.path("grid.mosb")),
            "cache": mosbtest.read(cache_file, "r") == "p sp 1 0\n",
            "other_run": os.listdir(os.path.join(root, "other-run")),
            "home": os.listdir(os.path.join(root, "home")),
            "output": output,
        }

    def fronts_are_the_reference(self, output):
        r = json.loads(self.ok("solutions", "compare", "--json", self.path("reference.sol"),
                               output).stdout)
        return r["ok"] and r["equal"] == 4

    def check_sealed(self, user=None):
        before = self.listener.connections
        got = self.attack("default", user=user)
        self.assertTrue(got["instance"], "the instance was written")
        self.assertTrue(got["cache"], "the export cache was written")
        self.assertEqual(got["other_run"], [])
        self.assertEqual(got["home"], [])
        self.assertEqual(self.listener.connections, before, "a sealed solver reached a server")
        self.assertTrue(self.fronts_are_the_reference(got["output"]))
        info = json.loads(self.ok("solutions", "inspect", "--json", got["output"]).stdout)
        self.assertEqual(info["parameters"]["run.seal"], "seal")

    def test_sealed_by_default_as_root(self):
        self.check_sealed()

    def test_sealed_by_default_as_an_unprivileged_user(self):
        self.check_sealed(user=NOBODY)

    def test_unsealed_the_same_solver_reaches_everything(self):
        before = self.listener.connections
        got = self.attack("none")
        self.assertFalse(got["instance"])
        self.assertFalse(got["cache"])
        self.assertEqual(got["other_run"], ["planted"])
        self.assertEqual(got["home"], ["planted"])
        self.assertGreater(self.listener.connections, before)
        info = json.loads(self.ok("solutions", "inspect", "--json", got["output"]).stdout)
        self.assertEqual(info["parameters"]["run.seal"], "none")

    def test_a_solver_writes_its_own_directory_and_dev_shm_only(self):
        # Its {fronts} directory and a private /dev/shm are writable; its working directory (the
        # user's), /tmp and /dev/shm of the machine are not.
        probe = self.write("probe.sh", "#!/bin/sh\n"
                           "touch \"$1/mine\" /dev/shm/mosb-seal-probe || exit 3\n"
                           "touch ./cwd-file 2>/dev/null && exit 4\n"
                           "touch /tmp/mosb-seal-probe 2>/dev/null && exit 5\n"
                           "echo 1 1\n")
        os.chmod(probe, 0o755)
        env = dict(os.environ)
        env.pop("MOSB_ISOLATION", None)
        r = subprocess.run([mosbtest.MOSB, "run", self.path("grid.mosb"), "--view", "Grid_2",
                            "--queries", "q", "--solver", probe + " {fronts}", "-o",
                            self.path("probe.sol")], capture_output=True, text=True, timeout=120,
                           cwd=self.dir, env=env)
        self.assertEqual(r.returncode, 0, r)
        info = json.loads(self.ok("solutions", "inspect", "--json", self.path("probe.sol")).stdout)
        self.assertEqual(info["statuses"]["solved"], 4, r.stderr)
        self.assertFalse(os.path.exists(self.path("cwd-file")))
        self.assertFalse(os.path.exists("/tmp/mosb-seal-probe"))
        self.assertFalse(os.path.exists("/dev/shm/mosb-seal-probe"))

    def test_a_solver_holds_no_descriptor_of_mosb_or_its_fork_server(self):
        # Standard input, output and error only: the fork server's request socket, the command
        # sockets, error pipes and memory-group files of the queries forked ahead are all closed
        # before a solver executes, sealed or not, two jobs at a time; so is a log mosb inherited
        # open from whatever started it, which a sealed solver could write. (`ls` holds 3, the
        # listing.)
        probe = self.write("descriptors.sh", "#!/bin/bash\n"
                           "fds=$(ls /proc/self/fd | tr '\\n' ' ')\n"
                           "[ \"$fds\" = '0 1 2 3 ' ] || { echo \"$fds\" >&2; exit 3; }\n"
                           "echo 1 1\n")
        os.chmod(probe, 0o755)
        env = dict(os.environ)
        env.pop("MOSB_ISOLATION", None)
        log = os.open(self.path("wrapper.log"), os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
        self.addCleanup(os.close, log)
        for isolation in ("seal", "none"):
            with self.subTest(isolation=isolation):
                output = self.path("descriptors-%s.sol" % isolation)
                r = subprocess.run([mosbtest.MOSB, "run", self.path("grid.mosb"), "--view",
                                    "Grid_2", "--queries", "q", "--jobs", "2", "--isolation",
                                    isolation, "--solver", probe, "-o", output],
                                   capture_output=True, text=True, timeout=120, cwd=self.dir,
                                   env=env, pass_fds=(log,))
                self.assertEqual(r.returncode, 0, r)
                info = json.loads(self.ok("solutions", "inspect", "--json", output).stdout)
                self.assertEqual(info["statuses"]["solved"], 4, r.stderr)

    def test_output_files_replaced_by_a_fifo_a_device_or_a_link_fail_the_query(self):
        # The solver's own directory is its to change: what it leaves there that is not a regular
        # file is the query's failure, read by nobody (a FIFO would block mosb, /dev/zero never
        # end, a link make mosb read another file as the query's front).
        cases = {
            "fifo": ('d=$(dirname "$(readlink /proc/$$/fd/1)"); echo "1 1"; rm "$d/stdout"; '
                     'mkfifo "$d/stdout"', "stdout is a FIFO"),
            "zero": ('d=$(dirname "$(readlink /proc/$$/fd/1)"); echo "1 1"; rm "$d/stderr"; '
                     'ln -s /dev/zero "$d/stderr"', "stderr is a symbolic link"),
            "link": ('ln -s "%s" "$1"' % self.path("reference.sol"), "front.txt is a symbolic link"),
        }
        env = dict(os.environ)
        env.pop("MOSB_ISOLATION", None)
        for name, (body, reason) in cases.items():
            with self.subTest(name=name):
                script = self.write(name + ".sh", "#!/bin/bash\n" + body + "\n")
                os.chmod(script, 0o755)
                output = self.path(name + ".sol")
                r = subprocess.run([mosbtest.MOSB, "run", self.path("grid.mosb"), "--view",
                                    "Grid_2", "--queries", "q", "--time-limit", "20s", "--solver",
                                    script + " {front}", "-o", output], capture_output=True,
                                   text=True, timeout=120, cwd=self.dir, env=env)
                # Every query failed: the run finished, and no query completed.
                self.assertEqual(r.returncode, 3, r)
                self.assertIn("mosb: no query completed (4 failed); most often, 4 of 4: " +
                              reason + ", not a regular file", r.stderr)
                self.assertIn(reason + ", not a regular file", r.stderr)
                info = json.loads(self.ok("solutions", "inspect", "--json", output).stdout)
                self.assertEqual(info["statuses"]["failed"], 4, r.stderr)

    def test_a_bad_isolation_is_a_usage_error(self):
        r = self.mosb("run", self.path("grid.mosb"), "--view", "Grid_2", "--solver", "/bin/true",
                      "-o", self.path("x.sol"), env=dict(os.environ, MOSB_ISOLATION="lax"))
        self.assert_one_line_error(r, "MOSB_ISOLATION=lax: give one of seal, none", code=2)


class PinnedPrograms(CliTest):
    """Every query runs the program the run started with (spec/RUN.md §6): a binary through the
    descriptor opened at the start, a script and the files its template names watched."""

    def setUp(self):
        super().setUp()
        self.ok("generate", "grid", "--width", "5", "--height", "5", "--objectives", "2", "-o",
                self.path("bare.mosb"))
        self.ok("queries", "generate", self.path("bare.mosb"), "--set", "q", "--count", "10",
                "-o", self.path("grid.mosb"))

    def start(self, template, output):
        return subprocess.Popen([mosbtest.MOSB, "run", self.path("grid.mosb"), "--view", "Grid_2",
                                 "--queries", "q", "--solver", template, "-o", output],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                cwd=self.dir)

    def wait_for_queries(self, output, count):
        journal = output + ".journal"
        for _ in range(1000):
            if os.path.exists(journal) and len(mosbtest.read(journal, "r").splitlines()) > count:
                return
            time.sleep(0.01)
        self.fail("the run did not get going")

    def test_a_binary_replaced_during_the_run_changes_no_query(self):
        program = self.path("prog")
        shutil.copy("/bin/sleep", program)
        output = self.path("pinned.sol")
        run = self.start(program + " 0.1", output)
        self.wait_for_queries(output, 2)
        shutil.copy("/bin/false", self.path("other"))
        os.rename(self.path("other"), program)  # what `mv` does: a new file at the path
        out, err = run.communicate(timeout=120)
        self.assertEqual(run.returncode, 0, err)
        info = json.loads(self.ok("solutions", "inspect", "--json", output).stdout)
        self.assertEqual(info["statuses"]["disconnected"], 10, err)  # sleep's, every one

    def test_a_script_changed_during_the_run_writes_no_file(self):
        script = self.write("solver.sh", "sleep 0.1\necho 1 1\n")
        output = self.path("script.sol")
        run = self.start("/bin/bash " + script, output)
        self.wait_for_queries(output, 2)
        with open(script, "a") as f:
            f.write("echo 2 2\n")
        out, err = run.communicate(timeout=120)
        self.assertEqual(run.returncode, 1, err)
        self.assertIn(script + " changed during the run", err.splitlines()[-1])
        self.assertFalse(os.path.exists(output))
        # Resumed with the changed script: refused, naming what differs.
        r = self.mosb("run", self.path("grid.mosb"), "--view", "Grid_2", "--queries", "q",
                      "--solver", "/bin/bash " + script, "-o", output, "--resume")
        self.assertNotEqual(r.returncode, 0, r)
        self.assertIn("files", r.stderr)
        self.assertFalse(os.path.exists(output))


if __name__ == "__main__":
    mosbtest.main()
