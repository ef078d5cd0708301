#!/usr/bin/python3
"""End-to-end tests of `mosb plot` (spec/EVALUATION.md §5).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_plot.py

Each figure is rendered by a real browser (Debian's chromium, headless); the screenshot must be a
PNG of the requested size with a substantial share of non-white pixels. Skipped without chromium.
"""

import os
import shutil
import struct
import subprocess
import tempfile
import unittest
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
MOSB = os.path.abspath(os.environ.get("MOSB", "mosb"))
CHROMIUM = shutil.which("chromium")
ARENA = os.path.join(HERE, "..", "..", "..", "shared", "data", "movingai", "arena2.map")


def run(*args, check=True):
    result = subprocess.run([MOSB, *args], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError("mosb %s failed: %s" % (" ".join(args), result.stderr))
    return result


def read(path, mode="r"):
    with open(path, mode, **({} if "b" in mode else {"encoding": "utf-8"})) as f:
        return f.read()


def read_png(path):
    """(width, height, rows of RGB(A) bytes) of an 8-bit RGB or RGBA non-interlaced PNG."""
    data = read(path, "rb")
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and colour in (2, 6) and interlace == 0, header
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return width, height, channels, rows


class PlotTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def screenshot(self, svg, width, height):
        """Renders svg in headless chromium; returns the share of non-white pixels."""
        if CHROMIUM is None:
            self.skipTest("chromium is not installed")
        png = svg + ".png"
        subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                        "--hide-scrollbars", "--screenshot=" + png,
                        "--window-size=%d,%d" % (width, height), "file://" + svg],
                       capture_output=True, timeout=120, check=True)
        self.assertGreater(os.path.getsize(png), 0)
        w, h, channels, rows = read_png(png)
        self.assertEqual((w, h), (width, height))
        coloured = 0
        for row in rows:
            for x in range(0, w * channels, channels):
                if min(row[x:x + 3]) < 235:
                    coloured += 1
        return coloured / (w * h)

    def test_correlation_heat_map_renders(self):
        g = self.path("g.mosb")
        run("generate", "grid", "--width", "20", "--height", "20", "--objectives", "3", "-o", g)
        svg = self.path("corr.svg")
        run("plot", "correlation", g, "-o", svg, "--title", "grid <3>")
        text = read(svg)
        self.assertIn("grid &lt;3&gt;", text)
        self.assertEqual(text.count(">1.00<"), 3)  # the diagonal
        run("plot", "correlation", g, "-o", self.path("again.svg"), "--title", "grid <3>")
        self.assertEqual(read(self.path("again.svg")), text)
        self.assertGreater(self.screenshot(svg, 640, 480), 0.05)

    def test_map_renders_blocked_cells_and_exposure(self):
        if not os.path.exists(ARENA):
            self.skipTest("../shared/data/movingai/arena2.map is absent")
        guards = self.path("guards.txt")
        with open(guards, "w") as f:
            f.write("120 100 25\n")  # a passable cell of arena2
        g = self.path("arena.mosb")
        run("convert", "guards", "--map", ARENA, "--guards", guards, "-o", g)
        svg = self.path("map.svg")
        run("plot", "map", g, "-o", svg)
        text = read(svg)
        self.assertIn("blocked cell", text)
        self.assertIn("#252525", text)    # blocked cells drawn
        self.assertIn("exposure 1", text)  # the legend's highest exposure
        share = self.screenshot(svg, 900, 560)
        self.assertGreater(share, 0.3)  # arena2 is mostly blocked
        self.assertLess(share, 0.95)

    def test_map_of_a_non_grid_instance_is_refused(self):
        g = self.path("g.mosb")
        run("generate", "grid", "--width", "4", "--height", "4", "-o", g)
        r = run("plot", "map", g, "-o", self.path("m.svg"), check=False)
        self.assertEqual(r.returncode, 1)
        self.assertIn("g.mosb: not a grid instance", r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1)
        self.assertFalse(os.path.exists(self.path("m.svg")))


if __name__ == "__main__":
    unittest.main()
