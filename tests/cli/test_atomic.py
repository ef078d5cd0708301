#!/usr/bin/python3
"""End-to-end tests of how `mosb` writes files (lib/core/include/mosb/atomic_file.hpp): temporaries
removed on signals and write errors, stale temporaries of killed runs removed, modes, in-place
rewrites, and outputs that are an input.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_atomic.py
"""

import os
import re
import resource
import signal
import stat
import subprocess
import time

import mosbtest
from mosbtest import MOSB, CliTest, read, setUpModule  # noqa: F401

SMALL = ["generate", "grid", "--width", "5", "--height", "4", "--objectives", "2", "--seed", "7"]
BIG = ["generate", "grid", "--width", "2000", "--height", "2000", "--seed", "1"]
TEMPORARY = re.compile(r"^\.(.+)\.tmp-(\d+)-[A-Za-z0-9]{6}$")
GR = "p sp 3 3\na 1 2 5\na 2 3 7\na 3 1 2\n"


def run(*args, umask=None, fsize=None, xfsz=signal.SIG_DFL, cwd=None):
    def setup():
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        signal.signal(signal.SIGXFSZ, xfsz)
        if umask is not None:
            os.umask(umask)
        if fsize is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))
    return mosbtest.run(*args, preexec_fn=setup, cwd=cwd)


def mode(path):
    return stat.S_IMODE(os.stat(path).st_mode)


class Base(CliTest):
    def temporaries(self, directory=None):
        return sorted(n for n in os.listdir(directory or self.dir) if ".tmp" in n)

    def start_big_and_wait_for_temporary(self):
        """Starts a multi-second generate and returns it once its temporary exists."""
        process = subprocess.Popen([MOSB, *BIG, "-o", self.path("big.mosb")], stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True,
                                   preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        deadline = time.monotonic() + 60
        while not self.temporaries() and time.monotonic() < deadline and process.poll() is None:
            time.sleep(0.01)
        names = self.temporaries()
        self.assertEqual(len(names), 1, names)
        match = TEMPORARY.match(names[0])
        self.assertIsNotNone(match, names[0])
        self.assertEqual(match.group(1), "big.mosb")
        self.assertEqual(int(match.group(2)), process.pid)
        # Inside the writing: its first bytes are in the temporary (they arrive 8 MiB at a time, a
        # fixed pause is not enough under a sanitizer on a loaded machine).
        temporary = self.path(names[0])
        while (process.poll() is None and os.path.getsize(temporary) == 0
               and time.monotonic() < deadline):
            time.sleep(0.01)
        self.assertIsNone(process.poll(), "the generate finished before it could be interrupted")
        return process


class Signals(Base):
    leaves_temporaries = True  # a run killed with SIGKILL cannot remove its own

    def interrupt(self, signal_number):
        process = self.start_big_and_wait_for_temporary()
        process.send_signal(signal_number)
        process.communicate(timeout=60)
        self.assertEqual(process.returncode, -signal_number)  # the default action, re-raised
        self.assertEqual(os.listdir(self.dir), [])  # no temporary and no target

    def test_sigint_removes_the_temporary(self):
        self.interrupt(signal.SIGINT)

    def test_sigterm_removes_the_temporary(self):
        self.interrupt(signal.SIGTERM)

    def test_sighup_removes_the_temporary(self):
        self.interrupt(signal.SIGHUP)

    def test_a_temporary_left_by_kill_9_is_removed_by_the_next_run(self):
        process = self.start_big_and_wait_for_temporary()
        process.kill()
        process.communicate(timeout=60)
        (left,) = self.temporaries()
        self.assertGreater(os.path.getsize(self.path(left)), 0)
        # A temporary of a live process (this one) for the same target is not touched.
        live = ".big.mosb.tmp-%d-AAAAAA" % os.getpid()
        self.write(live, "x")
        r = run(*SMALL, "-o", self.path("big.mosb"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("mosb: removed %s, left by an earlier run that was killed" % self.path(left), r.stderr)
        self.assertEqual(self.temporaries(), [live])
        self.assertTrue(os.path.exists(self.path("big.mosb")))


class WriteErrors(Base):
    def check_file_size_limit(self, xfsz):
        out = self.path("big.mosb")
        r = run("generate", "grid", "--width", "300", "--height", "300", "-o", out, fsize=1 << 20, xfsz=xfsz)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr, "mosb: %s: write failed: File too large\n" % out)
        self.assertEqual(os.listdir(self.dir), [])

    def test_file_size_limit_with_sigxfsz_ignored(self):
        self.check_file_size_limit(signal.SIG_IGN)

    def test_file_size_limit_with_sigxfsz_at_its_default(self):
        self.check_file_size_limit(signal.SIG_DFL)

    def test_export_write_error_names_the_file_and_leaves_nothing(self):
        inst = self.path("g.mosb")
        self.assertEqual(run("generate", "grid", "--width", "300", "--height", "300", "-o", inst).returncode, 0)
        out = self.path("text")
        os.mkdir(out)
        r = run("export", "dimacs", inst, "-o", out, fsize=1 << 20)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertRegex(r.stderr, r"^mosb: %s/[^ ]+\.gr: write failed: File too large$" % re.escape(out))
        self.assertEqual(os.listdir(out), [])


class Modes(Base):
    def test_new_files_honour_the_umask(self):
        for umask, expected in ((0o077, 0o600), (0o022, 0o644), (0o002, 0o664)):
            out = self.path("g%o.mosb" % umask)
            self.assertEqual(run(*SMALL, "-o", out, umask=umask).returncode, 0)
            self.assertEqual(mode(out), expected, "umask %o" % umask)
            text = self.path("text%o" % umask)
            self.assertEqual(run("export", "dimacs", out, "-o", text, umask=umask).returncode, 0)
            for name in os.listdir(text):
                self.assertEqual(mode(os.path.join(text, name)), expected, name)


class InPlace(Base):
    def instance(self, name="g.mosb"):
        out = self.path(name)
        self.assertEqual(run(*SMALL, "-o", out).returncode, 0)
        return out

    def add_queries(self, target):
        return run("queries", "generate", target, "--in-place", "--set", "r", "--count", "3", "--seed", "1")

    def test_mode_is_kept(self):
        inst = self.instance()
        os.chmod(inst, 0o600)
        r = self.add_queries(inst)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(mode(inst), 0o600)
        self.assertIn(b"r\0", read(inst))

    def test_a_symlink_is_written_through_and_stays_a_symlink(self):
        inst = self.instance()
        os.mkdir(self.path("links"))
        link = self.path("links/l.mosb")
        os.symlink("../g.mosb", link)
        r = self.add_queries(link)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(os.path.islink(link))
        self.assertEqual(os.readlink(link), "../g.mosb")
        self.assertIn(b"r\0", read(inst))
        self.assertEqual(os.listdir(self.path("links")), ["l.mosb"])

    def test_a_read_only_file_is_refused(self):
        inst = self.instance()
        os.chmod(inst, 0o444)  # the directory stays writable
        before = read(inst)
        r = self.add_queries(inst)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stderr, "mosb: %s: the file is read-only; not rewritten (make it writable first)\n" % inst)
        self.assertEqual(read(inst), before)
        self.assertEqual(mode(inst), 0o444)

    def test_a_file_with_several_hard_links_is_refused(self):
        inst = self.instance()
        os.link(inst, self.path("other.mosb"))
        before = read(inst)
        r = self.add_queries(inst)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertIn("%s: the file has 2 hard links" % inst, r.stderr)
        self.assertIn("split", r.stderr)
        self.assertEqual(read(inst), before)
        self.assertEqual(os.stat(inst).st_ino, os.stat(self.path("other.mosb")).st_ino)


class OutputIsAnInput(Base):
    def refused(self, args, protected):
        """Runs args three times: output given as the input's name, as a hard link to it and as a
        symlink to it; each must fail without changing the input."""
        before = read(protected)
        os.link(protected, self.path("hard"))
        os.symlink(protected, self.path("soft"))
        for output in (protected, self.path("hard"), self.path("soft")):
            r = run(*[output if a == "OUT" else a for a in args])
            self.assertNotEqual(r.returncode, 0, (args, output))
            self.assertIn("is the same file as the input", r.stderr)
            self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
            self.assertEqual(read(protected), before)
            self.assertTrue(os.path.islink(self.path("soft")))
            self.assertEqual(os.stat(self.path("hard")).st_ino, os.stat(protected).st_ino)
        self.assertEqual(self.temporaries(), [])

    def test_convert_dimacs(self):
        gr = self.write("x.gr", GR)
        self.refused(["convert", "dimacs", "--gr", gr, "-o", "OUT"], gr)

    def test_convert_dimacs_through_an_input_symlink(self):
        gr = self.write("x.gr", GR)
        os.symlink(gr, self.path("in.gr"))
        before = read(gr)
        r = run("convert", "dimacs", "--gr", self.path("in.gr"), "-o", gr)
        self.assertEqual(r.returncode, 1)
        self.assertIn("is the same file as the input", r.stderr)
        self.assertEqual(read(gr), before)

    def test_convert_netmaker(self):
        gr = self.write("n.gr", "p sp 2 1\na 0 1 5\n")
        self.refused(["convert", "netmaker", gr, "-o", "OUT"], gr)

    def test_convert_fmi(self):
        src = self.write("f.txt", "2\n1\n0 10 48.0 9.0 1\n1 11 48.1 9.1 1\n0 1 5 1 50\n")
        self.refused(["convert", "fmi", src, "-o", "OUT"], src)

    def test_convert_guards(self):
        m = self.write("s.map", "type octile\nheight 1\nwidth 2\nmap\n..\n")
        e = self.write("e.txt", "0 1\n")
        self.refused(["convert", "guards", "--map", m, "--exposure", e, "-o", "OUT"], m)

    def test_convert_movingai(self):
        m = self.write("s.map", "type octile\nheight 1\nwidth 2\nmap\n..\n")
        self.refused(["convert", "movingai", "--map", m, "-o", "OUT"], m)

    def test_convert_guards_write_exposure(self):
        m = self.write("s.map", "type octile\nheight 1\nwidth 2\nmap\n..\n")
        e = self.write("e.txt", "0 1\n")
        self.refused(["convert", "guards", "--map", m, "--exposure", e, "--write-exposure", "OUT",
                      "-o", self.path("x.mosb")], e)

    def test_convert_roadmap(self):
        gr = self.write("c1.gr", "p sp 2 2\na 0 1 0.5\na 1 0 1.25\n")
        self.refused(["convert", "roadmap", "--gr", gr, "--vertices-from-ids", "-o", "OUT"], gr)

    def test_queries_import(self):
        inst = self.path("g.mosb")
        self.assertEqual(run(*SMALL, "-o", inst).returncode, 0)
        self.refused(["queries", "import", "OUT", inst, "--in-place", "--set", "q"], inst)

    def test_queries_generate_output_is_not_the_instance(self):
        # -o is a new file; rewriting the instance takes --in-place.
        inst = self.path("g.mosb")
        self.assertEqual(run(*SMALL, "-o", inst).returncode, 0)
        self.refused(["queries", "generate", inst, "--set", "x", "--count", "2", "-o", "OUT"], inst)

    def test_queries_import_output_is_not_the_instance(self):
        inst = self.path("g.mosb")
        self.assertEqual(run(*SMALL, "-o", inst).returncode, 0)
        q = self.write("q.txt", "0 1\n")
        self.refused(["queries", "import", inst, q, "--set", "x", "-o", "OUT"], inst)

    def test_export_dimacs(self):
        os.mkdir(self.path("out"))
        inst = self.path("out/Grid-5x4-c1.gr")  # the name export gives objective c1 of this grid
        self.assertEqual(run(*SMALL, "-o", inst).returncode, 0)
        before = read(inst)
        r = run("export", "dimacs", inst, "-o", self.path("out"))
        self.assertEqual(r.returncode, 1, r.stdout)
        self.assertIn("is the same file as the input", r.stderr)
        self.assertEqual(read(inst), before)


if __name__ == "__main__":
    mosbtest.main()
