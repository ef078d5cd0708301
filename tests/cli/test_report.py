#!/usr/bin/python3
"""End-to-end tests of `mosb report` (spec/EVALUATION.md §7), in a real browser.

    MOSB=build/release/tools/mosb EXAMPLES=build/release/examples /usr/bin/python3 tests/cli/test_report.py

A small suite is built once: a generated Grid (30x30, 3 objectives), a generated NetMaker (1000
vertices) and, when shared/data holds it, the Moving AI map arena2 converted with a guard; each
gets a query set of a few queries, solved by the example NAMOA* (every view) and BOA* (the
bi-objective ones) through `mosb run`. The report of it is opened in headless chromium: with
script the DOM must show the sorting script ran and no console message may be an error; without
its script the tables must still be there; every figure, drawn alone as an image, must render
non-blank. Skipped without chromium or the example solvers.
"""

import functools
import os
import re
import shutil
import subprocess
import tempfile
import unittest
from html.parser import HTMLParser

import mosbtest
from mosbtest import DATA, read, setUpModule  # noqa: F401
from test_plot import read_png

CHROMIUM = shutil.which("chromium")
EXAMPLES = os.path.abspath(os.environ.get("EXAMPLES", ""))
ARENA = os.path.join(DATA, "movingai", "arena2.map")

run = functools.partial(mosbtest.run, check=True)


def compile_latex(test, directory):
    """Every .tex table of `directory` compiled by pdflatex in a document as a paper has it
    (booktabs), each on its own: a table that does not compile is not ready to \\input."""
    pdflatex = shutil.which("pdflatex")
    if pdflatex is None:
        raise mosbtest.missing("pdflatex (texlive-latex-base, texlive-latex-recommended)")
    tables = sorted(f for f in os.listdir(directory) if f.endswith(".tex"))
    test.assertTrue(tables)
    for table in tables:
        document = os.path.join(directory, "doc-" + table)
        with open(document, "w") as f:
            f.write("\\documentclass{article}\n\\usepackage{booktabs}\n\\begin{document}\n"
                    "\\input{%s}\n\\end{document}\n" % table)
        r = subprocess.run([pdflatex, "-interaction=nonstopmode", "-halt-on-error",
                            "-no-shell-escape", os.path.basename(document)], cwd=directory,
                           capture_output=True, text=True, errors="replace", timeout=120)
        test.assertEqual(r.returncode, 0, table + ":\n" + r.stdout[-3000:])
        test.assertTrue(os.path.exists(document[:-4] + ".pdf"), table)


def chromium(*args, timeout=120):
    return subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                           "--hide-scrollbars", "--no-first-run", "--disable-extensions",
                           *args], capture_output=True, text=True, errors="replace",
                          timeout=timeout)


def console_errors(stderr):
    """Console messages of level error and uncaught exceptions in chromium's log on stderr."""
    return [line for line in stderr.splitlines()
            if "Uncaught" in line or ("CONSOLE" in line and ":ERROR:" in line)
            or "console.error" in line]


class Tables(HTMLParser):
    """Each <table>'s id and rows of cell texts and data-v values; each <figure>'s kind, its
    <text> contents and whether it holds an <svg>."""

    def __init__(self):
        super().__init__()
        self.tables, self.figures, self.sortable_headings = {}, [], 0
        self._table = self._row = self._cell = None
        self._figure = None
        self._in_text = False

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "table":
            self._table = self.tables.setdefault(attrs.get("id"), [])
        elif tag == "tr" and self._table is not None:
            self._row = []
            self._table.append(self._row)
        elif tag in ("td", "th") and self._row is not None:
            self._cell = [attrs.get("data-v"), ""]
            self._row.append(self._cell)
            if tag == "th" and attrs.get("tabindex") == "0":
                self.sortable_headings += 1
        elif tag == "figure":
            self._figure = {"kind": attrs.get("data-figure"), "texts": [], "svg": False,
                            "groups": []}
            self.figures.append(self._figure)
        elif tag == "svg" and self._figure is not None:
            self._figure["svg"] = True
        elif tag == "text" and self._figure is not None:
            self._in_text = True
            self._figure["texts"].append("")
        elif tag == "g" and self._figure is not None and "data-series" in attrs:
            self._figure["groups"].append(attrs)

    def handle_endtag(self, tag):
        if tag == "table":
            self._table = None
        elif tag == "tr":
            self._row = None
        elif tag in ("td", "th"):
            self._cell = None
        elif tag == "figure":
            self._figure = None
        elif tag == "text":
            self._in_text = False

    def handle_data(self, data):
        if self._cell is not None:
            self._cell[1] += data
        if self._in_text and self._figure is not None:
            self._figure["texts"][-1] += data


def parse(html):
    p = Tables()
    p.feed(html)
    return p


class ReportTest(unittest.TestCase):
    """One suite, solution files and report for the whole class (the solver runs are the slow
    part); each test reads what it needs."""

    @classmethod
    def setUpClass(cls):
        if CHROMIUM is None:
            raise unittest.SkipTest("chromium is not installed")
        if not os.path.isfile(os.path.join(EXAMPLES, "boa_star")):
            raise unittest.SkipTest("EXAMPLES (the example solvers' directory) is not set")
        cls.dir = tempfile.mkdtemp(prefix="mosb-report-")
        d = cls.dir
        path = functools.partial(os.path.join, d)
        run("generate", "grid", "--width", "30", "--height", "30", "--objectives", "3", "-o",
            path("grid.mosb"))
        run("generate", "netmaker", "--vertices", "1000", "--amin", "1", "--amax", "10",
            "--locality", "20", "-o", path("netmaker.mosb"))
        cls.instances = [path("grid.mosb"), path("netmaker.mosb")]
        runs = [("grid.mosb", "Grid_2", True)]
        runs.append(("netmaker.mosb", "NetMaker-1k_3", False))
        cls.has_arena = os.path.exists(ARENA)
        if cls.has_arena:
            with open(path("guards.txt"), "w") as f:
                f.write("120 100 25\n")  # a passable cell of arena2: exposure within 25 cells
            run("convert", "guards", "--map", ARENA, "--guards", path("guards.txt"), "-o",
                path("arena.mosb"))
            cls.instances.append(path("arena.mosb"))
            runs.append(("arena.mosb", "Games-GUARDS_2", True))
        for instance in cls.instances:
            run("queries", "generate", instance, "--set", "q", "--count", "5", "--seed", "3",
                "--in-place")
        cls.boa, cls.namoa = [], []
        for instance, view, bi_objective in runs:
            solvers = [("namoa", cls.namoa)] + ([("boa_star", cls.boa)] if bi_objective else [])
            for solver, files in solvers:
                out = path("%s-%s.sol" % (solver, instance.split(".")[0]))
                run("run", path(instance), "--view", view, "--queries", "q", "--solver",
                    os.path.join(EXAMPLES, solver) +
                    " {instance} --view {view} --query {source} {target} --protocol",
                    "--time-limit", "60s", "--memory-limit", "2G", "-o", out)
                files.append(out)
        cls.html = path("report.html")
        cls.report_args = [*cls.instances, "--solutions", *cls.boa, *cls.namoa, "--reference",
                           *cls.namoa, "--title", "mosb report <test>"]
        run("report", *cls.report_args, "-o", cls.html, "--latex", path("latex"), "--csv",
            path("csv"))
        cls.text = read(cls.html, "r")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def path(self, name):
        return os.path.join(self.dir, name)

    # --- the page in the browser ------------------------------------------------------------

    def test_console_error_detection_works(self):
        """The check below would see an error: a page that throws is caught."""
        bad = self.path("throws.html")
        with open(bad, "w") as f:
            f.write("<!DOCTYPE html><p>x</p><script>throw new Error('boom')</script>")
        r = chromium("--enable-logging=stderr", "--v=0", "--dump-dom", "file://" + bad)
        self.assertTrue(console_errors(r.stderr), r.stderr[-2000:])

    def test_page_loads_without_console_errors_and_the_script_runs(self):
        r = chromium("--enable-logging=stderr", "--v=0", "--dump-dom", "file://" + self.html)
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        self.assertEqual(console_errors(r.stderr), [])
        page = parse(r.stdout)
        # The sorting script made every heading a keyboard-focusable button.
        headings = sum(len(t[0]) for t in page.tables.values())
        self.assertGreater(headings, 10)
        self.assertEqual(page.sortable_headings, headings)
        self.assertIn("mosb report &lt;test&gt;", r.stdout)

    def test_tables_are_there_without_script(self):
        # Headless chromium's --dump-dom and --screenshot run script of their own, so they return
        # nothing with scriptEnabled=false: the page is loaded without its <script> instead, which
        # is what a browser with script off shows.
        self.assertEqual(self.text.count("<script>"), 1)
        copy = self.path("noscript.html")
        with open(copy, "w", encoding="utf-8") as f:
            f.write(re.sub(r"<script>.*?</script>", "", self.text, flags=re.S))
        r = chromium("--dump-dom", "file://" + copy)
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        page = parse(r.stdout)
        self.assertEqual(page.sortable_headings, 0)  # the script did not run
        for table in ("suite-table", "instance-space-table", "comparison-table",
                      "coverage-table"):
            self.assertIn(table, page.tables)
            self.assertGreater(len(page.tables[table]), 1, table)
        suite = page.tables["suite-table"]
        headings = [c[1] for c in suite[0]]
        for column in ("family", "benchmark", "vertices", "arcs", "queries", "timeout",
                       "front min", "front max", "front mean", "front median",
                       "median runtime [s]", "max runtime [s]"):
            self.assertIn(column, headings)
        rows = {row[1][1]: dict(zip(headings, (c[1] for c in row))) for row in suite[1:]}
        self.assertEqual(rows["Grid_2"]["vertices"], "902")
        self.assertEqual(rows["Grid_2"]["queries"], "5")
        self.assertEqual(rows["Grid_2"]["timeout"], "0")
        self.assertEqual(rows["NetMaker-1k_3"]["vertices"], "1000")
        self.assertEqual(rows["Grid_3"]["fronts of"], "-")  # no solver ran Grid_3
        comparison = page.tables["comparison-table"]
        self.assertIn("boa_star", [row[2][1] for row in comparison[1:]])

    def test_every_figure_renders(self):
        page = parse(self.text)
        kinds = [f["kind"] for f in page.figures]
        for kind in ("instance-space", "correlation", "degrees", "front", "cactus", "profile",
                     "scatter", "coverage"):
            self.assertIn(kind, kinds)
        if self.has_arena:
            (game_map,) = [f for f in page.figures if f["kind"] == "map"]
            self.assertIn("start (query number)", game_map["texts"])
            self.assertIn("1 square: 2x2 cells", game_map["texts"])  # 281 x 209 cells
            # Each drawn query's start and goal labelled with its number.
            numbers = [t for t in game_map["texts"] if t.isdigit()]
            self.assertEqual(len(numbers), 6, game_map["texts"])
        for f in page.figures:
            self.assertTrue(f["svg"], f["kind"])
            self.assertTrue(any(t.strip() for t in f["texts"]), f["kind"])
        # Each figure alone, as an image (an XML error leaves it blank), on one page of tiles.
        svgs = re.findall(r"<svg .*?</svg>", self.text, re.S)
        self.assertEqual(len(svgs), len(page.figures))
        tile_w, tile_h, columns = 240, 150, 6
        rows = (len(svgs) + columns - 1) // columns
        tiles = self.path("tiles.html")
        import base64
        with open(tiles, "w") as out:
            out.write("<!DOCTYPE html><html><body style='margin:0;background:#fff'>")
            for k, svg in enumerate(svgs):
                data = base64.b64encode(svg.encode()).decode()
                out.write("<img style='position:absolute;left:%dpx;top:%dpx;width:%dpx;height:%dpx;"
                          "object-fit:contain' src='data:image/svg+xml;base64,%s'>"
                          % ((k % columns) * tile_w, (k // columns) * tile_h, tile_w - 10,
                             tile_h - 10, data))
            out.write("</body></html>")
        png = self.path("tiles.png")
        r = chromium("--screenshot=" + png, "--window-size=%d,%d" % (columns * tile_w,
                                                                      rows * tile_h),
                     "file://" + tiles)
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        w, h, channels, pixels = read_png(png)
        self.assertEqual((w, h), (columns * tile_w, rows * tile_h))
        for k in range(len(svgs)):
            x0, y0 = (k % columns) * tile_w, (k // columns) * tile_h
            coloured = 0
            for y in range(y0, y0 + tile_h - 10):
                row = pixels[y]
                for x in range(x0, x0 + tile_w - 10):
                    if min(row[x * channels:x * channels + 3]) < 200:
                        coloured += 1
            # A blank tile (white: the SVG failed to render) has none; a figure has its frame,
            # text and marks.
            self.assertGreater(coloured / ((tile_w - 10) * (tile_h - 10)), 0.02,
                               "figure %d (%s) rendered blank" % (k, page.figures[k]["kind"]))

    def test_screenshot_of_the_page_is_not_blank(self):
        png = self.path("page.png")
        r = chromium("--screenshot=" + png, "--window-size=900,700", "file://" + self.html)
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        w, h, channels, pixels = read_png(png)
        dark = sum(1 for row in pixels for x in range(0, w * channels, channels * 4)
                   if min(row[x:x + 3]) < 128)
        self.assertGreater(dark, 200)

    # --- what the page says -----------------------------------------------------------------

    def test_instance_space_carries_the_papers_correlations(self):
        page = parse(self.text)
        table = page.tables["instance-space-table"]
        headings = [c[1] for c in table[0]]
        rows = {row[0][1]: {h: c[0] for h, c in zip(headings, row)} for row in table[1:]}
        netmaker = [name for name in rows if name.startswith("NetMaker-1k_3, arcs of kind 0")]
        self.assertEqual(len(netmaker), 1, list(rows))
        # The Hamiltonian cycle's arcs: the paper's ρ ≈ −0.44 (spec/GENERATORS.md: −0.444), drawn
        # as |ρ| as the paper's figure is.
        self.assertAlmostEqual(float(rows[netmaker[0]]["|ρ| mean"]), 0.444, delta=0.06)
        self.assertAlmostEqual(float(rows[netmaker[0]]["|ρ| min"]), 0.444, delta=0.08)
        for grid in ("Grid_2", "Grid_3"):
            for column in ("|ρ| min", "|ρ| max"):
                self.assertLess(float(rows[grid][column]), 0.08, (grid, rows[grid]))
        # The figure's own numbers are the table's.
        (space,) = [f for f in page.figures if f["kind"] == "instance-space"]
        groups = {g["data-series"]: [float(v) for v in g["data-rho"].split(",")]
                  for g in space["groups"]}
        self.assertEqual(len(groups[netmaker[0]]), 3)
        for rho in groups[netmaker[0]]:
            self.assertAlmostEqual(rho, 0.444, delta=0.08)
        self.assertEqual(len(groups["Grid_3"]), 3)
        # The other reading, signed ρ, on request.
        signed = self.path("signed.html")
        run("report", *self.report_args, "--signed-rho", "-o", signed)
        (space,) = [f for f in parse(read(signed, "r")).figures if f["kind"] == "instance-space"]
        groups = {g["data-series"]: [float(v) for v in g["data-rho"].split(",")]
                  for g in space["groups"]}
        for rho in groups[netmaker[0]]:
            self.assertAlmostEqual(rho, -0.444, delta=0.08)

    def test_the_guards_map_marks_the_guard(self):
        if not self.has_arena:
            raise mosbtest.missing("shared/data is absent")
        # arena2's one guard (guards.txt), from the instance's metadata map.guards.
        self.assertEqual(self.text.count('class="guards" data-count="1"'), 1)
        self.assertIn("guards black dots", self.text)

    def test_fronts_are_projections_and_self_contained(self):
        page = parse(self.text)
        fronts = [f for f in page.figures if f["kind"] == "front"]
        texts = [t for f in fronts for t in f["texts"]]
        self.assertIn("projection on c1, c3 of 3 objectives", texts)  # NetMaker-1k_3
        # No network: the only URL is the SVG namespace.
        self.assertEqual(set(re.findall(r"https?://[^\"' )]*", self.text)),
                         {"http://www.w3.org/2000/svg"})
        self.assertNotIn("<link", self.text)
        self.assertNotIn(" src=", self.text)
        self.assertLess(len(self.text), 2_000_000)

    def test_same_inputs_same_bytes_and_thinning(self):
        again = self.path("again.html")
        run("report", *self.report_args, "-o", again)
        self.assertEqual(read(again), read(self.html))
        thin = self.path("thin.html")
        run("report", *self.report_args, "--max-points", "2", "-o", thin)
        self.assertRegex(read(thin, "r"), r">showing [0-9]+ of [0-9]+<")
        # A size limit thins the fronts until the page fits, and refuses a page that cannot.
        limit = len(self.text) * 3 // 4
        small = self.path("small.html")
        run("report", *self.report_args, "--max-size", str(limit), "-o", small)
        self.assertLessEqual(len(read(small)), limit)
        self.assertRegex(read(small, "r"), r">showing [0-9]+ of [0-9]+<")
        r = mosbtest.run("report", *self.report_args, "--max-size", "1000", "-o", small + "2")
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("over the limit of 1000 bytes", r.stderr)
        self.assertFalse(os.path.exists(small + "2"))

    def test_every_figure_alone_as_pdf(self):
        figures = self.path("figures")
        run("report", *self.report_args, "-o", self.path("with-figures.html"), "--figures",
            figures, "--figure-format", "pdf")
        files = sorted(os.listdir(figures))
        self.assertEqual(len(files), len(parse(self.text).figures))
        self.assertEqual(files[0], "01-instance-space.pdf")
        # Named by kind, benchmark and query; cactus and profile per benchmark of two solvers.
        names = [f[3:-4] for f in files]
        for name in ("correlation-grid_2", "cactus-grid_2", "profile-grid_2",
                     "scatter-boa_star-namoa"):
            self.assertIn(name, names)
        self.assertTrue([n for n in names if re.fullmatch(r"front-grid_2-q\d+", n)], names)
        # Three objectives: three projections, each named by its axes.
        self.assertTrue([n for n in names if re.fullmatch(r"front-netmaker_1k_3-q\d+-13", n)], names)
        self.assertNotIn("cactus-netmaker_1k_3", names)  # one solver there: nothing to compare
        self.assertNotIn("cactus", names)  # pooled only on request
        if shutil.which("pdfinfo"):
            info = subprocess.run(["pdfinfo", os.path.join(figures, files[-1])],
                                  capture_output=True, text=True)
            self.assertEqual(info.returncode, 0, info.stderr)
            self.assertIn("Pages:           1", info.stdout)

    def test_runtime_kind_baseline_and_pooled_figures(self):
        html = self.path("choices.html")
        wall = self.path("wall.html")
        run("report", *self.report_args, "--runtime", "wall", "-o", wall)
        self.assertIn("wall-clock runtime (mosb", read(wall, "r"))
        self.assertNotIn("runtime as each solver reported it", read(wall, "r"))
        self.assertIn("runtime as each solver reported it", self.text)  # the default: all report
        run("report", *self.report_args, "--baseline", "namoa", "--pooled", "-o", html)
        page = parse(read(html, "r"))
        titles = [f["texts"][0] for f in page.figures if f["kind"] == "scatter"]
        self.assertEqual(titles, ["Runtime per query: namoa against boa_star"])
        kinds = [f["kind"] for f in page.figures]
        # Grid_2's (and the games map's), and every benchmark's pooled.
        self.assertEqual(kinds.count("cactus"), 3 if self.has_arena else 2)
        self.assertIn("Cactus plot, every benchmark",
                      [f["texts"][0] for f in page.figures if f["kind"] == "cactus"])
        for bad in (["--baseline", "nobody"], ["--runtime", "cpu"]):
            out = self.path("bad.html")
            r = mosbtest.run("report", *self.report_args, *bad, "-o", out)
            self.assertNotEqual(r.returncode, 0)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertFalse(os.path.exists(out))
        r = mosbtest.run("report", *self.report_args, "--baseline", "nobody", "-o", html + "2")
        self.assertIn("the solvers: boa_star, namoa", r.stderr)

    def test_chosen_queries(self):
        chosen = self.path("chosen.html")
        run("report", *self.report_args, "--queries", "1,99", "-o", chosen)
        page = parse(read(chosen, "r"))
        titles = {t for f in page.figures if f["kind"] == "front" for t in f["texts"][:1]}
        self.assertIn("Grid_2, query 1", titles)  # no path: it would be clipped
        self.assertFalse(any("query 0" in t or "query 99" in t or "/" in t for t in titles),
                         titles)
        self.assertIn("Query 99: not a solved query with a front in", read(chosen, "r"))
        r = mosbtest.run("report", *self.report_args, "--queries", "1,x", "-o", chosen + "2")
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("--queries: 'x' is not a query number", r.stderr)

    def test_every_latex_table_compiles(self):
        compile_latex(self, self.path("latex"))

    def test_latex_and_csv_tables(self):
        tex = read(self.path("latex/suite.tex"), "r")
        self.assertIn("\\toprule", tex)
        self.assertIn("Grid\\_2", tex)
        self.assertIn("\\toprule", read(self.path("latex/comparison.tex"), "r"))
        csv = read(self.path("csv/suite.csv"), "r")
        self.assertTrue(csv.startswith("family,benchmark,instances,vertices,arcs"), csv[:80])
        self.assertIn("covered@0.05", read(self.path("csv/coverage.csv"), "r"))

    def test_bad_inputs_one_line_no_output(self):
        out = self.path("bad.html")
        damaged = self.path("damaged.mosb")
        data = bytearray(read(self.instances[0]))
        data[len(data) // 2] ^= 0xFF
        with open(damaged, "wb") as f:
            f.write(data)
        other = self.path("other.mosb")
        run("generate", "grid", "--width", "5", "--height", "5", "-o", other)
        damaged_sol = self.path("damaged.sol")
        data = bytearray(read(self.namoa[0]))
        data[-1] ^= 0xFF
        with open(damaged_sol, "wb") as f:
            f.write(data)
        for args, message in (
                ([damaged], "damaged.mosb"),
                ([self.instances[0], "--solutions", damaged_sol], "damaged.sol: header checksum mismatch"),
                ([other, "--solutions", self.namoa[0]], "none of the report's instances"),
                ([self.instances[0], "--solutions", self.namoa[0], self.namoa[0]],
                 "a second file of solver")):
            r = mosbtest.run("report", *args, "-o", out)
            self.assertEqual(r.returncode, 1, r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertIn(message, r.stderr)
            self.assertFalse(os.path.exists(out))


class HostileInputTest(mosbtest.CliTest):
    """Issue 36: names, metadata and values that pass every check of the files they are in, and
    the destinations of the outputs. Needs the solution-file helper only (no browser, no example
    solver): the files are written by SolutionWriter."""

    MAP = "type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n"  # 11 vertices

    def setUp(self):
        super().setUp()
        if not os.path.exists(mosbtest.WRITE_SOLUTION):
            raise mosbtest.missing("WRITE_SOLUTION (mosb_test_write_solution) is not built")
        self.grid = self.path("grid.mosb")
        run("generate", "grid", "--width", "3", "--height", "3", "-o", self.grid)

    def solution(self, name, solver, instance=None, spec="0 solved 1,2 2,1 t=0.5\n"):
        env = dict(os.environ, MOSB_TEST_SOLVER_NAME=solver)
        return mosbtest.write_solution(self.path(name), instance or self.grid, "Grid_2", spec,
                                       "0", env=env)

    def report(self, *args, **options):
        return self.mosb("report", *args, timeout=300, **options)

    def test_front_size_against_epsilon_and_spread(self):
        """An experiment's ε sweep (files named NAME-epsE, each of its ε) against the exact
        reference: the median front size per ε and its reduction, as a figure and a table; and
        the reference fronts' spread per objective, a one-vector front left out."""
        def write(name, solver, spec, epsilon):
            env = dict(os.environ, MOSB_TEST_SOLVER_NAME=solver)
            return mosbtest.write_solution(self.path(name), self.grid, "Grid_2", spec, epsilon,
                                           env=env)
        ref = write("ref.sol", "namoa", "0 solved 10,40 20,20 40,10\n", "0")
        sweep = [write("a1.sol", "apx-eps0.05", "0 solved 10,40 40,10\n", "0.05"),
                 write("a2.sol", "apx-eps0.1", "0 solved 20,20\n", "0.1")]
        out, html, figures = self.path("csv"), self.path("r.html"), self.path("figures")
        self.ok("report", self.grid, "--solutions", *reversed(sweep), "--reference", ref, "-o",
                html, "--csv", out, "--figures", figures)
        rows = [(r["sweep"], r["solver"], r["epsilon"], r["queries"], r["front_median"],
                 r["reduction_percent"][:5]) for r in csv_rows(os.path.join(out, "epsilon.csv"))]
        self.assertEqual(rows, [("apx", "reference", "0", "1", "3", ""),
                                ("apx", "apx-eps0.05", "0.05", "1", "2", "33.33"),
                                ("apx", "apx-eps0.1", "0.1", "1", "1", "66.66")])
        page = read(html, "r")
        self.assertIn('<section id="approximation">', page)
        self.assertIn("apx: the median front size at ε = 0.1 is 66.7% below the exact one", page)
        self.assertTrue([f for f in os.listdir(figures) if f.endswith("-epsilon-grid_2.svg")])
        # The front figure draws the sweep's fronts over the reference, each named with its size,
        # in the experiment's order (here the order given).
        (front,) = [f for f in os.listdir(figures) if f.endswith("-front-grid_2-q0.svg")]
        svg = read(os.path.join(figures, front), "r")
        self.assertLess(svg.index(">apx-eps0.1 (1 vector)<"), svg.index(">apx-eps0.05 (2 vectors)<"))
        self.assertEqual(svg.count('stroke="#009E73"'), 1 + 1)  # apx-eps0.1's square and swatch
        self.assertEqual(svg.count('stroke="#CC79A7"'), 2 + 1)  # apx-eps0.05's two and swatch
        (caption,) = [c for c in re.findall(r"<figcaption>(Front of [^<]*)</figcaption>", page)]
        self.assertTrue(caption.endswith("(3 vectors, apx-eps0.1 1, apx-eps0.05 2)"), caption)
        spread = [(r["objective"], r["queries"], r["spread_mean"])
                  for r in csv_rows(os.path.join(out, "spread.csv"))]
        self.assertEqual(spread, [("c1", "1", "4"), ("c2", "1", "4")])
        # Exact solvers only: no approximation section. A one-vector front has no spread.
        one = write("one.sol", "namoa", "0 solved 5,5\n", "0")
        self.ok("report", self.grid, "--reference", one, "-o", html, "--csv", out + "2")
        self.assertNotIn('id="approximation"', read(html, "r"))
        self.assertEqual([(r["queries"], r["spread_mean"])
                          for r in csv_rows(os.path.join(out + "2", "spread.csv"))],
                         [("0", ""), ("0", "")])

    def test_benchmarks_are_named_as_the_suite_groups_them(self):
        """A suite view (NAME_d) groups its instances; a Moving AI map's view `length` is the map's
        own benchmark, named by its `benchmark` metadata; each section lists its instances."""
        maps = []
        for name in ("DarkContinent", "Arena"):
            self.write(name + ".map", self.MAP)
            maps.append(self.path(name + ".mosb"))
            run("convert", "movingai", "--map", self.path(name + ".map"), "-o", maps[-1])
        twin = self.path("grid2.mosb")
        run("generate", "grid", "--width", "4", "--height", "3", "-o", twin)
        out, html = self.path("csv"), self.path("r.html")
        self.ok("report", self.grid, twin, *maps, "-o", html, "--csv", out)
        suite = list(csv_rows(os.path.join(out, "suite.csv")))
        self.assertEqual([(row["benchmark"], row["instances"]) for row in suite],
                         [("Grid_2", "2"), ("Grid_3", "2"), ("DarkContinent", "1"),
                          ("Arena", "1")])
        page = read(html, "r")
        self.assertNotIn(">length<", page)
        self.assertIn("2 instances (Grid-3x3, Grid-4x3)", page)
        self.assertIn("1 instance (DarkContinent)", page)

    def test_a_map_that_does_not_fit_is_left_out_and_said(self):
        self.write("tiny.map", self.MAP)
        self.write("guards.txt", "3 0 1\n")
        tiny = self.path("tiny.mosb")
        run("convert", "guards", "--map", self.path("tiny.map"), "--guards",
            self.path("guards.txt"), "-o", tiny)
        run("queries", "generate", tiny, "--set", "q", "--count", "2", "--in-place")
        for width, height, why in (("-5", "3", "map.width '-5' is not a whole number"),
                                   ("4294967295", "4294967295", "more than the 4294967294"),
                                   ("100000", "100000", "more than the 4294967294")):
            with self.subTest(width=width):
                data = bytearray(read(tiny))
                mosbtest.set_metadata(data, **{"map.width": width, "map.height": height})
                bad = self.write("bad.mosb", bytes(data))
                html = self.path("r.html")
                self.ok("report", bad, "-o", html, timeout=300)
                page = read(html, "r")
                self.assertIn("No map: %s: metadata" % bad, page)
                self.assertIn(why.replace("'", "&apos;"), page)
                kinds = [f["kind"] for f in parse(page).figures]
                self.assertNotIn("map", kinds)
                self.assertIn("degrees", kinds)  # the rest of the page is drawn

    def test_fronts_and_runtimes_up_to_the_largest_double(self):
        data = bytearray(read(self.grid))
        for column in ("c1", "c2"):
            costs = mosbtest.values(data, column, "B")
            mosbtest.relocate_as_float(data, column, [float(c) for c in costs], mosbtest.F64)
        f64 = self.write("f64.mosb", bytes(data))
        largest = "1.7976931348623157e308"
        spec = "0 solved %s,3 2,%s t=%s\n" % (largest, largest, largest)
        a = self.solution("a.sol", "a", f64, spec)
        b = self.solution("b.sol", "b", f64, "0 solved %s,3 2,%s t=1e-300\n" % (largest, largest))
        html = self.path("r.html")
        self.ok("report", f64, "--solutions", a, b, "--reference", a, "-o", html, timeout=300)
        page = parse(read(html, "r"))
        for figure in page.figures:
            self.assertFalse([t for t in figure["texts"] if t in ("inf", "nan", "-nan")],
                             figure["kind"])
        self.assertIn("front", [f["kind"] for f in page.figures])

    def test_runtimes_of_zero_are_counted_not_drawn_on_log_axes(self):
        """A*pex reports whole milliseconds: a fast query's runtime is 0, which a log axis cannot
        show; the cactus legend and the scatter's note count it instead."""
        files = [self.solution("z%d.sol" % k, n, spec="0 solved 1,2 2,1 t=0\n")
                 for k, n in enumerate(["a", "b"])]
        html = self.path("zero.html")
        self.ok("report", self.grid, "--solutions", *files, "-o", html)
        page = parse(read(html, "r"))
        cactus = [f for f in page.figures if f["kind"] == "cactus"]
        self.assertIn("a (1 solved, 1 in 0 s not drawn)", cactus[0]["texts"])
        (scatter,) = [f for f in page.figures if f["kind"] == "scatter"]
        self.assertIn("1 query with a runtime of 0 s, not drawn", scatter["texts"])

    def test_latex_names_escaped_headings_included(self):
        names = ["\\end{tabular}\\input{/etc/passwd}", "$ _ # % & ~ ^ { }"]
        files = [self.solution("s%d.sol" % k, n) for k, n in enumerate(names)]
        tex = self.path("tex")
        self.ok("report", self.grid, "--solutions", *files, "-o", self.path("r.html"), "--latex",
                tex)
        comparison = read(os.path.join(tex, "comparison.tex"), "r")
        body = comparison.splitlines()
        self.assertIn("& \\textbackslash{}end\\{tabular\\}\\textbackslash{}input\\{/etc/passwd\\} &",
                      body[5])
        self.assertIn("& \\$ \\_ \\# \\% \\& \\textasciitilde{} \\textasciicircum{} \\{ \\} &",
                      body[6])
        for text in (read(os.path.join(tex, f), "r") for f in os.listdir(tex)):
            self.assertNotIn("\\input", text)
            self.assertEqual(text.count("\\end{tabular}"), 1)
        compile_latex(self, tex)
        # Beyond ASCII: a profile's default name, Greek, dashes, a Latin-1 letter.
        names = ["A*pex RANDOM ε=0.05", "αβ–ω × 2 … Müller"]
        files = [self.solution("u%d.sol" % k, n) for k, n in enumerate(names)]
        self.ok("report", self.grid, "--solutions", *files, "-o", self.path("u.html"), "--latex",
                self.path("utex"))
        body = read(os.path.join(self.path("utex"), "comparison.tex"), "r")
        self.assertIn("A*pex RANDOM \\ensuremath{\\varepsilon}=0.05", body)
        self.assertIn("\\ensuremath{\\alpha}\\ensuremath{\\beta}--\\ensuremath{\\omega} "
                      "\\ensuremath{\\times} 2 \\ldots{} Müller", body)
        compile_latex(self, self.path("utex"))

    def test_comparison_by_benchmark_groups_each_solvers_columns_under_its_name(self):
        """The paper's appendix layout: a row per benchmark, each solver's four columns under a
        \\multicolumn head with a \\cmidrule; a solver without a file for a benchmark has none
        of its numbers there. The table still compiles with hostile names."""
        a2 = self.solution("a2.sol", "a")
        b2 = self.solution("b2.sol", "b $ ε=0.05", spec="0 timeout\n")
        env = dict(os.environ, MOSB_TEST_SOLVER_NAME="a")
        a3 = mosbtest.write_solution(self.path("a3.sol"), self.grid, "Grid_3",
                                     "0 solved 1,2,3 t=0.25\n", "0", env=env)
        tex, csv, html = self.path("tex"), self.path("csv"), self.path("r.html")
        self.ok("report", self.grid, "--solutions", a2, b2, a3, "-o", html, "--latex", tex,
                "--csv", csv, "--comparison-by-benchmark")
        body = read(os.path.join(tex, "comparison.tex"), "r").splitlines()
        self.assertEqual(body[3], " &  &  &  & \\multicolumn{4}{c}{a} & "
                         "\\multicolumn{4}{c}{b \\$ \\ensuremath{\\varepsilon}=0.05} \\\\")
        self.assertEqual(body[4], "\\cmidrule(lr){5-8}\\cmidrule(lr){9-12}")
        self.assertTrue(body[5].startswith("Family & Benchmark & Queries & Common & Timeout"))
        rows = [line for line in body if line.startswith("synthetic &")]
        self.assertEqual(len(rows), 2, body)
        self.assertIn("& Grid\\_2 & 1 & 0 & 0 & 0 & -- & -- & 1 & 0 & -- & -- \\\\", rows[0])
        self.assertIn("& Grid\\_3 & 1 & 1 & 0 & 0 & 0.25 & 0.25 & -- & -- & -- & -- \\\\",
                      rows[1])
        compile_latex(self, tex)
        lines = read(os.path.join(csv, "comparison.csv"), "r").splitlines()
        self.assertEqual(lines[0].split(",")[:6],
                         ["family", "benchmark", "queries", "common", "timeout@a",
                          "memory_limit@a"])
        self.assertEqual(len(lines), 3)
        page = read(html, "r")
        self.assertIn('<th scope="colgroup" colspan="4">b $ ε=0.05</th>', page)
        self.assertIn(">b $ ε=0.05: median runtime [s]</th>", page)
        # Without the option: a row per benchmark and solver, no group heads.
        self.ok("report", self.grid, "--solutions", a2, b2, a3, "-o", self.path("long.html"),
                "--latex", self.path("long"))
        long = read(os.path.join(self.path("long"), "comparison.tex"), "r")
        self.assertNotIn("multicolumn", long)
        self.assertEqual(long.count("\\\\\n"), 1 + 3)

    def test_csv_names_a_spreadsheet_would_run_are_quoted_after_a_quote(self):
        names = ["=HYPERLINK(\"http://x\")", "+1", "-1", "@SUM(A1)"]
        files = [self.solution("s%d.sol" % k, n) for k, n in enumerate(names)]
        out = self.path("csv")
        self.ok("report", self.grid, "--solutions", *files, "--reference", files[0], "-o",
                self.path("r.html"), "--csv", out)
        coverage = read(os.path.join(out, "coverage.csv"), "r").splitlines()
        self.assertEqual([line.split(",")[0] for line in coverage[2:]],
                         ['"\'+1"', '"\'-1"', '"\'@SUM(A1)"'])
        self.assertTrue(coverage[1].startswith('"\'=HYPERLINK(""http://x"")",'), coverage[1])
        suite = read(os.path.join(out, "suite.csv"), "r")
        self.assertIn('"reference (=HYPERLINK(""http://x""))"', suite)  # no formula: as it is

    def test_names_differing_by_punctuation_or_case_get_rows_and_figures_of_their_own(self):
        names = ["a b", "a_b", "A-B", "a b 2"]
        files = [self.solution("s%d.sol" % k, n) for k, n in enumerate(names)]
        out, html, figures = self.path("csv"), self.path("r.html"), self.path("figures")
        self.ok("report", self.grid, "--solutions", *files, "-o", html, "--csv", out,
                "--figures", figures)
        rows = read(os.path.join(out, "comparison.csv"), "r").splitlines()[1:]
        self.assertEqual([r.split(",")[2] for r in rows], names)
        scatters = sorted(f[3:] for f in os.listdir(figures) if f[3:].startswith("scatter-"))
        self.assertEqual(len(scatters), len(names) - 1)
        self.assertEqual(len(set(scatters)), len(scatters))
        page = read(html, "r")
        for name in names:
            self.assertIn(">%s</td>" % name, page)  # names shown as given

    def test_an_instance_given_twice_is_counted_once(self):
        import shutil as copier
        twin = self.path("twin.mosb")
        copier.copy(self.grid, twin)
        sol = self.solution("s.sol", "s")
        html, out = self.path("r.html"), self.path("csv")
        r = self.ok("report", self.grid, twin, "--solutions", sol, "-o", html, "--csv", out)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("warning: %s is the same instance as %s" % (twin, self.grid), r.stderr)
        self.assertIn("counted once", r.stderr)
        suite = list(csv_rows(os.path.join(out, "suite.csv")))
        self.assertEqual([(row["benchmark"], row["instances"]) for row in suite],
                         [("Grid_2", "1"), ("Grid_3", "1")])
        instance_space = list(csv_rows(os.path.join(out, "instance-space.csv")))
        self.assertEqual(instance_space[0]["pairs"], "1")  # Grid_2's one pair, not two
        self.assertIn("1 instance, 2 benchmarks", read(html, "r"))
        self.assertIn("is the same instance as", read(html, "r"))

    def test_every_destination_checked_first_and_all_or_nothing(self):
        sol = self.solution("s.sol", "s")
        args = [self.grid, "--solutions", sol]
        afile = self.write("afile", "not a directory\n")
        for outputs, message in (
                (["-o", "missing/r.html", "--csv", "t", "--latex", "t", "--figures", "f"],
                 "missing/r.html: the directory missing does not exist"),
                (["-o", "r.html", "--csv", "afile"], "afile: not a directory"),
                (["-o", "r.html", "--figures", "afile/f"], "afile/f: not a directory"),
                (["-o", "t", "--csv", "t"], "t: is a directory"),
                # Found only while writing: the tables were written to temporaries, the
                # directory t made; both are gone again.
                (["-o", "r.html", "--csv", "t", "--figures", "/proc/self"], "/proc/self/01-"),
                (["-o", "r.html", "--csv", "t", "--figures", "/proc/mosb-report-test"],
                 "/proc/mosb-report-test: cannot make the directory")):
            with self.subTest(outputs=outputs):
                if outputs[1] == "t":
                    os.mkdir(self.path("t"))
                r = self.report(*args, *outputs)
                self.assert_one_line_error(r, message)
                self.assertEqual(sorted(os.listdir(self.dir)),
                                 sorted(["grid.mosb", "s.sol", "afile"] +
                                        (["t"] if outputs[1] == "t" else [])))
                if outputs[1] == "t":
                    os.rmdir(self.path("t"))
        self.assertEqual(read(afile, "r"), "not a directory\n")


def csv_rows(path):
    import csv
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


if __name__ == "__main__":
    mosbtest.main()
