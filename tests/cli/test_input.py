#!/usr/bin/python3
"""How converters read their text inputs (issue 8): declared sizes against memory, out of memory
naming the input, compressed input streamed in bounded memory, truncated compressed files.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_input.py
"""

import gzip
import os
import resource
import shutil
import subprocess
import unittest

import mosbtest
from mosbtest import CliTest, setUpModule  # noqa: F401

# AddressSanitizer reserves terabytes of shadow address space and adds to the peak RSS.
UNDER_ASAN = "address-space and memory limits do not apply under AddressSanitizer"


def physical_gib():
    return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE") / 2**30


def graph_text(arcs):
    """A chain of `arcs` + 1 vertices, one arc per line."""
    lines = ["c generated", f"p sp {arcs + 1} {arcs}"]
    lines += [f"a {v} {v + 1} {v % 97 + 1}" for v in range(1, arcs + 1)]
    return "\n".join(lines) + "\n"


class InputTest(CliTest):
    def convert(self, *gr, limit_bytes=None):
        args = ["convert", "dimacs"]
        for g in gr:
            args += ["--gr", g]
        args += ["-o", self.path("out.mosb")]
        preexec = None
        if limit_bytes:
            def preexec():
                resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))
        return self.mosb(*args, preexec_fn=preexec)

    def assert_error(self, r, message):
        super().assert_error(r, message)
        self.assertFalse(os.path.exists(self.path("out.mosb")))

    def test_declared_vertex_count_beyond_physical_memory(self):
        # 25 bytes of header that would ask for 96 GiB: a located error, not std::bad_alloc.
        gr = self.write("huge.gr", "p sp 4294967294 1\na 1 2 1\n")
        need = 4294967294 * 24 / 2**30
        self.assert_error(self.convert(gr),
                          f"{gr}:1:6: the header declares 4294967294 vertices: {need:.1f} GiB, "
                          f"more than the {physical_gib():.1f} GiB of physical memory")

    @unittest.skipIf("ASAN_OPTIONS" in os.environ, UNDER_ASAN)
    def test_out_of_memory_names_the_input(self):
        # 90 million vertices fit in physical memory but not under a 1 GiB address-space limit:
        # the CSR build holds the forward and the reverse offsets, 8 (n + 1) bytes each.
        gr = self.write("big.gr", "p sp 90000000 1\na 1 2 1\n")
        self.assert_error(self.convert(gr, limit_bytes=1 << 30), f"{gr}: out of memory converting this input")

    @unittest.skipIf("ASAN_OPTIONS" in os.environ, UNDER_ASAN)
    def test_compressed_input_is_streamed(self):
        # 256 MB of comment lines in a gzip of well under 1 MB: the text must not be held whole.
        # Written piece by piece: a forked child's peak RSS counts the parent's pages before exec.
        comment = ("c " + "x" * 1022 + "\n").encode() * 1024
        gr = self.path("bomb.gr.gz")
        with gzip.GzipFile(gr, "wb", compresslevel=9, mtime=0) as f:
            for _ in range(256):
                f.write(comment)
            f.write(graph_text(3).encode())
        self.assertLess(os.path.getsize(gr), 1 << 20)
        before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        r = self.convert(gr)
        self.assertEqual(r.returncode, 0, r.stderr)
        peak_mib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
        self.assertLess(peak_mib, 64, f"peak RSS {peak_mib:.0f} MiB (children's maximum before: {before} KiB)")

    def test_error_after_chunk_boundaries_keeps_line_and_column(self):
        # Many chunks of 1 MiB before the bad line: its number and column are those of the plain file.
        text = graph_text(300000).replace("a 250000 250001 ", "a 250000 250001 x", 1)
        plain = self.write("late.gr", text)
        line = text[:text.index("a 250000 250001 x")].count("\n") + 1
        expected = self.convert(plain).stderr.replace(plain, self.path("late.gr.gz"))
        self.assertIn(f":{line}:17:", expected)
        packed = self.write("late.gr.gz", gzip.compress(text.encode(), mtime=0))
        r = self.convert(packed)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stderr, expected)

    def test_truncated_compressed_files_say_so(self):
        text = graph_text(20000)
        plain = self.write("t.gr", text)
        for tool, suffix, name in (("gzip", ".gz", "gzip"), ("bzip2", ".bz2", "bzip2"),
                                   ("xz", ".xz", "xz"), ("zstd", ".zst", "zstd")):
            if shutil.which(tool) is None:
                raise mosbtest.missing(f"no '{tool}' command")
            with self.subTest(tool=tool):
                packed = subprocess.run([tool, "-c", plain], capture_output=True, check=True).stdout
                cut = self.write("t.gr" + suffix, packed[:len(packed) // 2])
                self.assert_error(self.convert(cut),
                                  f"{cut}: the {name} data ends before its end marker: "
                                  "the file is truncated or corrupt")
                whole = self.write("w.gr" + suffix, packed)
                r = self.convert(whole)
                self.assertEqual(r.returncode, 0, r.stderr)
                os.remove(self.path("out.mosb"))

    def test_corrupt_gzip_names_the_file(self):
        packed = bytearray(gzip.compress(graph_text(20000).encode(), mtime=0))
        for i in range(len(packed) // 2, len(packed) // 2 + 64):
            packed[i] ^= 0x5A
        gr = self.write("c.gr.gz", bytes(packed))
        r = self.convert(gr)
        self.assertEqual(r.returncode, 1)
        self.assertRegex(r.stderr, "^mosb: " + gr.replace(".", r"\.") +
                         r": corrupt gzip data \([^)\n]+\): the file is truncated or corrupt\n$")


if __name__ == "__main__":
    mosbtest.main()
