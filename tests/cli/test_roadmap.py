#!/usr/bin/python3
"""End-to-end tests of `mosb convert roadmap` (spec/families/robots.md).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_roadmap.py

Counts on the real fixtures are checked independently of mosb: lines of the .gr files, and the
<edge> elements and directedness of the GraphML file read with xml.etree.
"""

import json
import os
import re
import shlex
import unittest
import xml.etree.ElementTree as ET

import mosbtest
from mosbtest import DATA, CliTest, header, read, run, setUpModule  # noqa: F401

POINT_ROBOT = os.path.join(DATA, "roadmap-point-robot", "exp_4_obs")
GRAPHML = os.path.join(DATA, "roadmap-graphml", "roadmap.xml")
README = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "README.md")
NS = "{http://graphml.graphdrawing.org/xmlns}"


def inspect(path):
    result = run("inspect", path, "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def header_counts(path):
    """n, m and d from the file header (spec/FORMAT.md §2), independent of `inspect`."""
    h = header(read(path))
    return h["vertex_count"], h["arc_count"], h["objective_count"]


class HandMade(CliTest):
    def graphml(self, bc_link0="0.5"):
        # a=(0,0), b=(3,4), c=(3,0); undirected a-b (length 5) and b-c (length 4), 2 links.
        return self.write("r.graphml", f"""<?xml version="1.0"?>
<graphml xmlns="http://graphml.graphdrawing.org/xmlns">
  <key id="q" for="node" attr.name="coords" attr.type="string"/>
  <key id="d0" for="edge" attr.name="clearance_0" attr.type="double"/>
  <key id="d1" for="edge" attr.name="clearance_1" attr.type="double"/>
  <graph edgedefault="undirected">
    <node id="a"><data key="q">0,0</data></node>
    <node id="b"><data key="q">3,4</data></node>
    <node id="c"><data key="q">3,0</data></node>
    <edge id="e0" source="a" target="b"><data key="d0">0.05</data><data key="d1">0.2</data></edge>
    <edge id="e1" source="b" target="c"><data key="d0">{bc_link0}</data><data key="d1">0.01</data></edge>
  </graph>
</graphml>
""")

    def test_graphml_modes(self):
        src = self.graphml()
        out = self.path("both.mosb")
        result = run("convert", "roadmap", "--graphml", src, "--clearance", "both", "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(header_counts(out), (3, 4, 4))
        info = inspect(out)
        self.assertEqual([o["name"] for o in info["objectives"]], ["length", "clearance", "clearance_0", "clearance_1"])
        self.assertEqual(info["metadata"]["view.Panda-RRG_2.objectives"], "length,clearance")
        verify = run("verify", out, "--level", "full")
        self.assertEqual(verify.returncode, 0, verify.stdout + verify.stderr)
        for mode, d in (("aggregate", 2), ("per-link", 3), ("none", 1)):
            path = self.path(mode + ".mosb")
            result = run("convert", "roadmap", "--graphml", src, "--clearance", mode, "-o", path)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertEqual(header_counts(path), (3, 4, d))

    def test_collision_refused(self):
        src = self.graphml("-0.01")
        result = run("convert", "roadmap", "--graphml", src, "--clearance", "per-link", "-o",
                     self.path("x.mosb"))
        self.assertEqual(result.returncode, 1)
        self.assertIn("edge 'e1' ('b' -> 'c'): clearance_0 = -0.01 <= 0: a collision", result.stderr)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1)
        self.assertFalse(os.path.exists(self.path("x.mosb")))

    def test_deterministic_from_any_directory(self):
        src = self.graphml()
        os.mkdir(self.path("sub"))
        a, b = self.path("a.mosb"), self.path("sub", "b.mosb")
        self.assertEqual(run("convert", "roadmap", "--graphml", src, "-o", a).returncode, 0)
        self.assertEqual(run("convert", "roadmap", "--graphml", "../r.graphml", "-o", "b.mosb",
                             cwd=self.path("sub")).returncode, 0)
        with open(a, "rb") as fa, open(b, "rb") as fb:
            self.assertEqual(fa.read(), fb.read())

    def test_gr_vertices_from_ids(self):
        gr = self.write("c1.gr", "p sp 2 2\na 0 1 0.5\na 1 2 1.25\n")
        result = run("convert", "roadmap", "--gr", gr, "-o", self.path("x.mosb"))
        self.assertEqual(result.returncode, 1)
        self.assertIn("c1.gr:3:5: the largest vertex id, 2, is outside the 2 vertices declared on line 1", result.stderr)
        self.assertIn("--vertices-from-ids", result.stderr)
        out = self.path("y.mosb")
        result = run("convert", "roadmap", "--gr", gr, "--vertices-from-ids", "--objective", "len:m", "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("warning: vertex_count: declared 2, ids reach 2", result.stderr)
        self.assertEqual(header_counts(out), (3, 2, 1))
        self.assertEqual(inspect(out)["metadata"]["warning.vertex_count"], "declared 2, ids reach 2")

    def test_gr_huge_id_with_vertices_from_ids_is_refused(self):
        # One id of 4e9 in a 24-byte file would size the graph to 4e9 vertices (it died of
        # std::bad_alloc): refused at the id, before anything that large is allocated.
        gr = self.write("huge.gr", "p sp 2 1\na 0 4000000000 1.5\n")
        out = self.path("x.mosb")
        result = run("convert", "roadmap", "--gr", gr, "--vertices-from-ids", "-o", out)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertEqual(result.stderr.count("\n"), 1, result.stderr)
        self.assertIn(gr + ":2:5: vertex id 4000000000 would size the graph to 4000000001 vertices", result.stderr)
        self.assertFalse(os.path.exists(out))
        # The same from the vertex file.
        gr = self.write("ok.gr", "p sp 2 1\na 0 1 1.5\n")
        vertices = self.write("v.txt", "0 0.0\n1 1.0\n3000000000 2.0\n")
        result = run("convert", "roadmap", "--gr", gr, "--vertices", vertices, "--vertices-from-ids", "-o", out)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn(vertices + ":3:1: vertex id 3000000000 would size the graph", result.stderr)
        self.assertFalse(os.path.exists(out))
        # Ids a little beyond the header, within what the input can hold, still work.
        gr = self.write("gap.gr", "p sp 2 1\na 0 9 1.5\n")
        result = run("convert", "roadmap", "--gr", gr, "--vertices-from-ids", "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(header_counts(out), (10, 1, 1))

    def test_gr_objective_names_and_units(self):
        a = self.write("a.gr", "p sp 3 2\na 0 1 0.5\na 1 2 1.25\n")
        b = self.write("b.gr", "p sp 3 2\na 0 1 2\na 1 2 3\n")
        out = self.path("n.mosb")
        result = run("convert", "roadmap", "--gr", a, "--gr", b, "--objective", "length:m", "--objective", "risk",
                     "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        info = inspect(out)
        self.assertEqual([o["name"] for o in info["objectives"]], ["length", "risk"])
        self.assertEqual(info["metadata"]["objective.length.unit"], "m")
        self.assertEqual(info["metadata"]["source.param.objectives"], "length:m,risk")
        result = run("convert", "roadmap", "--gr", a, "--gr", b, "--objective", "length", "-o", out + "2")
        self.assertEqual(result.returncode, 1)
        self.assertIn("1 --objective names given, the input has 2 objectives", result.stderr)
        result = run("convert", "roadmap", "--gr", a, "--objective", ":m", "-o", out + "3")
        self.assertEqual(result.returncode, 1)
        self.assertIn("convert roadmap: --objective ':m' has an empty name", result.stderr)

    def test_graphml_without_clearance_warns(self):
        src = self.write("plain.graphml", """<?xml version="1.0"?>
<graphml xmlns="http://graphml.graphdrawing.org/xmlns">
  <key id="q" for="node" attr.name="coords" attr.type="string"/>
  <graph edgedefault="directed">
    <node id="a"><data key="q">0,0</data></node>
    <node id="b"><data key="q">3,4</data></node>
    <edge source="a" target="b"/>
  </graph>
</graphml>
""")
        out = self.path("p.mosb")
        result = run("convert", "roadmap", "--graphml", src, "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("mosb: warning: clearance: no edge key 'clearance' or 'clearance_0'.. in plain.graphml",
                      result.stderr)
        self.assertEqual(header_counts(out), (2, 1, 1))
        self.assertIn("no clearance objective is written", inspect(out)["metadata"]["warning.clearance"])
        # Asked for explicitly: no warning.
        result = run("convert", "roadmap", "--graphml", src, "--clearance", "none", "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn("warning", result.stderr)
        self.assertNotIn("warning.clearance", inspect(out)["metadata"])


@unittest.skipUnless(os.path.isdir(POINT_ROBOT) and os.path.isfile(GRAPHML), mosbtest.MISSING + f"shared data absent: {DATA}")
class RealFixtures(CliTest):
    def test_point_robot(self):
        files = [os.path.join(POINT_ROBOT, f"file_{i}.gr") for i in range(6)]
        args = []
        for f in files:
            args += ["--gr", f]
        args += ["--vertices", os.path.join(POINT_ROBOT, "vertex_positions.txt")]
        out = self.path("p.mosb")
        refused = run("convert", "roadmap", *args, "-o", out)
        self.assertEqual(refused.returncode, 1)
        self.assertEqual(refused.stderr.strip(), "mosb: " + files[0] + ":146501:8: the largest vertex id, 5002, is "
                         "outside the 5002 vertices declared on line 2 (0-based ids 0..5001); --vertices-from-ids "
                         "sizes the graph from the largest id instead")
        result = run("convert", "roadmap", *args, "--vertices-from-ids", "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        # Independent counts: arc lines of every file, largest id, vertex file lines.
        arcs, largest = set(), 0
        for f in files:
            with open(f) as fh:
                lines = [line.split() for line in fh if line.startswith("a ")]
            arcs.add(len(lines))
            largest = max(largest, max(max(int(t[1]), int(t[2])) for t in lines))
        with open(os.path.join(POINT_ROBOT, "vertex_positions.txt")) as fh:
            vertex_lines = sum(1 for line in fh if line.strip())
        self.assertEqual(arcs, {154414})
        self.assertEqual(header_counts(out), (max(largest + 1, vertex_lines), 154414, 6))
        self.assertEqual(header_counts(out), (5003, 154414, 6))
        meta = inspect(out)["metadata"]
        self.assertEqual(meta["warning.vertex_count"], "declared 5002, ids reach 5002")
        self.assertEqual(meta["family"], "robots")

    def test_graphml(self):
        root = ET.parse(GRAPHML).getroot()
        graph = root.find(NS + "graph")
        directed_default = graph.get("edgedefault") == "directed"
        expected_arcs = 0
        for edge in graph.findall(NS + "edge"):
            directed = edge.get("directed", "true" if directed_default else "false") == "true"
            expected_arcs += 1 if directed or edge.get("source") == edge.get("target") else 2
        nodes = len(graph.findall(NS + "node"))
        out = self.path("g.mosb")
        result = run("convert", "roadmap", "--graphml", GRAPHML, "--weight", "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(header_counts(out), (nodes, expected_arcs, 2))
        self.assertEqual((nodes, expected_arcs), (170, 698))
        # The sample has no clearance keys: the default writes length alone and says so.
        out = self.path("plain.mosb")
        result = run("convert", "roadmap", "--graphml", GRAPHML, "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("mosb: warning: clearance: no edge key", result.stderr)
        self.assertEqual(header_counts(out), (nodes, expected_arcs, 1))
        self.assertIn("warning.clearance", inspect(out)["metadata"])

    def test_readme_example_runs_on_the_sample(self):
        with open(README) as f:
            commands = re.findall(r"`(mosb convert roadmap --graphml [^`]*)`", f.read())
        self.assertEqual(len(commands), 1, commands)
        out = self.path("readme.mosb")
        args = [GRAPHML if a == "roadmap.xml" else out if a == "F" else a for a in shlex.split(commands[0])[1:]]
        self.assertIn(GRAPHML, args)
        result = run(*args)
        self.assertEqual(result.returncode, 0, commands[0] + ": " + result.stderr)
        self.assertEqual(header_counts(out)[:2], (170, 698))


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
