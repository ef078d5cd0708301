#!/usr/bin/python3
"""End-to-end tests of `mosb suite build DIR --raw RAWDIR` (spec/MANIFEST.md, "Raw-source
benchmarks"): each built file is byte-identical to its `mosb convert ...` command, listed in the
MANIFEST with its raw inputs, checkable with `verify --sources`; absent inputs are skipped, a bad
one fails the run without touching the MANIFEST.

Hand-made inputs under the download names cover GER_10, DIMACS-FLA and Panda-RRG; the real files of
shared/data (the NY head, the NY query file, random512-20-1.map) cover DIMACS-NY and GUARDS, and
those tests are skipped visibly when ../shared is absent.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_raw_suite.py
"""

import gzip
import json
import os
import shutil

import mosbtest
from mosbtest import DATA, REPOSITORY, CliTest, read, run, setUpModule  # noqa: F401

# FMI multi-cost layout (spec/families/ger.md): 4 nodes, 5 edges of 10 costs.
FMI = """# Id : 0
# Type : maxspeed

4
5
0 100 48.1 9.1 300
1 101 48.2 9.2 310
2 102 48.3 9.3 305
3 103 48.4 9.4 290
0 1 1 2 3 4 5 6 7 8 9 10
1 2 2 3 4 5 6 7 8 9 10 11
2 3 3 4 5 6 7 8 9 10 11 12
3 0 4 5 6 7 8 9 10 11 12 13
1 0 5 6 7 8 9 10 11 12 13 14
"""

FLA_D = "c distance\np sp 4 5\na 1 2 5\na 2 3 7\na 3 1 2\na 3 4 1\na 4 1 9\n"
FLA_T = "c time\np sp 4 5\na 1 2 50\na 2 3 60\na 3 1 25\na 3 4 14\na 4 1 80\n"
FLA_CO = "p aux sp co 4\nv 1 -80100000 25100000\nv 2 -80200000 25200000\n" \
    "v 3 -80300000 25300000\nv 4 -80400000 25400000\n"


def panda_graphml():
    # 3 configurations of a 7-DoF arm, undirected edges with the aggregate and 7 per-link clearances.
    keys = "".join(f'  <key id="c{i}" for="edge" attr.name="clearance_{i}" attr.type="double"/>\n'
                   for i in range(7))
    def edge(eid, s, t, base):
        data = "".join(f'<data key="c{i}">{base + 0.01 * i:.2f}</data>' for i in range(7))
        return (f'    <edge id="{eid}" source="{s}" target="{t}"><data key="agg">{base:.2f}</data>'
                f"{data}</edge>\n")
    return ('<?xml version="1.0"?>\n<graphml xmlns="http://graphml.graphdrawing.org/xmlns">\n'
            '  <key id="q" for="node" attr.name="coords" attr.type="string"/>\n'
            '  <key id="agg" for="edge" attr.name="clearance" attr.type="double"/>\n' + keys +
            '  <graph edgedefault="undirected">\n'
            '    <node id="a"><data key="q">0,0,0,0,0,0,0</data></node>\n'
            '    <node id="b"><data key="q">0.1,0.2,0,0,0,0,0.3</data></node>\n'
            '    <node id="c"><data key="q">0.4,0,0.1,0,0.2,0,0</data></node>\n' +
            edge("e0", "a", "b", 0.02) + edge("e1", "b", "c", 0.05) +
            "  </graph>\n</graphml>\n")


class RawSuite(CliTest):
    def setUp(self):
        super().setUp()
        self.raw = self.path("raw")
        os.mkdir(self.raw)

    def write_raw(self, name, text, compress=False):
        """`name` in the raw directory, gzip-compressed with `compress`."""
        path = os.path.join(self.raw, name)
        data = text.encode()
        with open(path, "wb") as f:
            f.write(gzip.compress(data, mtime=0) if compress else data)
        return path

    def hand_made(self):
        self.write_raw("GER_10.txt", FMI)
        self.write_raw("USA-road-d.FLA.gr.gz", FLA_D, compress=True)
        self.write_raw("USA-road-t.FLA.gr", FLA_T)  # plain twin of the .gz download name
        self.write_raw("USA-road-d.FLA.co.gz", FLA_CO, compress=True)
        self.write_raw("Panda-RRG_2.graphml", panda_graphml())
        self.write_raw("Panda-RRG_8.graphml", panda_graphml())

    def build(self, out, *extra):
        return run("suite", "build", self.path(out), "--raw", self.raw, "--no-generated", *extra)

    def converted(self, name, *args):
        out = self.path("convert", name + ".mosb")
        os.makedirs(self.path("convert"), exist_ok=True)
        self.ok("convert", *args, "-o", out)
        return out

    def r(self, name):
        return os.path.join(self.raw, name)

    def manifest(self, out):
        lines = read(self.path(out, "MANIFEST")).decode().splitlines()
        return {rec["file"]: rec for rec in map(json.loads, lines[1:])}

    def test_hand_made_recipes_match_their_convert_commands(self):
        self.hand_made()
        r = self.build("plain", "--no-pack")
        self.assertEqual(r.returncode, 0, r)
        lines = r.stdout.splitlines()
        for name in ("DIMACS-FLA", "GER_10", "Panda-RRG_2", "Panda-RRG_8"):
            self.assertIn(name + ": built", lines)
        # Each skipped recipe names its missing inputs and where they come from.
        self.assertIn("DIMACS-NY: skipped: missing USA-road-d.NY.gr.gz, USA-road-t.NY.gr.gz, "
                      "USA-road-d.NY.co.gz (from: the .gr and .co files: the 9th DIMACS "
                      "Implementation Challenge (http://www.diag.uniroma1.it/challenge9/"
                      "download.shtml); NY.elev: no public download (spec/families/road.md section "
                      "1); USA-road-NY-queries: github.com/CRL-Technion/path-pair-graph-search)",
                      lines)
        guards = next(x for x in lines if x.startswith("Games-GUARDS-random512-20-1: "))
        self.assertTrue(guards.startswith("Games-GUARDS-random512-20-1: skipped: missing "
                                          "random512-20-1.map, random512-20-1.guards (from: "),
                        guards)
        # A selection that matches only recipes without their inputs says which, exit 1.
        r = self.mosb("suite", "build", self.path("none"), "--raw", self.path("raw"),
                      "--no-generated", "--benchmark", "Games-*")
        self.assert_one_line_error(r, "--benchmark 'Games-*' matches no benchmark that can be "
                                   "built: Games-GUARDS-random512-20-1: skipped: missing "
                                   "random512-20-1.map, random512-20-1.guards (from: ")
        self.assertFalse(os.path.exists(self.path("none", "MANIFEST")))
        expected = {
            "GER_10": self.converted("GER_10", "fmi", self.r("GER_10.txt"), "--costs", "10",
                                     "--name", "GER_10"),
            "DIMACS-FLA": self.converted(
                "DIMACS-FLA", "dimacs", "--gr", self.r("USA-road-d.FLA.gr.gz"), "--gr",
                self.r("USA-road-t.FLA.gr"), "--objective", "distance", "--objective", "time",
                "--co", self.r("USA-road-d.FLA.co.gz"), "--view", "DIMACS-FLA_2=distance,time",
                "--name", "DIMACS-FLA"),
            "Panda-RRG_2": self.converted("Panda-RRG_2", "roadmap", "--graphml",
                                          self.r("Panda-RRG_2.graphml"), "--clearance",
                                          "aggregate", "--name", "Panda-RRG_2"),
            "Panda-RRG_8": self.converted("Panda-RRG_8", "roadmap", "--graphml",
                                          self.r("Panda-RRG_8.graphml"), "--clearance",
                                          "per-link", "--name", "Panda-RRG_8"),
        }
        records = self.manifest("plain")
        self.assertEqual(sorted(records), sorted(n + ".mosb" for n in expected))
        for name, reference in expected.items():
            with self.subTest(name=name):
                built = self.path("plain", name + ".mosb")
                self.assertEqual(read(built), read(reference))
                self.ok("verify", "--sources", self.raw, built)
        self.assertEqual([s["name"] for s in records["DIMACS-FLA.mosb"]["sources"]],
                         ["USA-road-d.FLA.gr.gz", "USA-road-t.FLA.gr", "USA-road-d.FLA.co.gz"])
        self.assertEqual(records["DIMACS-FLA.mosb"]["views"], ["DIMACS-FLA_2"])
        self.assertEqual(records["Panda-RRG_8.mosb"]["views"], ["Panda-RRG_8"])

        # Packed (the default): unpacking gives the convert command's bytes again.
        r = self.build("packed")
        self.assertEqual(r.returncode, 0, r)
        packed = self.manifest("packed")
        for name, reference in expected.items():
            with self.subTest(packed=name):
                self.assertTrue(packed[name + ".mosb"]["packed"])
                self.assertEqual(packed[name + ".mosb"]["digest"],
                                 records[name + ".mosb"]["digest"])
                unpacked = self.path(name + ".unpacked")
                self.ok("unpack", self.path("packed", name + ".mosb"), "-o", unpacked)
                self.assertEqual(read(unpacked), read(reference))
                self.ok("verify", "--sources", self.raw, self.path("packed", name + ".mosb"))

        # Deterministic: a second run gives the same MANIFEST bytes.
        first = read(self.path("packed", "MANIFEST"))
        self.assertEqual(self.build("packed").returncode, 0)
        self.assertEqual(read(self.path("packed", "MANIFEST")), first)

    def test_json_report(self):
        def suite_source(name):  # the recipe's `source` in spec/suite.json
            with open(os.path.join(REPOSITORY, "spec", "suite.json"), encoding="utf-8") as f:
                return next(r["source"] for r in json.load(f)["raw"] if r["name"] == name)
        self.write_raw("GER_10.txt", FMI)
        r = self.build("out", "--json")
        self.assertEqual(r.returncode, 0, r)
        report = json.loads(r.stdout)
        raw = {s["name"]: s for s in report["raw"]}
        self.assertEqual(raw["GER_10"], {"name": "GER_10", "status": "built", "missing": [],
                                         "source": suite_source("GER_10")})
        self.assertEqual(raw["Panda-RRG_2"]["status"], "skipped")
        self.assertEqual(raw["Panda-RRG_2"]["missing"], ["Panda-RRG_2.graphml"])
        self.assertEqual([i["name"] for i in report["instances"]], ["GER_10"])

    def test_damaged_input_fails_located_and_keeps_the_manifest(self):
        self.hand_made()
        self.assertEqual(self.build("out").returncode, 0)
        before = read(self.path("out", "MANIFEST"))
        self.write_raw("GER_10.txt", FMI.replace("2 3 3 4 5", "2 3 x 4 5"))
        r = self.build("out")
        self.assertEqual(r.returncode, 1, r)
        self.assertRegex(r.stderr, r"^mosb: \S*GER_10\.txt:12:5: ")
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertEqual(read(self.path("out", "MANIFEST")), before)
        # Nor a file it added: a new directory stays without instances, and `store verify` finds no
        # unlisted file in the old one.
        # One thread: DIMACS-FLA, before GER_10 in the description, is built before the failure.
        r = self.build("fresh", "--threads", "1")
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual([f for f in os.listdir(self.path("fresh")) if f.endswith(".mosb")], [])
        first = sorted(f for f in os.listdir(self.path("out")) if f.endswith(".mosb"))[0]
        self.assertTrue(first.startswith("DIMACS-FLA"), first)
        os.remove(self.path("out", first))
        self.assertEqual(self.build("out", "--threads", "1").returncode, 1)
        self.assertFalse(os.path.exists(self.path("out", first)))

    def test_queries_complete_the_views_meant_for_them(self):
        # convert dimacs keeps a view's intended set in source.param.view.NAME while the set is
        # missing (road.md §2); importing or generating that set adds view.NAME.queries.
        self.write_raw("g.gr", FLA_D)
        for command in (("import", self.write_raw("q.txt", "1 2\n3 4\n")),
                        ("generate", "--count", "3")):
            with self.subTest(command=command[0]):
                out = self.path(command[0] + ".mosb")
                self.ok("convert", "dimacs", "--gr", self.r("g.gr"), "--view", "A=c1",
                        "--view", "B=c1@other", "-o", out)
                self.ok("queries", *command[:1], out, "--set", "default", "--in-place",
                        *command[1:])
                meta = json.loads(self.ok("inspect", "--json", out).stdout)["metadata"]
                self.assertEqual(meta.get("view.A.queries"), "default")
                self.assertNotIn("view.B.queries", meta)
                self.ok("verify", out)

    def test_usage(self):
        r = run("suite", "build", self.path("out"), "--no-generated")
        self.assertEqual(r.returncode, 2, r)
        self.assertIn("--no-generated needs --raw", r.stderr)
        r = run("suite", "build", self.path("out"), "--raw", self.path("nowhere"), "--no-generated")
        self.assertEqual(r.returncode, 1, r)
        self.assertIn("nowhere: the raw-source directory does not exist", r.stderr)
        self.assertFalse(os.path.exists(self.path("out", "MANIFEST")))

    def test_real_files(self):
        head = os.path.join(DATA, "dimacs-small", "USA-road-d.NY.head.gr")
        queries = os.path.join(DATA, "dimacs-queries", "USA-road-NY-queries")
        grid_map = os.path.join(DATA, "movingai", "random512-20-1.map")
        self.skip_unless_present(head, queries, grid_map)
        # The head of the real NY distance file, its arc count made to match its 92 arcs; the same
        # arcs stand for the time file (as the .gz download name).
        text = read(head).decode().replace("p sp 264346 733846", "p sp 264346 92")
        self.write_raw("USA-road-d.NY.gr", text)
        self.write_raw("USA-road-t.NY.gr.gz", text, compress=True)
        n = 264346
        self.write_raw("USA-road-d.NY.co.gz", f"p aux sp co {n}\n" + "".join(
            f"v {i} {-73000000 - i} {40000000 + i % 977}\n" for i in range(1, n + 1)), True)
        self.write_raw("NY.elev", f"p aux sp elev {n}\n" + "".join(
            f"v {i} {i * 7919 % 1000}\n" for i in range(1, n + 1)))
        shutil.copy(queries, self.raw)
        shutil.copy(grid_map, self.raw)
        self.write_raw("random512-20-1.guards", "10 10 5\n100 200\n")
        r = self.build("out", "--no-pack")
        self.assertEqual(r.returncode, 0, r)
        self.assertIn("DIMACS-NY: built", r.stdout.splitlines())
        self.assertIn("Games-GUARDS-random512-20-1: built", r.stdout.splitlines())

        ny = self.converted(
            "DIMACS-NY", "dimacs", "--gr", self.r("USA-road-d.NY.gr"), "--gr",
            self.r("USA-road-t.NY.gr.gz"), "--objective", "distance", "--objective", "time", "--co",
            self.r("USA-road-d.NY.co.gz"), "--elevation", self.r("NY.elev"), "--derive",
            "avg-outdegree", "--derive", "hop", "--view", "DIMACS-NY_2=distance,time", "--view",
            "DIMACS-Extended-NY_3=distance,time,elevation", "--view",
            "DIMACS-Extended-NY_4=distance,time,elevation,avg_outdegree", "--view",
            "DIMACS-Extended-NY_5=distance,time,elevation,avg_outdegree,hop", "--name", "DIMACS-NY")
        self.ok("queries", "import", ny, "--set", "default", "--in-place",
                self.r("USA-road-NY-queries"))
        guards = self.converted("Games-GUARDS-random512-20-1", "guards", "--map",
                                self.r("random512-20-1.map"), "--guards",
                                self.r("random512-20-1.guards"))
        self.assertEqual(read(self.path("out", "DIMACS-NY.mosb")), read(ny))
        self.assertEqual(read(self.path("out", "Games-GUARDS-random512-20-1.mosb")), read(guards))
        records = self.manifest("out")
        self.assertEqual(records["DIMACS-NY.mosb"]["query_sets"], ["default"])
        self.assertEqual(records["DIMACS-NY.mosb"]["views"],
                         ["DIMACS-Extended-NY_3", "DIMACS-Extended-NY_4", "DIMACS-Extended-NY_5",
                          "DIMACS-NY_2"])
        self.assertEqual([s["name"] for s in records["DIMACS-NY.mosb"]["sources"]],
                         ["USA-road-d.NY.gr", "USA-road-t.NY.gr.gz", "USA-road-d.NY.co.gz",
                          "NY.elev"])
        for name in records:
            self.ok("verify", "--sources", self.raw, self.path("out", name))
        r = self.ok("store", "instance", self.path("out"), "DIMACS-Extended-NY_4", "--json")
        self.assertEqual(json.loads(r.stdout)["file"], "DIMACS-NY.mosb")
        self.assertEqual(json.loads(r.stdout)["query_set"], "default")

        # Without the elevation file: DIMACS-NY_2 alone, still built.
        os.remove(self.r("NY.elev"))
        r = self.build("noelev", "--no-pack")
        self.assertEqual(r.returncode, 0, r)
        self.assertEqual(self.manifest("noelev")["DIMACS-NY.mosb"]["views"], ["DIMACS-NY_2"])


if __name__ == "__main__":
    mosbtest.main()
