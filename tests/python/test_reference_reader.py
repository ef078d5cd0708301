#!/usr/bin/python3
"""The reference reader (spec/reference/mosb_reader.py) against FORMAT.md §9: every golden file,
valid and invalid, fails (or passes) at the level spec/golden/1.0/invalid/EXPECTED.tsv gives, and
the checks of §9 it used to miss. Needs MOSB_SOURCE_DIR; runs under /usr/bin/python3."""
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import mosbtest  # noqa: E402 (main: the suites' skip exit code)

import xxhash

SOURCE = os.environ["MOSB_SOURCE_DIR"]
sys.path.insert(0, os.path.join(SOURCE, "spec", "reference"))
import mosb_reader  # noqa: E402

GOLDEN = os.path.join(SOURCE, "spec", "golden", "1.0")
LEVELS = ("header", "checksums", "structure")
# What the reference reader's own message says for each golden file: the right check refused it.
REASONS = {
    "truncated.mosb": "truncated", "bad-magic.mosb": "bad magic",
    "byte-swapped.mosb": "byte-swapped", "text-mode.mosb": "text-mode",
    "newer-major.mosb": "format 2.0", "unknown-feature.mosb": r"feature bit\(s\) \[7\]",
    "header-checksum.mosb": "header checksum mismatch", "overlap.mosb": "overlap",
    "misaligned.mosb": "64-aligned", "count-mismatch.mosb": "rows, expected",
    "table-past-end.mosb": "section table", "section-checksum.mosb": "'time': checksum mismatch",
    "target-range.mosb": "target 9, not < 4", "not-transpose.mosb": "not the transpose",
    "padding.mosb": "padding byte at offset",
}


def expected_rows():
    with open(os.path.join(GOLDEN, "invalid", "EXPECTED.tsv")) as f:
        return [line.rstrip("\n").split("\t")[:2] for line in f if not line.startswith("#")]


def read_at(path, level):
    mosb_reader.open_instance(path).verify(level)


class GoldenTest(unittest.TestCase):
    def test_valid_file_passes_every_level(self):
        for level in mosb_reader.VERIFY_LEVELS:
            read_at(os.path.join(GOLDEN, "valid", "small.mosb"), level)

    def test_every_invalid_file_is_listed(self):
        listed = {name for name, _ in expected_rows()}
        present = {f for f in os.listdir(os.path.join(GOLDEN, "invalid")) if f.endswith(".mosb")}
        self.assertEqual(listed, present)
        self.assertEqual(listed, set(REASONS))

    def test_invalid_files_fail_at_their_level_only(self):
        for name, level in expected_rows():
            path = os.path.join(GOLDEN, "invalid", name)
            failing = "header" if level == "open" else level
            with self.subTest(file=name):
                with self.assertRaisesRegex(mosb_reader.FormatError, REASONS[name]):
                    read_at(path, failing)
                with self.assertRaisesRegex(mosb_reader.FormatError, REASONS[name]):
                    read_at(path, "full")
                for other in LEVELS:
                    if level != "open" and other != failing:
                        read_at(path, other)  # the other levels do not see this damage

    def test_command_line_exit_status(self):
        script = os.path.join(SOURCE, "spec", "reference", "mosb_reader.py")
        ok = subprocess.run([sys.executable, script, os.path.join(GOLDEN, "valid", "small.mosb"),
                             "--level", "full"], capture_output=True, text=True)
        self.assertEqual(ok.returncode, 0, ok.stderr)
        bad = os.path.join(GOLDEN, "invalid", "target-range.mosb")
        self.assertEqual(subprocess.run([sys.executable, script, bad], capture_output=True)
                         .returncode, 0)
        failed = subprocess.run([sys.executable, script, bad, "--level", "structure"],
                                capture_output=True, text=True)
        self.assertEqual(failed.returncode, 1)
        self.assertIn(bad + ": ", failed.stderr)


class IndependenceTest(unittest.TestCase):
    def test_reference_reader_and_package_share_no_code(self):
        """The reference reader is the spec's second implementation: it must not use the mosb
        package (which binds the C++ reader), nor the package the reference reader."""
        import re
        for directory, forbidden in (("spec/reference", r"^\s*(import|from)\s+mosb\b"),
                                     ("python", r"mosb_reader")):
            for base, _, files in os.walk(os.path.join(SOURCE, directory)):
                for name in files:
                    if name.endswith((".py", ".cpp")):
                        with open(os.path.join(base, name), encoding="utf-8") as f:
                            self.assertIsNone(re.search(forbidden, f.read(), re.M),
                                              os.path.join(base, name))


class PatchedHeaderTest(unittest.TestCase):
    """Files made from small.mosb with one header or entry field changed, the header checksum
    recomputed, so that only the check under test can refuse them."""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="mosb-reference-")
        self.addCleanup(shutil.rmtree, self.dir)
        with open(os.path.join(GOLDEN, "valid", "small.mosb"), "rb") as f:
            self.data = bytearray(f.read())
        self.table_offset, self.section_count = struct.unpack_from("<QI", self.data, 48)

    def write(self, data):
        table_end = self.table_offset + 64 * self.section_count
        checksum = xxhash.xxh3_64_intdigest(bytes(data[:120]) +
                                            bytes(data[self.table_offset:table_end]))
        struct.pack_into("<Q", data, 120, checksum)
        path = os.path.join(self.dir, "patched.mosb")
        with open(path, "wb") as f:
            f.write(data)
        return path

    def with_u64(self, offset, value):
        data = bytearray(self.data)
        struct.pack_into("<Q", data, offset, value)
        return self.write(data)

    def test_unchanged_copy_opens(self):
        mosb_reader.open_instance(self.write(bytearray(self.data))).verify("full")

    def test_vertex_and_arc_count_limit(self):
        for offset, field in ((64, "n"), (72, "m")):
            with self.assertRaisesRegex(mosb_reader.FormatError, "too large", msg=field):
                mosb_reader.open_instance(self.with_u64(offset, 2**32 - 1))
            # 2^32-2 is allowed by the limit: the row counts refuse it instead.
            with self.assertRaisesRegex(mosb_reader.FormatError, "rows, expected", msg=field):
                mosb_reader.open_instance(self.with_u64(offset, 2**32 - 2))

    def test_zstd_bit_without_zstd_section(self):
        with self.assertRaisesRegex(mosb_reader.FormatError, "zstd-sections.*no section"):
            mosb_reader.open_instance(self.with_u64(24, 1))

    def test_zstd_section_without_zstd_bit(self):
        data = bytearray(self.data)
        data[self.table_offset + 64 * 1 + 27] = 1  # encoding of the second entry: zstd
        with self.assertRaisesRegex(mosb_reader.FormatError, "zstd encoding but required bit 0"):
            mosb_reader.open_instance(self.write(data))

    def test_refuses_to_load_without_xxhash(self):
        code = ("import sys; sys.modules['xxhash'] = None; sys.path.insert(0, %r); "
                "import mosb_reader" % os.path.join(SOURCE, "spec", "reference"))
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("xxhash module is required for the header checksum", done.stderr)


if __name__ == "__main__":
    mosbtest.main()
