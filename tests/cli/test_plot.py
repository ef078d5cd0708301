#!/usr/bin/python3
"""End-to-end tests of `mosb plot` (spec/EVALUATION.md §5).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_plot.py

Each figure is rendered by a real browser (Debian's chromium, headless); the screenshot must be a
PNG of the requested size with a substantial share of non-white pixels. Skipped without chromium.
"""

import functools
import json
import os
import re
import shutil
import struct
import subprocess
import zlib

import mosbtest
from mosbtest import DATA, WRITE_SOLUTION, CliTest, read, setUpModule, write_solution  # noqa: F401

CHROMIUM = shutil.which("chromium")
ARENA = os.path.join(DATA, "movingai", "arena2.map")


# Every run here must succeed unless it says check=False.
run = functools.partial(mosbtest.run, check=True)


def read_png(path):
    """(width, height, rows of RGB(A) bytes) of an 8-bit RGB or RGBA non-interlaced PNG."""
    data = read(path)
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


class PlotCase(CliTest):
    """The chromium screenshot check."""

    def screenshot(self, svg, width, height):
        """Renders svg in headless chromium; returns the share of non-white pixels."""
        if CHROMIUM is None:
            raise mosbtest.missing("chromium is not installed")
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

class PlotTest(PlotCase):
    def test_correlation_heat_map_renders(self):
        g = self.path("g.mosb")
        run("generate", "grid", "--width", "20", "--height", "20", "--objectives", "3", "-o", g)
        svg = self.path("corr.svg")
        run("plot", "correlation", g, "-o", svg, "--title", "grid <3>")
        text = read(svg, "r")
        self.assertIn("grid &lt;3&gt;", text)
        self.assertEqual(text.count(">1.00<"), 3)  # the diagonal
        run("plot", "correlation", g, "-o", self.path("again.svg"), "--title", "grid <3>")
        self.assertEqual(read(self.path("again.svg"), "r"), text)
        self.assertGreater(self.screenshot(svg, 640, 480), 0.05)

    def test_map_renders_blocked_cells_and_exposure(self):
        self.skip_unless_present(ARENA)
        guards = self.path("guards.txt")
        with open(guards, "w") as f:
            f.write("120 100 25\n")  # a passable cell of arena2
        g = self.path("arena.mosb")
        run("convert", "guards", "--map", ARENA, "--guards", guards, "-o", g)
        svg = self.path("map.svg")
        run("plot", "map", g, "-o", svg)
        text = read(svg, "r")
        self.assertIn("blocked cell", text)
        self.assertIn("#252525", text)    # blocked cells drawn
        self.assertIn("exposure 1", text)  # the legend's highest exposure
        self.assertIn(">exposure [guards]<", text)  # the objective's unit
        # The guard is marked where it stands (metadata map.guards), and the legend says so.
        self.assertIn('class="guards" data-count="1"', text)
        self.assertIn(">guard<", text)
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


class PaperFigureTest(PlotCase):
    """Issue 22 §3: `-o fig.pdf|fig.png` rendered by librsvg and cairo, sized for a paper."""

    def setUp(self):
        super().setUp()
        self.grid = self.path("g.mosb")
        run("generate", "grid", "--width", "20", "--height", "20", "--objectives", "3", "-o",
            self.grid)

    def test_pdf_opens_at_the_asked_size_and_is_the_same_twice(self):
        if shutil.which("pdfinfo") is None:
            raise mosbtest.missing("pdfinfo (poppler-utils) is not installed")
        pdf = self.path("rho.pdf")
        run("plot", "correlation", self.grid, "-o", pdf, "--width", "3.5in")
        info = subprocess.run(["pdfinfo", pdf], capture_output=True, text=True, check=True).stdout
        self.assertIn("Pages:           1", info)
        width, height = map(float, re.search(r"Page size:\s+([0-9.]+) x ([0-9.]+) pts",
                                             info).groups())
        self.assertAlmostEqual(width, 252, delta=0.5)  # 3.5 in
        self.assertGreater(height, 100)
        text = subprocess.run(["pdftotext", pdf, "-"], capture_output=True, text=True).stdout
        self.assertIn("Pearson", text)  # text stays text
        again = self.path("again.pdf")
        run("plot", "correlation", self.grid, "-o", again, "--width", "3.5in")
        self.assertEqual(read(again), read(pdf))
        run("plot", "correlation", self.grid, "-o", pdf, "--width", "8cm", "--height", "6cm")
        info = subprocess.run(["pdfinfo", pdf], capture_output=True, text=True, check=True).stdout
        self.assertIn("226.772 x 170.079 pts", info)  # 8 cm x 6 cm

    def test_png_has_the_size_and_is_not_blank(self):
        png = self.path("rho.png")
        run("plot", "correlation", self.grid, "-o", png, "--width", "3.5in", "--dpi", "200")
        w, h, channels, rows = read_png(png)
        self.assertEqual(w, 700)
        coloured = sum(1 for row in rows for x in range(0, w * channels, channels)
                       if min(row[x:x + 3]) < 235)
        self.assertGreater(coloured / (w * h), 0.05)
        self.assertLess(coloured / (w * h), 0.9)

    def test_bad_format_and_size_are_usage_errors(self):
        for args, message in ((["-o", self.path("f.jpg")], "write a figure as .svg, .pdf or .png"),
                              (["-o", self.path("f.pdf"), "--width", "3.5"],
                               "--width: '3.5' is not a length"),
                              (["-o", self.path("f.png"), "--height", "0in"], "--height:"),
                              (["-o", self.path("f.svg"), "--width", "3in"], "an SVG keeps")):
            r = run("plot", "correlation", self.grid, *args, check=False)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertIn(message, r.stderr)
            self.assertFalse(os.path.exists(args[1]))


class SolutionPlotTest(PlotCase):
    """`plot front` and `plot cardinality` on solution files imported from per-query front files
    of a generated 3-objective grid with a 3-query set (query 2 is left unsolved)."""

    def setUp(self):
        super().setUp()
        run("generate", "grid", "--width", "5", "--height", "4", "--objectives", "3", "-o",
            self.path("bare.mosb"))
        self.write("q.txt", "0 19\n1 18\n2 17\n")
        self.grid = self.path("g.mosb")
        run("queries", "import", self.path("bare.mosb"), self.path("q.txt"), "--set", "s", "-o",
            self.grid)
        self.reference = self.import_("ref.sol", {"0.txt": "10 40 5\n20 20 7\n40 10 9\n",
                                                  "1.txt": "30 30 30\n"}, "--solver", "exact")
        self.solutions = self.import_("sol.sol", {"0.txt": "10 40 5\n21 21 8\n40 10 9\n"},
                                      "--solver", "approx", "--epsilon", "0.1")

    def import_(self, name, fronts, *extra, instance=None):
        for file, text in fronts.items():
            self.write(os.path.join(name + ".d", file), text)
        path = self.path(name)
        run("solutions", "import", "--instance", instance or self.grid, "--view", "Grid_3",
            "--queries", "s", "--dir", self.path(name + ".d"), *extra, "-o", path)
        return path

    def texts(self, svg):
        return re.findall(r"<text[^>]*>([^<]*)</text>", read(svg, "r"))

    def assert_refused(self, args, code, *expected):
        svg = self.path("bad.svg")
        r = run(*args, "-o", svg, check=False)
        self.assertEqual(r.returncode, code, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        for text in expected:
            self.assertIn(text, r.stderr)
        self.assertFalse(os.path.exists(svg))

    def test_front_against_reference_with_epsilon_boxes(self):
        svg = self.path("front.svg")
        args = ["plot", "front", "--solutions", self.solutions, "--reference", self.reference,
                "--query", "0", "--eps", "0.05"]
        run(*args, "-o", svg)
        texts = self.texts(svg)
        self.assertEqual(texts[0], "query 0 of s: approx vs reference")
        for label in ("c1", "c2", "reference exact (3 vectors)", "approx (3 vectors)",
                      "ε-box, ε = 0.05"):
            self.assertIn(label, texts)
        text = read(svg, "r")
        self.assertEqual(text.count('fill="#56B4E9"'), 3 + 1)  # a box per reference vector, legend
        run(*args, "-o", self.path("again.svg"))
        self.assertEqual(read(self.path("again.svg"), "r"), text)
        self.assertGreater(self.screenshot(svg, 720, 480), 0.01)

    def test_front_of_a_chosen_pair_without_reference(self):
        svg = self.path("front.svg")
        run("plot", "front", "--solutions", self.solutions, "--query", "0", "--objectives",
            "c3,1", "-o", svg)
        texts = self.texts(svg)
        self.assertIn("c3", texts)  # x axis
        self.assertIn("c2", texts)  # y axis, by position
        self.assertNotIn("c1", texts)
        self.assertIn("approx (3 vectors)", texts)
        self.assertFalse(any(t.startswith("reference") for t in texts), texts)
        # The c3 values 5, 8, 9 set the x range, from 0: no tick beyond 10.
        self.assertIn("10", texts)
        self.assertNotIn("40", texts[:texts.index("c3")][:7])

    def test_front_legend_axes_and_projection(self):
        """Issue 22 §2: the legend says what it counts, both plots of a query start at 0, a
        3-objective front says it is a projection, units label the axes."""
        with_reference = self.path("with.svg")
        run("plot", "front", "--solutions", self.solutions, "--reference", self.reference,
            "--query", "0", "--eps", "0.5", "-o", with_reference)
        alone = self.path("alone.svg")
        run("plot", "front", "--solutions", self.solutions, "--query", "0", "--instance",
            self.grid, "-o", alone)
        for svg in (with_reference, alone):
            texts = self.texts(svg)
            self.assertIn("projection on c1, c2 of 3 objectives", texts)
            self.assertIn("approx (3 vectors)", texts)
            self.assertNotIn("solver (3)", texts)
            text = read(svg, "r")
            # The x axis's first tick, 0, at the plot area's left edge; the y axis's at its foot.
            self.assertIn('<text x="90" y="431" text-anchor="middle" font-size="13" '
                          'fill="#000">0</text>', text)
            self.assertIn('<text x="82" y="415" text-anchor="end" font-size="13" '
                          'fill="#000">0</text>', text)
            sizes = [float(v) for v in re.findall(r'font-size="([0-9.]+)"', text)]
            self.assertGreaterEqual(min(sizes), 13)
        self.assertIn("reference exact (3 vectors)", self.texts(with_reference))
        # The grid's objectives have no unit: the names alone.
        self.assertIn("c1", self.texts(alone))
        other = self.path("other.mosb")
        run("generate", "grid", "--width", "5", "--height", "4", "--objectives", "3", "--seed",
            "9", "-o", other)
        self.assert_refused(["plot", "front", "--solutions", self.solutions, "--query", "0",
                             "--instance", other], 1, "sol.sol")

    def test_front_errors(self):
        front = ["plot", "front", "--solutions", self.solutions]
        self.assert_refused(front + ["--query", "3"], 2, "--query 3", "sol.sol has 3 queries")
        self.assert_refused(front + ["--query", "1"], 1,
                            "sol.sol: query 1 is not-run, not solved")
        self.assert_refused(front + ["--query", "0", "--objectives", "c1,cost"], 2,
                            "'cost' is not an objective of", "c1, c2, c3")
        self.assert_refused(front + ["--query", "0", "--objectives", "c1"], 2,
                            "give two different objectives")
        self.assert_refused(front + ["--query", "0", "--eps", "0.1"], 2, "give --reference")
        self.assert_refused(front + ["--query", "0", "--reference", self.reference, "--eps",
                                     "-1"], 2, "--eps: invalid epsilon '-1'")
        # A reference of another instance: both files and both digests.
        run("generate", "grid", "--width", "5", "--height", "4", "--objectives", "3", "--seed",
            "9", "-o", self.path("bare9.mosb"))
        other = self.path("g9.mosb")
        run("queries", "import", self.path("bare9.mosb"), self.path("q.txt"), "--set", "s", "-o",
            other)
        foreign = self.import_("foreign.sol", {"0.txt": "1 2 3\n"}, instance=other)

        def digest(path):
            return json.loads(run("solutions", "inspect", "--json", path).stdout)[
                "instance_digest"]

        self.assert_refused(front + ["--reference", foreign, "--query", "0"], 1,
                            "foreign.sol", "sol.sol", digest(foreign), digest(self.solutions))

    def test_cardinality_leaves_unsolved_queries_out(self):
        svg = self.path("card.svg")
        run("plot", "cardinality", "--solutions", self.reference, "-o", svg)
        texts = self.texts(svg)
        self.assertEqual(texts[0], "exact on s: front size per query (1 unsolved query left out)")
        self.assertIn("2 queries", texts)
        self.assertIn("front size", texts)
        # Sorted: rank 1 has size 1, rank 2 size 3; whole-number ticks only.
        self.assertNotIn("0.5", texts)
        (points,) = re.findall(r'<polyline points="([^"]*)"', read(svg, "r"))
        ys = [float(p.split(",")[1]) for p in points.split()]
        self.assertEqual(len(ys), 2)
        self.assertGreater(ys[0], ys[1])  # SVG y grows downwards: the second front is larger
        run("plot", "cardinality", "--solutions", self.solutions, "-o", svg, "--title", "t")
        self.assertEqual(self.texts(svg)[0], "t (2 unsolved queries left out)")
        self.assertGreater(self.screenshot(svg, 720, 480), 0.01)


class MapPathsTest(PlotCase):
    """`plot map --solutions S --query K`: a hand-written 4x3 Moving AI map with one blocked cell;
    the solution file (SolutionWriter, through the test helper) gives two paths of query 0."""

    # Passable cells in row-major order are the vertices: row 0 is 0-3, row 1 (x=1 blocked) 4-6,
    # row 2 is 7-10.
    MAP = "type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n"

    def setUp(self):
        super().setUp()
        if not os.path.exists(WRITE_SOLUTION):
            raise mosbtest.missing("WRITE_SOLUTION (mosb_test_write_solution) is not built")
        for name, text in (("tiny.map", self.MAP), ("guards.txt", "3 0 1\n"), ("q.txt", "0 10\n")):
            self.write(name, text)
        run("convert", "guards", "--map", self.path("tiny.map"), "--guards",
            self.path("guards.txt"), "-o", self.path("bare.mosb"))
        self.map = self.path("tiny.mosb")
        run("queries", "import", self.path("bare.mosb"), self.path("q.txt"), "--set", "s", "-o",
            self.map)

    def solutions(self, name, spec):
        return write_solution(self.path(name), self.map, "Games-GUARDS_2", spec, "0", "s")

    def test_paths_drawn_on_the_map(self):
        # (0,0) (1,0) (2,0) (3,1) (3,2), and (0,0) (0,1) (0,2) (1,2) (2,2) (3,2).
        sol = self.solutions("paths.sol", "0 solved 44,2@0/1/2/6/10 50,1@0/4/7/8/9/10\n")
        svg = self.path("map.svg")
        run("plot", "map", self.map, "--solutions", sol, "--query", "0", "-o", svg)
        text = read(svg, "r")
        polylines = re.findall(r'<polyline points="([^"]*)"', text)
        self.assertEqual(len(polylines), 2, text)
        cells = [[tuple(float(c) for c in p.split(",")) for p in line.split()]
                 for line in polylines]
        self.assertEqual([len(c) for c in cells], [5, 6])
        # Same cell size both ways; the first path's third step is a diagonal.
        (x0, y0), (x1, y1) = cells[0][0], cells[0][1]
        step = x1 - x0
        self.assertGreater(step, 0)
        self.assertEqual(y1, y0)
        self.assertEqual(cells[0][3], (x0 + 3 * step, y0 + step))
        self.assertEqual(cells[1][-1], (x0 + 3 * step, y0 + 2 * step))
        self.assertIn(">path 1<", text)
        self.assertIn(">path 2<", text)
        self.assertGreater(self.screenshot(svg, 900, 560), 0.05)

    def test_front_axes_carry_the_instance_units(self):
        sol = self.solutions("units.sol", "0 solved 44,2 50,1\n")
        svg = self.path("front.svg")
        run("plot", "front", "--solutions", sol, "--query", "0", "--instance", self.map, "-o", svg)
        texts = re.findall(r"<text[^>]*>([^<]*)</text>", read(svg, "r"))
        self.assertIn("exposure [guards]", texts)  # objective.exposure.unit of --guards
        self.assertFalse(any(t.startswith("projection") for t in texts), texts)  # d = 2
        run("plot", "front", "--solutions", sol, "--query", "0", "-o", svg)
        self.assertIn("exposure", re.findall(r"<text[^>]*>([^<]*)</text>", read(svg, "r")))

    def test_map_paths_errors(self):
        without = self.solutions("nopaths.sol", "0 solved 44,2\n")
        svg = self.path("m.svg")
        for args, code, message in (
                (["--solutions", without, "--query", "0"], 1,
                 "nopaths.sol: the solver gave no paths"),
                (["--solutions", without], 2, "--solutions and --query go together"),
                (["--query", "0"], 2, "--solutions and --query go together")):
            r = run("plot", "map", self.map, *args, "-o", svg, check=False)
            self.assertEqual(r.returncode, code, r.stderr)
            self.assertIn(message, r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertFalse(os.path.exists(svg))
        timeout = self.solutions("timeout.sol", "0 timeout\n")
        # A file with no front has no paths either: the status is what the user needs to know.
        r = run("plot", "map", self.map, "--solutions", timeout, "--query", "0", "-o", svg,
                check=False)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertFalse(os.path.exists(svg))


class HostileMetadataTest(PlotCase):
    """Issue 36 §1-§2: files that pass `verify --level full` whose map metadata or front values
    crashed, hung or exhausted memory. Each must be drawn in bounded time and memory or refused
    in one line, nothing written."""

    MAP = MapPathsTest.MAP  # 4 x 3, one wall: 11 vertices

    def setUp(self):
        super().setUp()
        self.write("tiny.map", self.MAP)
        self.write("guards.txt", "3 0 1\n")
        self.map = self.path("tiny.mosb")
        run("convert", "guards", "--map", self.path("tiny.map"), "--guards",
            self.path("guards.txt"), "-o", self.map)

    def with_map(self, name, **values):
        data = bytearray(read(self.map))
        mosbtest.set_metadata(data, **values)
        path = self.write(name, bytes(data))
        self.ok("verify", "--level", "full", path)  # valid files: only their metadata lies
        return path

    def test_map_metadata_that_does_not_fit_the_instance_is_refused(self):
        svg = self.path("m.svg")
        for width, height, message in (
                ("-5", "3", "metadata map.width '-5' is not a whole number from 1 to 4294967295"),
                ("5x", "3", "metadata map.width '5x' is not a whole number"),
                ("4294967301", "3", "metadata map.width '4294967301' is not a whole number"),
                ("4", "0", "metadata map.height '0' is not a whole number"),
                ("4294967295", "4294967295",
                 "4294967295 x 4294967295 map (18446744065119617025 cells), more than the "
                 "4294967294 a map may have"),
                ("100000", "100000", "(10000000000 cells), more than the 4294967294"),
                ("2", "5", "its 11 vertices do not fit a 2 x 5 map (10 cells)")):
            with self.subTest(width=width, height=height):
                bad = self.with_map("bad.mosb", **{"map.width": width, "map.height": height})
                r = self.mosb("plot", "map", bad, "-o", svg, timeout=120)
                self.assert_one_line_error(r, "bad.mosb: ", message)
                self.assertFalse(os.path.exists(svg))

    def test_a_huge_map_of_few_cells_is_drawn_in_squares(self):
        # 3.6 billion cells, all blocked but the 11 in the corner: drawn from the vertices alone.
        huge = self.with_map("huge.mosb", **{"map.width": "60000", "map.height": "60000"})
        svg = self.path("huge.svg")
        self.ok("plot", "map", huge, "-o", svg, timeout=120)
        text = read(svg, "r")
        self.assertIn(">1 square: 59x59 cells<", text)  # 1017 squares a side, at most 1024
        self.assertLess(len(text), 1_000_000)

    def test_front_of_values_up_to_the_largest_double(self):
        if not os.path.exists(WRITE_SOLUTION):
            raise mosbtest.missing("WRITE_SOLUTION (mosb_test_write_solution) is not built")
        grid = self.path("g.mosb")
        run("generate", "grid", "--width", "3", "--height", "3", "-o", grid)
        data = bytearray(read(grid))
        for column in ("c1", "c2"):  # both objectives f64
            costs = mosbtest.values(data, column, "B")
            mosbtest.relocate_as_float(data, column, [float(c) for c in costs], mosbtest.F64)
        f64 = self.write("f64.mosb", bytes(data))
        largest = "1.7976931348623157e308"
        spec = "0 solved %s,3 2,%s\n" % (largest, largest)
        sol = write_solution(self.path("s.sol"), f64, "Grid_2", spec, "0")
        ref = write_solution(self.path("r.sol"), f64, "Grid_2", spec, "0")
        svg = self.path("front.svg")
        # Alone (the axis walked its ticks past the largest double for 48 s, then bad_alloc),
        # and with ε-boxes whose far corners lie past it.
        for extra in ([], ["--reference", ref, "--eps", "0.5"]):
            self.ok("plot", "front", "--solutions", sol, *extra, "--query", "0", "-o", svg,
                    timeout=120)
            texts = re.findall(r"<text[^>]*>([^<]*)</text>", read(svg, "r"))
            self.assertIn("1.5e+308", texts)
            self.assertFalse([t for t in texts if "inf" in t or "nan" in t], texts)
            self.assertNotRegex(read(svg, "r"), r'(width|height)="-')


if __name__ == "__main__":
    mosbtest.main()
