#!/usr/bin/python3
"""`mosb convert dimacs` at the scale of DIMACS NY: 264,346 vertices, 733,846 arcs, 2 objectives.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_dimacs_scale.py

Generated text (not the real NY files, which are not shipped) in plain, CRLF-with-comments, gzip,
bzip2, xz and zstd forms must give the same graph, cost and vertex sections (equal section
checksums; only the metadata's provenance differs); export and re-conversion must give them back;
malformed copies must fail with their exact line and column.
"""

import os
import random
import shutil
import subprocess
import tempfile
import unittest

import mosbtest
from mosbtest import run, setUpModule  # noqa: F401
from test_dimacs import sections

N, M = 264346, 733846


def ny_like_text(seed):
    """Two .gr texts (distance, time) and a .co text of NY size: a chain plus 'vertical' links."""
    rng = random.Random(seed)
    width = 514
    arcs = []
    for v in range(1, N):
        arcs.append((v, v + 1))
        arcs.append((v + 1, v))
    v = 1
    while len(arcs) < M:
        arcs.append((v, v + width))
        arcs.append((v + width, v))
        v = (v + 7) % (N - width) + 1
    arcs = arcs[:M]
    distance = [rng.randint(1, 5000) for _ in arcs]
    time = [d * rng.randint(10, 30) // 10 for d in distance]
    head = "c NY-size test graph\np sp %d %d\n" % (N, M)
    gr_d = head + "".join("a %d %d %d\n" % (u, w, c) for (u, w), c in zip(arcs, distance))
    gr_t = head + "".join("a %d %d %d\n" % (u, w, c) for (u, w), c in zip(arcs, time))
    co = "p aux sp co %d\n" % N + "".join(
        "v %d %d %d\n" % (i, -74000000 + rng.randint(0, 999999), 40000000 + rng.randint(0, 999999))
        for i in range(1, N + 1))
    return gr_d, gr_t, co


def crlf_with_comments(text):
    """CRLF line ends, a comment and a blank line every 1000 lines, trailing blanks, no final newline."""
    out = []
    for i, line in enumerate(text.split("\n")[:-1]):
        if i % 1000 == 999:
            out.append("c comment %d" % i)
            out.append("")
        out.append(line + ("  " if i % 7 == 0 else ""))
    return "\r\n".join(out)


class DimacsAtScale(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="mosb-ny-scale-")
        cls.gr_d, cls.gr_t, cls.co = ny_like_text(11)
        for name, text in (("d.gr", cls.gr_d), ("t.gr", cls.gr_t), ("ny.co", cls.co),
                           ("d-crlf.gr", crlf_with_comments(cls.gr_d)),
                           ("t-crlf.gr", crlf_with_comments(cls.gr_t))):
            with open(os.path.join(cls.dir, name), "w", newline="") as f:
                f.write(text)
        cls.reference = cls.convert("plain.mosb", "d.gr", "t.gr")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    @classmethod
    def run_mosb(cls, *args):
        return run(*args, cwd=cls.dir, timeout=600)

    @classmethod
    def convert(cls, output, d, t, *extra):
        r = cls.run_mosb("convert", "dimacs", "--gr", d, "--gr", t, "--objective", "distance:m",
                         "--objective", "time:ds", "--co", "ny.co", *extra, "-o", output)
        assert r.returncode == 0, r.stderr
        return sections(os.path.join(cls.dir, output))

    def test_counts_and_full_verification(self):
        r = self.run_mosb("verify", "--level", "full", "plain.mosb")
        self.assertEqual(r.returncode, 0, r.stdout)
        r = self.run_mosb("inspect", "--json", "plain.mosb")
        self.assertIn('"vertices":%d' % N, r.stdout)
        self.assertIn('"arcs":%d' % M, r.stdout)
        self.assertEqual(len(self.reference), 5 + 2 + 1)  # CSR x5, two costs, coords

    def test_crlf_comments_and_blanks_give_the_same_sections(self):
        self.assertEqual(self.convert("crlf.mosb", "d-crlf.gr", "t-crlf.gr"), self.reference)

    def test_every_compression_gives_the_same_sections(self):
        for tool, suffix in (("gzip", ".gz"), ("bzip2", ".bz2"), ("xz", ".xz"), ("zstd", ".zst")):
            with self.subTest(tool=tool):
                if not shutil.which(tool):
                    raise mosbtest.missing("%s is not installed" % tool)
                subprocess.run([tool, "-1", "-k", "-f", "-q", "t.gr"], cwd=self.dir, check=True)
                # A misleading name: detection is by magic bytes, never by file name.
                shutil.move(os.path.join(self.dir, "t.gr" + suffix), os.path.join(self.dir, "t-" + tool + ".txt"))
                self.assertEqual(self.convert(tool + ".mosb", "d.gr", "t-" + tool + ".txt"), self.reference)

    def test_export_then_convert_gives_the_same_sections(self):
        r = self.run_mosb("export", "dimacs", "plain.mosb", "-o", "exported")
        self.assertEqual(r.returncode, 0, r.stderr)
        files = sorted(os.listdir(os.path.join(self.dir, "exported")))
        gr = [f for f in files if f.endswith(".gr")]
        co = [f for f in files if f.endswith(".co")]
        self.assertEqual(len(gr), 2, files)
        self.assertEqual(len(co), 1, files)
        distance = next(f for f in gr if "distance" in f)
        time = next(f for f in gr if "time" in f)
        r = self.run_mosb("convert", "dimacs", "--gr", "exported/" + distance, "--gr", "exported/" + time,
                          "--objective", "distance:m", "--objective", "time:ds", "--co", "exported/" + co[0],
                          "-o", "again.mosb")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sections(os.path.join(self.dir, "again.mosb")), self.reference)

    def test_malformed_lines_fail_at_their_line_and_column(self):
        lines = self.gr_t.split("\n")
        deep = 500000  # 0-based index into lines; the file's line number is deep + 1
        cases = [
            (lines[deep].split()[0] + " " + lines[deep].split()[1] + " x 5",
             "t-bad.gr:%d:%d: expected a vertex id, found 'x'" % (deep + 1, len(lines[deep].split()[1]) + 4)),
            ("a 1 %d 5" % (N + 1), "t-bad.gr:%d:5: vertex id '%d' outside 1..%d" % (deep + 1, N + 1, N)),
            ("a 1 2 -5", "t-bad.gr:%d:7: negative cost '-5'" % (deep + 1)),
        ]
        for replacement, message in cases:
            with self.subTest(message=message):
                bad = lines[:deep] + [replacement] + lines[deep + 1:]
                with open(os.path.join(self.dir, "t-bad.gr"), "w") as f:
                    f.write("\n".join(bad))
                r = self.run_mosb("convert", "dimacs", "--gr", "d.gr", "--gr", "t-bad.gr", "-o", "bad.mosb")
                self.assertEqual(r.returncode, 1, r)
                self.assertEqual(r.stderr.strip(), "mosb: " + message)
                self.assertFalse(os.path.exists(os.path.join(self.dir, "bad.mosb")))

    def test_a_disagreeing_arc_names_both_files_and_lines(self):
        lines = self.gr_t.split("\n")
        deep = 400000
        u, v = lines[deep].split()[1:3]
        lines[deep] = "a %s %d 5" % (u, int(v) % N + 1)
        with open(os.path.join(self.dir, "t-swap.gr"), "w") as f:
            f.write("\n".join(lines))
        r = self.run_mosb("convert", "dimacs", "--gr", "d.gr", "--gr", "t-swap.gr", "-o", "bad.mosb")
        self.assertEqual(r.returncode, 1, r)
        self.assertIn("t-swap.gr:%d:" % (deep + 1), r.stderr)
        self.assertIn("d.gr:%d" % (deep + 1), r.stderr)


if __name__ == "__main__":
    mosbtest.main()
