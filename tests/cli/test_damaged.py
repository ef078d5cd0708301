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
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_cli import (MOSB, CliTest, entries, entry, header, reseal, set_entry,  # noqa: E402
                      set_header, setUpModule)  # noqa: F401  (setUpModule checks MOSB)

import xxhash  # noqa: E402


def files_under(directory):
    return sorted(os.path.join(root, f) for root, dirs, files in os.walk(directory) for f in files)


class DamagedPayload(CliTest):
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
        self.assertEqual(r.code, 1, r)
        self.assertEqual(len(r.err_lines), 1, r)
        self.assertIn(name, r.err_lines[0], r)
        self.assertIn("damaged", r.err_lines[0], r)
        self.assertIn("run mosb verify", r.err_lines[0], r)
        self.assertEqual(r.out, "", r)  # no numbers from corrupt data
        self.assertEqual(files_under(self.dir), before, "an output or temporary file was left")
        with open(self.path(name), "rb") as f:
            self.assertEqual(f.read(), original, "the damaged input was rewritten")

    def check_every_command(self, section, index):
        name = self.damaged_copy(section, index)
        with open(self.path("q.txt"), "w") as f:
            f.write("1 2\n3 4\n")
        commands = [
            ["export", "dimacs", name, "-o", "out"],
            ["inspect", name],
            ["inspect", "--json", name],
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
        self.assertEqual(r.code, 1, r)
        self.assertIn("[checksum] mismatch", r.out, r)

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
            self.assertEqual(r.code, 0, r)


class NotARegularFile(CliTest):
    def check_refused_quickly(self, path, kind):
        for args in (["verify", path], ["inspect", path], ["stats", path],
                     ["export", "dimacs", path, "-o", "out"]):
            with self.subTest(kind=kind, command=args[0]):
                try:
                    completed = subprocess.run([MOSB, *args], cwd=self.dir, capture_output=True,
                                               text=True, timeout=20)
                except subprocess.TimeoutExpired:
                    self.fail("%s on a %s blocked" % (" ".join(args), kind))
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
        self.assertIn("is a FIFO, not a regular file", r.out, r)

    def test_directory(self):
        directory = self.path("d.mosb")
        os.mkdir(directory)
        self.check_refused_quickly(directory, "directory")
        r = self.mosb("inspect", directory)
        self.assertIn("is a directory, not a regular file", r.err, r)


class HostileMetadata(CliTest):
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
        h = header(data)
        table = bytes(data[h["table_offset"]:])
        data[meta["offset"]:meta["offset"] + meta["stored_length"]] = bytes(meta["stored_length"])
        new_offset = h["table_offset"]
        padded = body + bytes(-len(body) % 64)
        del data[new_offset:]
        data += padded + table
        set_header(data, table_offset=new_offset + len(padded), file_size=len(data))
        set_entry(data, "metadata", offset=new_offset, stored_length=len(body), row_count=len(body),
                  checksum=xxhash.xxh3_64_intdigest(body))
        reseal(data)
        return self.write("hostile.mosb", data)

    def test_inspect_escapes_control_characters(self):
        path = self.with_benchmark(self.FAKE)
        self.assertEqual(self.mosb("verify", path).code, 0)
        r = self.mosb("inspect", path)
        self.assertEqual(r.code, 0, r)
        for bad in ("\x1b", "\r", "\u009b", "\u202e"):
            self.assertNotIn(bad, r.out)
        self.assertFalse(any(line.startswith("OK") for line in r.out_lines), r.out)
        (line,) = [line for line in r.out_lines if line.startswith("benchmark ")]
        self.assertIn("x\\x1b[2J\\x1b[1;1H\\rOK   g.mosb (full, digest 0)\\nOK   all fine"
                      "\\u{009b}31m\\u{202e}", line)
        r = self.mosb("inspect", "--json", path)
        self.assertEqual(r.code, 0, r)
        self.assertNotIn("\x1b", r.out)
        self.assertEqual(json.loads(r.out)["metadata"]["benchmark"], self.FAKE)

    def test_verify_refuses_id_base_outside_its_value_set(self):
        data = self.grid_bytes()
        meta = entry(data, "metadata")
        text = bytes(data[meta["offset"]:meta["offset"] + meta["stored_length"]])
        at = text.find(b"id_base=0\n")
        self.assertGreaterEqual(at, 0, text)
        body = bytearray(text)
        body[at + len("id_base=")] = ord("7")
        data[meta["offset"]:meta["offset"] + len(body)] = body
        set_entry(data, "metadata", checksum=xxhash.xxh3_64_intdigest(bytes(body)))
        reseal(data)
        path = self.write("id7.mosb", data)
        r = self.mosb("verify", "--level", "structure", path)
        self.assertEqual(r.code, 1, r)
        self.assertIn("[metadata-values] metadata key 'id_base' is '7', not one of 0, 1", r.out)
        self.assertEqual(self.mosb("verify", "--level", "checksums", path).code, 0)


if __name__ == "__main__":
    unittest.main()
