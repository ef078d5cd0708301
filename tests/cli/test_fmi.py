#!/usr/bin/python3
"""End-to-end tests of `mosb convert fmi` (spec/families/ger.md).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_fmi.py
"""

import gzip
import json
import os

import mosbtest
from mosbtest import CliTest, run, setUpModule  # noqa: F401

# A one-way street 3 -> 5; ten costs per edge: c1 is 1 + 10 * (file position), the rest 0..9.
NODES = "".join(f"{v} {10 + v} 48.0{v} 9.0{v} {v + 1}\n" for v in range(8))
ARCS = [(3, 1), (1, 3), (3, 5), (5, 6), (6, 5), (1, 0), (0, 1), (6, 2), (2, 7), (4, 3), (7, 2)]
TEN = "# ten costs\n\n8\n11\n" + NODES + "".join(
    f"{s} {t} {1 + 10 * k} " + " ".join(str(j) for j in range(1, 10)) + "\n" for k, (s, t) in enumerate(ARCS))


class ConvertFmi(CliTest):
    def inspect(self, mosb_file):
        r = run("inspect", mosb_file, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        return json.loads(r.stdout)

    def test_ten_costs_get_ger10_names_and_verify(self):
        src = self.write("ger.txt", TEN)
        out = self.path("ger.mosb")
        r = run("convert", "fmi", src, "--costs", "10", "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("8 vertices, 11 arcs, 10 objectives", r.stdout)
        info = json.dumps(self.inspect(out))
        for name in ["distance", "time", "ascent", "large_roads", "medium_roads", "small_roads",
                     "gas_price", "energy", "unit", "quietness"]:
            self.assertIn(f'"{name}"', info)
        self.assertIn("convert fmi", info)
        v = run("verify", out, "--level", "full")
        self.assertEqual(v.returncode, 0, v.stdout + v.stderr)

    def test_bfs_extraction_and_determinism(self):
        src = self.write("ger.txt", TEN)
        outs = []
        for name in ["a.mosb", "b.mosb"]:
            out = self.path(name)
            r = run("convert", "fmi", src, "--costs", "10", "--extract-bfs", "3", "--count", "5",
                    "--name", "GER_10", "-o", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("5 vertices, 7 arcs, 10 objectives", r.stdout)
            outs.append(open(out, "rb").read())
        self.assertEqual(outs[0], outs[1])
        info = json.dumps(self.inspect(self.path("a.mosb")))
        for text in ["original_id", "extract_bfs_root", "GER_10"]:
            self.assertIn(text, info)

    def test_compressed_input_gives_the_same_sections(self):
        src = self.write("ger.txt", TEN)
        with open(self.path("ger.txt.gz"), "wb") as f:
            f.write(gzip.compress(TEN.encode(), mtime=0))
        plain, packed = self.path("p.mosb"), self.path("z.mosb")
        self.assertEqual(run("convert", "fmi", src, "--costs", "10", "--name", "g", "-o", plain).returncode, 0)
        r = run("convert", "fmi", self.path("ger.txt.gz"), "--costs", "10", "--name", "g", "-o", packed)
        self.assertEqual(r.returncode, 0, r.stderr)
        digest = lambda p: self.inspect(p)["digest"]
        self.assertNotEqual(digest(plain), "")
        sections = lambda p: {s["name"]: s["checksum"] for s in self.inspect(p)["sections"]
                              if s["name"] != "metadata"}
        self.assertEqual(sections(plain), sections(packed))

    def test_errors_are_one_line_naming_the_file(self):
        src = self.write("bad.txt", "2\n1\n0 0 0 0 0\n1 0 0 0 0\n0 1 -5 1\n")
        r = run("convert", "fmi", src, "-o", self.path("x.mosb"))
        self.assertEqual(r.returncode, 1)
        self.assertIn(f"{src}:5:5: negative cost '-5'", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1)
        self.assertFalse(os.path.exists(self.path("x.mosb")))
        src = self.write("ger.txt", TEN)
        r = run("convert", "fmi", src, "--costs", "10", "--extract-bfs", "7", "--count", "8",
                "-o", self.path("y.mosb"))
        self.assertEqual(r.returncode, 1)
        self.assertIn(f"{src}: BFS from vertex 7 reaches only 2 vertices, --count asks for 8", r.stderr)

    def test_count_requires_extract_bfs(self):
        src = self.write("ger.txt", TEN)
        r = run("convert", "fmi", src, "--count", "5", "-o", self.path("z.mosb"))
        self.assertNotEqual(r.returncode, 0)


if __name__ == "__main__":
    mosbtest.main()
