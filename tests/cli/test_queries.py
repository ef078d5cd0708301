#!/usr/bin/python3
"""End-to-end tests of `mosb queries import` and `mosb queries generate` (spec/QUERIES.md).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_queries.py
"""

import os
import re
import struct

import mosbtest
from mosbtest import (DATA, METADATA_KIND, QUERIES_KIND, CliTest, entries, metadata,  # noqa: F401
                      read, setUpModule)

GRID = ["generate", "grid", "--width", "5", "--height", "4", "--objectives", "2", "--seed", "7"]
N = 5 * 4 + 2
WROTE = re.compile(r"^wrote (.+): query set (\S+), (\d+) queries, digest [0-9a-f]{32}$")


def sections(data):
    """[(name, kind, checksum, payload bytes)] in table order."""
    return [(e["name"], e["kind"], e["checksum"],
             data[e["offset"]:e["offset"] + e["stored_length"]]) for e in entries(data)]


def query_pairs(data, name):
    (payload,) = [p for n, k, _c, p in sections(data) if k == QUERIES_KIND and n == name]
    values = struct.unpack("<%dI" % (len(payload) // 4), payload)
    return list(zip(values[0::2], values[1::2]))


MASK = (1 << 64) - 1


def mix(z):
    """SplitMix64's finalizer (spec/GENERATORS.md, Random source)."""
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
    return z ^ (z >> 31)


class SplitMix64:
    """spec/GENERATORS.md, written again here so the test checks the documented draw order."""

    def __init__(self, seed, index):
        self.state = mix((seed + 0x9E3779B97F4A7C15 * (index + 1)) & MASK)

    def next(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        return mix(self.state)

    def uniform(self, lo, hi):
        r = hi - lo + 1
        t = (1 << 64) % r
        x = self.next()
        while x < t:
            x = self.next()
        return lo + x % r


def expected_generated(seed, count, n, allow_same):
    rng = SplitMix64(seed, 0)
    pairs = []
    for _ in range(count):
        s = rng.uniform(0, n - 1)
        g = rng.uniform(0, n - 1)
        while not allow_same and g == s:
            g = rng.uniform(0, n - 1)
        pairs.append((s, g))
    return pairs


class QueriesTest(CliTest):
    def fails(self, *args):
        return self.assert_one_line_error(self.mosb(*args)).strip()

    def grid(self, name="g.mosb"):
        path = self.path(name)
        self.ok(*GRID, "-o", path)
        return path

    def verify_full(self, path):
        c = self.ok("verify", path, "--level", "full")
        self.assertTrue(c.stdout.startswith("OK"), c.stdout)

    def assert_wrote(self, c, path, name, count):
        m = WROTE.match(c.stdout.strip())
        self.assertIsNotNone(m, c.stdout)
        self.assertEqual(m.groups(), (path, name, str(count)))

    def assert_others_unchanged(self, before, after, changed):
        """Every section but metadata and `changed` has the same checksum and bytes."""
        old = {(n, k): (c, p) for n, k, c, p in sections(before)}
        for n, k, c, p in sections(after):
            if k == METADATA_KIND or (k == QUERIES_KIND and n == changed):
                continue
            self.assertEqual(old[(n, k)], (c, p), n)

    def test_import_into_grid(self):
        g = self.grid()
        before = read(g)
        q = self.write("pairs.txt", "# two pairs\r\n1 2\r\n3 ,4\r\n\r\nc end\r\n5;21")
        c = self.ok("queries", "import", g, q, "--in-place", "--set", "mine")
        self.assert_wrote(c, g, "mine", 3)
        after = read(g)
        self.assertEqual(query_pairs(after, "mine"), [(1, 2), (3, 4), (5, 21)])
        self.assertEqual([n for n, *_ in sections(after)], [n for n, *_ in sections(before)] + ["mine"])
        self.assert_others_unchanged(before, after, "mine")
        meta = metadata(after)
        self.assertEqual(meta["queries.mine.source"], "import")
        self.assertEqual(meta["queries.mine.input.name"], "pairs.txt")
        self.assertEqual(meta["queries.mine.input.size"], str(os.path.getsize(q)))
        self.assertRegex(meta["queries.mine.input.xxh3"], r"^[0-9a-f]{16}$")
        self.assertEqual(meta["queries.mine.id_base"], "0")
        self.assertEqual(meta["benchmark"], metadata(before)["benchmark"])
        self.verify_full(g)

    def test_id_base_and_out_of_range(self):
        g = self.grid()
        q = self.write("q.txt", "1 2\n1 22\n")
        before = read(g)
        err = self.fails("queries", "import", g, q, "--in-place", "--set", "x")
        self.assertEqual(err, "mosb: %s:2:3: vertex id '22' outside 0..21" % q)
        self.assertEqual(read(g), before)  # untouched
        # The grid records id_base 0: an explicit --id-base 1 is the classic off-by-one, refused
        # (usage error, file untouched) unless --force-id-base says it is meant.
        r = self.mosb("queries", "import", g, q, "--in-place", "--set", "x", "--id-base", "1")
        line = self.assert_one_line_error(r, "--id-base 1 contradicts", "records id_base 0",
                                          "--force-id-base", code=2)
        self.assertIn(g, line)
        self.assertEqual(read(g), before)
        self.ok("queries", "import", g, q, "--in-place", "--set", "x", "--id-base", "1",
                "--force-id-base")
        self.assertEqual(query_pairs(read(g), "x"), [(0, 1), (0, 21)])
        self.assertEqual(metadata(read(g))["queries.x.id_base"], "1")
        self.verify_full(g)

    def test_a_new_set_becomes_the_query_set_of_views_without_one(self):
        # Views written before any set existed (here: by --view, with no intended set given
        # through a family default) get the first set added, and stderr says so.
        q = self.write("q.txt", "0 1\n")
        g = self.path("n.mosb")
        self.ok("generate", "netmaker", "--vertices", "30", "--queries", "2", "-o", g)
        meta = metadata(read(g))
        self.assertEqual(meta["view.NetMaker-30_3.queries"], "default")  # bound already: untouched
        gr = self.write("n.gr", "p sp 3 2\na 0 1 5 6\na 1 2 7 8\n")
        inst = self.path("c.mosb")
        self.ok("convert", "netmaker", gr, "-o", inst)
        self.assertNotIn("view.NetMaker-3_2.queries", metadata(read(inst)))
        c = self.ok("queries", "import", inst, q, "-o", self.path("c1.mosb"), "--set", "mine")
        self.assertEqual(c.stderr, "query set mine is now the query set of view NetMaker-3_2\n")
        self.assertEqual(metadata(read(self.path("c1.mosb")))["view.NetMaker-3_2.queries"], "mine")
        # A view bound already keeps its set; --view V rebinds V alone.
        c = self.ok("queries", "generate", self.path("c1.mosb"), "--set", "other", "--count", "2",
                    "-o", self.path("c2.mosb"))
        self.assertEqual(c.stderr, "")
        self.assertEqual(metadata(read(self.path("c2.mosb")))["view.NetMaker-3_2.queries"], "mine")
        c = self.ok("queries", "generate", self.path("c2.mosb"), "--set", "third", "--count", "2",
                    "--view", "NetMaker-3_2", "-o", self.path("c3.mosb"))
        self.assertEqual(c.stderr, "query set third is now the query set of view NetMaker-3_2\n")
        self.assertEqual(metadata(read(self.path("c3.mosb")))["view.NetMaker-3_2.queries"], "third")
        err = self.fails("queries", "generate", self.path("c2.mosb"), "--set", "fourth",
                         "--view", "nope", "-o", self.path("c4.mosb"))
        self.assertIn("no view 'nope' (views: NetMaker-3_2)", err)
        self.assertFalse(os.path.exists(self.path("c4.mosb")))

    def test_replace_keeps_position(self):
        g = self.grid()
        q = self.write("q.txt", "0 1\n")
        err = self.fails("queries", "import", g, q, "--in-place", "--set", "default")
        self.assertIn("query set 'default' exists", err)
        self.assertIn("--replace", err)
        before = read(g)
        self.ok("queries", "import", g, q, "--in-place", "--set", "default", "--replace")
        after = read(g)
        self.assertEqual([n for n, *_ in sections(after)], [n for n, *_ in sections(before)])
        self.assertEqual(query_pairs(after, "default"), [(0, 1)])
        self.assert_others_unchanged(before, after, "default")
        # Replacing an imported set by a generated one drops the import's keys.
        self.ok("queries", "generate", g, "--in-place", "--set", "default", "--seed", "1", "--replace")
        meta = metadata(read(g))
        self.assertEqual(meta["queries.default.source"], "generate")
        self.assertNotIn("queries.default.input.name", meta)
        self.verify_full(g)

    def test_generate(self):
        g = self.grid()
        before = read(g)
        c = self.ok("queries", "generate", g, "--in-place", "--set", "rand", "--count", "200", "--seed", "9")
        self.assert_wrote(c, g, "rand", 200)
        after = read(g)
        pairs = query_pairs(after, "rand")
        self.assertEqual(pairs, expected_generated(9, 200, N, False))
        self.assertTrue(all(s != t for s, t in pairs))
        self.assert_others_unchanged(before, after, "rand")
        meta = metadata(after)
        self.assertEqual((meta["queries.rand.source"], meta["queries.rand.seed"],
                          meta["queries.rand.count"], meta["queries.rand.allow_same"]),
                         ("generate", "9", "200", "0"))
        self.verify_full(g)
        self.ok("queries", "generate", g, "--in-place", "--set", "same", "--count", "300", "--seed", "9",
                "--allow-same")
        same = query_pairs(read(g), "same")
        self.assertEqual(same, expected_generated(9, 300, N, True))
        self.assertTrue(any(s == t for s, t in same))  # 300 draws over 22 vertices: some s = t

    def test_generate_is_deterministic(self):
        a, b = self.grid("a.mosb"), self.grid("b.mosb")
        for path in (a, b):
            self.ok("queries", "generate", path, "--in-place", "--set", "r", "--count", "50", "--seed", "4")
        self.assertEqual(read(a), read(b))
        self.ok("queries", "generate", b, "--in-place", "--set", "r", "--count", "50", "--seed", "5",
                "--replace")
        self.assertNotEqual(read(a), read(b))

    def test_graph_lines_and_match(self):
        g = self.grid()
        q = self.write("x.inst", "/c/one_1.gr 1 2\n/c/two_2.gr 3 4\n/c/one_1.gr 5 6\n")
        err = self.fails("queries", "import", g, q, "--in-place", "--set", "t")
        self.assertIn("%s:2:1: the file names more than one graph" % q, err)
        self.assertIn("--match", err)
        self.ok("queries", "import", g, q, "--in-place", "--set", "t", "--match", "one_1")
        self.assertEqual(query_pairs(read(g), "t"), [(1, 2), (5, 6)])
        self.assertEqual(metadata(read(g))["queries.t.match"], "one_1")
        self.verify_full(g)

    def test_real_inst_file(self):
        inst = os.path.join(DATA, "netmaker", "netMaker_4d.inst")
        self.skip_unless_present(inst)
        # A 100x100 grid has 10002 vertices: every netMaker id (< 10000) is in range.
        g = self.path("big.mosb")
        self.ok("generate", "grid", "--width", "100", "--height", "100", "--objectives", "1", "-o", g)
        c = self.ok("queries", "import", g, inst, "--in-place", "--set", "nm", "--match", "_79134.gr")
        self.assert_wrote(c, g, "nm", 40)
        self.assertEqual(query_pairs(read(g), "nm")[0], (8326, 5528))


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
