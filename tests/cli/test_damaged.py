#!/usr/bin/python3
"""Damaged and hostile inputs to the commands that read a file's payload.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_damaged.py

Every command that walks the CSR or copies payload (export dimacs, inspect's loop counts, stats,
queries import|generate) opens with the checks of `verify --level full`, so one flipped byte in an
offsets, targets or cost column gives one line naming the file and saying it is damaged, exit 1,
and no output or temporary file. A path that is not a regular file (a FIFO, a directory) is refused
at once instead of blocking. Metadata values are escaped in `inspect`'s text output.
"""

import json
import os

import mosbtest
from mosbtest import entry, files_under, move_payload_to_end, payload, write_payload
from mosbtest import setUpModule  # noqa: F401
from test_cli import GridTest


class DamagedPayload(GridTest):
    def damaged_copy(self, section, index):
        """A copy of the grid file with one bit flipped at byte `index` of `section`'s payload."""
        data = self.grid_bytes()
        e = entry(data, section)
        self.assertLess(index, e["stored_length"])
        data[e["offset"] + index] ^= 0x04
        name = "bad-%s.mosb" % section
        self.write(name, data)
        return name

    def assert_refused(self, name, *args):
        before = files_under(self.dir)
        with open(self.path(name), "rb") as f:
            original = f.read()
        r = self.mosb(*args)
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual(len(r.stderr.splitlines()), 1, r)
        self.assertIn(name, r.stderr.splitlines()[0], r)
        self.assertIn("damaged", r.stderr.splitlines()[0], r)
        self.assertIn("run mosb verify", r.stderr.splitlines()[0], r)
        self.assertEqual(r.stdout, "", r)  # no numbers from corrupt data
        self.assertEqual(files_under(self.dir), before, "an output or temporary file was left")
        with open(self.path(name), "rb") as f:
            self.assertEqual(f.read(), original, "the damaged input was rewritten")

    def check_every_command(self, section, index):
        name = self.damaged_copy(section, index)
        with open(self.path("q.txt"), "w") as f:
            f.write("1 2\n3 4\n")
        commands = [
            ["export", "dimacs", name, "-o", "out"],
            # A plain inspect reads no payload (a look, not a check); with --verify it checks.
            ["inspect", "--verify", "checksums", name],
            ["inspect", "--json", "--verify", "full", name],
            ["stats", name],
            ["stats", "--json", name],
            ["queries", "generate", name, "--set", "fresh", "--in-place"],
            ["queries", "import", name, "q.txt", "--set", "fresh", "--in-place"],
        ]
        for args in commands:
            with self.subTest(section=section, command=" ".join(args[:2])):
                self.assert_refused(name, *args)
        self.assertFalse(os.path.exists(self.path("out")))
        # verify names the same problem.
        r = self.mosb("verify", name)
        self.assertEqual(r.returncode, 1, r)
        self.assertIn("[checksum] mismatch", r.stdout, r)

    def test_flipped_byte_in_forward_offsets(self):
        self.check_every_command("forward_offsets", 8 * 3)  # low byte of offsets[3]

    def test_flipped_byte_in_forward_targets(self):
        self.check_every_command("forward_targets", 4 * 5)

    def test_flipped_byte_in_a_cost_column(self):
        self.check_every_command("c1", 7)

    def test_undamaged_file_still_works(self):
        path = self.generate()
        for args in (["inspect", path], ["stats", path], ["export", "dimacs", path, "-o", "out"],
                     ["queries", "generate", path, "--set", "fresh", "--in-place"]):
            r = self.mosb(*args)
            self.assertEqual(r.returncode, 0, r)


class NotARegularFile(GridTest):
    def check_refused_quickly(self, path, kind):
        for args in (["verify", path], ["inspect", path], ["stats", path],
                     ["export", "dimacs", path, "-o", "out"]):
            with self.subTest(kind=kind, command=args[0]):
                completed = self.mosb(*args, timeout=20)
                self.assertNotEqual(completed.returncode, 0, completed)
                self.assertGreater(completed.returncode, 0, completed)
                # The first line names the file (a usage error from the option parser may add a
                # hint line).
                text = (completed.stdout + completed.stderr).strip()
                self.assertIn(os.path.basename(path), text.splitlines()[0], completed)
                self.assertFalse(os.path.exists(self.path("out")))

    def test_fifo(self):
        fifo = self.path("p.mosb")
        os.mkfifo(fifo)
        self.check_refused_quickly(fifo, "FIFO")
        r = self.mosb("verify", fifo)
        self.assertIn("is a FIFO, not a regular file", r.stdout, r)

    def test_directory(self):
        directory = self.path("d.mosb")
        os.mkdir(directory)
        self.check_refused_quickly(directory, "directory")
        r = self.mosb("inspect", directory)
        self.assertIn("is a directory, not a regular file", r.stderr, r)


class SolutionCommandsBadInput(GridTest):
    """Every input of `solutions import|export|inspect|verify|compare|merge`, `eval`, `plot *`
    and `report` given as a damaged (one flipped bit in a section payload), truncated, directory
    or FIFO file: one line naming the file, exit 1 (2 when the option parser refuses it), nothing
    on stdout, no output file, and no blocking on a FIFO."""

    def setUp(self):
        super().setUp()
        self.instance = self.generate("g.mosb")
        os.mkdir(self.path("fronts"))
        with open(self.path("fronts/0.txt"), "w") as f:
            f.write("10 20\n20 10\n")
        self.solutions = self.path("good.sol")
        r = self.mosb("solutions", "import", "--instance", self.instance, "--view", "Grid_2",
                      "--dir", self.path("fronts"), "-o", self.solutions)
        self.assertEqual(r.returncode, 0, r)

    def bad_copy(self, original, name, kind):
        """`name` in the test directory as a `kind` version of `original`."""
        path = self.path(name)
        if kind == "directory":
            os.mkdir(path)
            return path
        if kind == "FIFO":
            os.mkfifo(path)
            return path
        with open(original, "rb") as f:
            data = bytearray(f.read())
        if kind == "truncated":
            del data[len(data) // 2:]
        else:
            section = "c1"  # a cost column: in the instance and in the solution file
            e = entry(data, section)
            data[e["offset"] + 1 if e["stored_length"] > 1 else e["offset"]] ^= 0x04
        return self.write(name, data)

    def assert_refused(self, name, kind, args):
        before = files_under(self.dir)
        completed = self.mosb(*args, timeout=20)
        self.assertIn(completed.returncode, (1, 2), completed)
        if completed.returncode == 2:  # only the option parser's existing-file check
            self.assertEqual(kind, "directory", completed)
        err = completed.stderr.splitlines()
        self.assertEqual(len(err), 1, completed)
        self.assertIn(name, err[0], completed)
        if kind == "damaged" and args[:2] != ["solutions", "verify"]:
            self.assertIn("file is damaged", err[0], completed)
            self.assertIn("run mosb verify", err[0], completed)
        self.assertEqual(completed.stdout, "", completed)
        self.assertEqual(files_under(self.dir), before, "an output or temporary file was left")
        self.assertFalse(os.path.exists(self.path("out")), completed)

    def check(self, kind):
        bad_sol = self.bad_copy(self.solutions, "bad.sol", kind)
        bad_graph = self.bad_copy(self.instance, "bad.mosb", kind)
        good, g = self.solutions, self.instance
        commands = [
            (bad_sol, ["solutions", "inspect", bad_sol]),
            (bad_sol, ["solutions", "inspect", "--json", bad_sol]),
            (bad_sol, ["solutions", "verify", bad_sol]),
            (bad_sol, ["solutions", "verify", bad_sol, "--instance", g]),
            (bad_graph, ["solutions", "verify", good, "--instance", bad_graph]),
            (bad_sol, ["solutions", "export", bad_sol, "--dir", "out"]),
            (bad_sol, ["solutions", "export", bad_sol, "--json-log", "out", "--instance", g]),
            (bad_graph, ["solutions", "export", good, "--json-log", "out", "--instance",
                         bad_graph]),
            (bad_graph, ["solutions", "import", "--instance", bad_graph, "--view", "Grid_2",
                         "--dir", "fronts", "-o", "out"]),
            (bad_sol, ["eval", "--reference", bad_sol, "--solutions", good]),
            (bad_sol, ["eval", "--reference", good, "--solutions", bad_sol]),
            (bad_sol, ["eval", "--reference", good, "--solutions", good, bad_sol, "--csv"]),
            (bad_sol, ["solutions", "compare", bad_sol, good]),
            (bad_sol, ["solutions", "compare", good, bad_sol, "--json"]),
            (bad_sol, ["plot", "front", "--solutions", bad_sol, "--query", "0", "-o", "out"]),
            (bad_sol, ["plot", "front", "--solutions", good, "--reference", bad_sol, "--query",
                       "0", "-o", "out"]),
            (bad_sol, ["plot", "cardinality", "--solutions", bad_sol, "-o", "out"]),
            (bad_graph, ["plot", "correlation", bad_graph, "-o", "out"]),
            (bad_graph, ["plot", "map", bad_graph, "-o", "out"]),
            (bad_sol, ["plot", "map", g, "--solutions", bad_sol, "--query", "0", "-o", "out"]),
            (bad_graph, ["report", bad_graph, "-o", "out"]),
            (bad_sol, ["report", g, "--solutions", bad_sol, "-o", "out"]),
            (bad_sol, ["report", g, "--reference", bad_sol, "--solutions", good, "-o", "out"]),
            (bad_sol, ["solutions", "merge", bad_sol, "-o", "out"]),
            (bad_sol, ["solutions", "merge", good, bad_sol, "--allow-missing", "-o", "out"]),
        ]
        for path, args in commands:
            with self.subTest(kind=kind, command=" ".join(args)):
                self.assert_refused(os.path.basename(path), kind, args)

    def test_damaged(self):
        self.check("damaged")

    def test_truncated(self):
        self.check("truncated")

    def test_directory(self):
        self.check("directory")

    def test_fifo(self):
        self.check("FIFO")

    def text_inputs(self, kind, text):
        """The text inputs of `solutions import`: a table, a JSON log, a front directory."""
        bad = self.path("bad.txt")
        if kind == "truncated":
            with open(bad, "w") as f:
                f.write(text)
        else:
            self.bad_copy(None, "bad.txt", kind)
        for option in ("--table", "--json-log", "--dir"):
            if kind != "FIFO" and option == "--dir":
                continue  # a directory is what --dir reads
            args = ["solutions", "import", "--instance", self.instance, "--view", "Grid_2",
                    option, bad, "-o", "out"]
            with self.subTest(kind=kind, option=option):
                self.assert_refused("bad.txt", kind, args)

    def test_import_text_inputs(self):
        self.text_inputs("directory", "")
        os.rmdir(self.path("bad.txt"))
        self.text_inputs("FIFO", "")

    def test_import_truncated_json_log(self):
        self.text_inputs("truncated", '[{"source": 0, "target": 19, "finish_info": {"solut')

    def test_import_from_a_pipe_with_a_writer(self):
        # Not blocking on a FIFO without a writer must not refuse a pipe that has one.
        completed = self.mosb("solutions", "import", "--instance", self.instance, "--view",
                              "Grid_2", "--table", "/dev/stdin", "-o", "piped.sol",
                              input="query,c1,c2\n0,10,20\n", timeout=20)
        self.assertEqual(completed.returncode, 0, completed)
        self.assertIn("1 of 1 queries imported, 1 vectors", completed.stdout)

    def test_good_files_still_work(self):
        for args in (["solutions", "inspect", self.solutions],
                     ["solutions", "verify", self.solutions],
                     ["eval", "--reference", self.solutions, "--solutions", self.solutions],
                     ["solutions", "compare", self.solutions, self.solutions],
                     ["plot", "cardinality", "--solutions", self.solutions, "-o", "c.svg"],
                     ["plot", "front", "--solutions", self.solutions, "--query", "0", "-o",
                      "f.svg"]):
            r = self.mosb(*args)
            self.assertEqual(r.returncode, 0, r)


class HostileMetadata(GridTest):
    FAKE = "x\x1b[2J\x1b[1;1H\rOK   g.mosb (full, digest 0)\nOK   all fine\u009b31m\u202e"

    def with_benchmark(self, value):
        """The grid file with metadata `benchmark` set to `value`; the section is moved to the end."""
        data = self.grid_bytes()
        meta = entry(data, "metadata")
        text = bytes(data[meta["offset"]:meta["offset"] + meta["stored_length"]]).decode()
        escaped = value.replace("\\", "\\\\").replace("\n", "\\n")
        lines = [("benchmark=" + escaped) if line.startswith("benchmark=") else line
                 for line in text.split("\n")[:-1]]
        body = ("\n".join(lines) + "\n").encode()
        move_payload_to_end(data, "metadata", body, row_count=len(body))
        return self.write("hostile.mosb", data)

    def test_inspect_escapes_control_characters(self):
        path = self.with_benchmark(self.FAKE)
        self.assertEqual(self.mosb("verify", path).returncode, 0)
        r = self.mosb("inspect", path)
        self.assertEqual(r.returncode, 0, r)
        for bad in ("\x1b", "\r", "\u009b", "\u202e"):
            self.assertNotIn(bad, r.stdout)
        self.assertFalse(any(line.startswith("OK") for line in r.stdout.splitlines()), r.stdout)
        (line,) = [line for line in r.stdout.splitlines() if line.startswith("benchmark ")]
        self.assertIn("x\\x1b[2J\\x1b[1;1H\\rOK   g.mosb (full, digest 0)\\nOK   all fine"
                      "\\u{009b}31m\\u{202e}", line)
        r = self.mosb("inspect", "--json", path)
        self.assertEqual(r.returncode, 0, r)
        self.assertNotIn("\x1b", r.stdout)
        self.assertEqual(json.loads(r.stdout)["metadata"]["benchmark"], self.FAKE)

    def test_verify_refuses_id_base_outside_its_value_set(self):
        data = self.grid_bytes()
        meta = entry(data, "metadata")
        text = bytes(data[meta["offset"]:meta["offset"] + meta["stored_length"]])
        at = text.find(b"id_base=0\n")
        self.assertGreaterEqual(at, 0, text)
        body = bytearray(text)
        body[at + len("id_base=")] = ord("7")
        write_payload(data, "metadata", body)
        path = self.write("id7.mosb", data)
        r = self.mosb("verify", "--level", "structure", path)
        self.assertEqual(r.returncode, 1, r)
        self.assertIn("[metadata-values] metadata key 'id_base' is '7', not one of 0, 1", r.stdout)
        self.assertEqual(self.mosb("verify", "--level", "checksums", path).returncode, 0)



class MalformedViews(GridTest):
    """FORMAT.md §7: a view needs a name and objectives. Such metadata, checksums recomputed,
    fails `verify` at structure level with the key named, and fails every command that reads views."""

    def with_metadata(self, name, edit):
        data = self.grid_bytes()
        lines = [line for line in bytes(payload(data, "metadata")).decode().splitlines()]
        lines = sorted(edit(lines))
        body = ("\n".join(lines) + "\n").encode()
        move_payload_to_end(data, "metadata", body, row_count=len(body))
        self.write(name, data)
        return self.path(name)

    def test_a_view_with_only_a_query_set(self):
        path = self.with_metadata("q.mosb", lambda lines: [
            line for line in lines if not line.startswith("view.Grid_3.objectives=")])
        self.assert_ok(path, "checksums")
        self.assert_fail(path, "structure", "'view.Grid_3.queries' names a view without objectives")

    def test_a_view_with_an_empty_name(self):
        path = self.with_metadata("e.mosb", lambda lines: lines + ["view..objectives=c1"])
        self.assert_fail(path, "full", "'view..objectives' names a view with an empty name")


if __name__ == "__main__":
    mosbtest.main()
