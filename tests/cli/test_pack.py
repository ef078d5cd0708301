#!/usr/bin/python3
"""End-to-end tests of `mosb pack` and `mosb unpack` (lib/pack/include/mosb/pack.hpp,
spec/FORMAT.md §6):
exact round trips over the golden valid files and every converter's output, deterministic bytes,
packed files read by inspect and verify, and hostile packed files refused in one line.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_pack.py
"""

import glob
import json
import os
import subprocess
import unittest

from mosbtest import (GOLDEN, CliTest, entries, entry, header, move_payload_to_end,  # noqa: F401
                      read, reseal, set_entry, set_header, setUpModule)
from test_fmi import TEN
from test_movingai import HAND_MADE

GOLDEN_VALID = sorted(glob.glob(os.path.join(GOLDEN, "*", "valid", "*.mosb")))
GR = "p sp 4 5\na 1 2 5\na 2 3 7\na 3 1 2\na 3 4 9\na 4 1 1\n"


class PackTest(CliTest):
    def converter_outputs(self):
        """One instance from each generator and converter, from the inputs the CLI tests use."""
        out = {}
        gr = self.write("in.gr", GR)
        fmi = self.write("in.fmi", TEN)
        map_file = self.write("in.map", HAND_MADE)
        commands = {
            "grid": ["generate", "grid", "--width", "30", "--height", "20", "--objectives", "3",
                     "--seed", "7"],
            "netmaker": ["generate", "netmaker", "--vertices", "300", "--seed", "3"],
            "dimacs": ["convert", "dimacs", "--gr", gr],
            "fmi": ["convert", "fmi", fmi, "--costs", "10"],
            "movingai": ["convert", "movingai", "--map", map_file],
        }
        for name, command in commands.items():
            target = self.path(name + ".mosb")
            self.ok(*command, "-o", target)
            out[name] = target
        return out

    def round_trip(self, source):
        original = read(source)
        packed, unpacked = self.path("p.mosb"), self.path("u.mosb")
        self.ok("pack", source, "-o", packed)
        self.ok("unpack", packed, "-o", unpacked)
        self.assertEqual(read(unpacked), original, source)
        data = read(packed)
        if header(data)["required_features"]:
            self.assertTrue(any(e["encoding"] != 0 for e in entries(data)))
        # An instance's reverse CSR is derived at unpacking (encoding 4, format 1.2), unless
        # --keep-reverse; both unpack to the same bytes.
        if header(data)["file_kind"] == 1:
            reverse = [e for e in entries(data) if e["kind"] in (4, 5, 6)]
            self.assertEqual([(e["encoding"], e["stored_length"]) for e in reverse], [(4, 0)] * 3)
            self.assertEqual(header(data)["version_minor"], 2)
            shown = json.loads(self.ok("inspect", "--json", packed).stdout)["sections"]
            self.assertEqual([s["encoding"] for s in shown if s["kind"].startswith("reverse")],
                             ["transpose"] * 3)
            kept = self.path("kept.mosb")
            self.ok("pack", "--keep-reverse", source, "-o", kept)
            self.assertNotIn(4, [e["encoding"] for e in entries(read(kept))])
            self.assertLessEqual(header(read(kept))["version_minor"], 1)
            self.assertLess(len(data), len(read(kept)) + 1)
            self.ok("unpack", kept, "-o", unpacked)
            self.assertEqual(read(unpacked), original, source)
        # Same content digest, read from the tables alone; verify decodes and checks.
        digests = {json.loads(self.ok("inspect", "--json", f).stdout)["digest"]
                   for f in (source, packed)}
        self.assertEqual(len(digests), 1, source)
        self.ok("verify", packed)
        # Deterministic: again, with other threads, and from the packed file itself.
        again = self.path("again.mosb")
        self.ok("pack", source, "-o", again, "--threads", "3")
        self.assertEqual(read(again), data, source)
        self.ok("pack", packed, "-o", again)
        self.assertEqual(read(again), data, source)
        return data

    def test_round_trip_golden_valid_files(self):
        self.assertTrue(GOLDEN_VALID)
        for source in GOLDEN_VALID:
            self.round_trip(source)

    def test_round_trip_converter_outputs(self):
        for name, source in self.converter_outputs().items():
            data = self.round_trip(source)
            if name == "grid":
                self.assertLess(len(data), len(read(source)) // 2)

    def test_in_place_and_output_rules(self):
        source = self.converter_outputs()["grid"]
        original = read(source)
        self.ok("pack", "--in-place", source)
        self.assertLess(len(read(source)), len(original))
        self.ok("unpack", "--in-place", source)
        self.assertEqual(read(source), original)
        for args in (["pack", source], ["pack", source, "-o", source],
                     ["pack", source, source, "-o", self.path("x.mosb")]):
            r = self.mosb(*args)
            self.assertNotEqual(r.returncode, 0, args)
            self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertEqual(read(source), original)

    def test_zero_copy_reader_refuses_packed_file(self):
        source = self.converter_outputs()["grid"]
        self.ok("pack", source, "-o", self.path("p.mosb"))
        r = self.mosb("stats", self.path("p.mosb"))
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("packed", r.stderr)

    def test_non_canonical_layout_is_refused(self):
        source = self.converter_outputs()["dimacs"]
        data = bytearray(read(source))
        set_header(data, optional_features=1)
        reseal(data)
        odd = self.write("odd.mosb", data)
        r = self.mosb("pack", odd, "-o", self.path("p.mosb"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("could not restore its exact bytes", r.stderr)
        self.assertFalse(os.path.exists(self.path("p.mosb")))

    def hostile(self, mutate, *expected):
        """Packs a grid, applies mutate(data), and expects unpack, verify and pack to refuse it in
        one line containing every fragment of `expected`, writing nothing."""
        packed = self.path("p.mosb")
        if not os.path.exists(packed):
            # Every section in a zstd frame: the frame checks are what these tests attack.
            self.ok("pack", "--keep-reverse", self.converter_outputs()["grid"], "-o", packed)
        data = bytearray(read(packed))
        mutate(data)
        bad = self.write("bad.mosb", data)
        for args in (["unpack", bad, "-o", self.path("out.mosb")], ["verify", bad],
                     ["pack", bad, "-o", self.path("out.mosb")]):
            r = self.mosb(*args)
            self.assertEqual(r.returncode, 1, (args, r.stdout, r.stderr))
            text = r.stderr + r.stdout
            self.assertEqual(len(text.strip().splitlines()), 1, text)
            for fragment in expected:
                self.assertIn(fragment, text)
            self.assertFalse(os.path.exists(self.path("out.mosb")))

    def test_declared_length_disagrees_with_frame(self):
        def grow(data):
            e = entry(data, "forward_targets")
            set_entry(data, "forward_targets", row_count=e["row_count"] + 1)
            set_header(data, arc_count=e["row_count"] + 1)
            reseal(data)
        self.hostile(grow, "bad.mosb", "forward_targets", "zstd frame declares")

    def test_frame_decodes_to_more_than_declared(self):
        def append_frame(data):
            # A second frame after the first (in the padding, which is then part of the section).
            e = entry(data, "forward_targets")
            first = bytes(data[e["offset"]:e["offset"] + e["stored_length"]])
            extra = subprocess.run(["zstd", "-q", "-c"], input=b"\0" * 64,
                                   capture_output=True).stdout
            move_payload_to_end(data, "forward_targets", first + extra, checksum=e["checksum"])
        self.hostile(append_frame, "forward_targets", "bytes follow the zstd frame")

    def test_decompression_bomb(self):
        def bomb(data):
            set_entry(data, "forward_targets", row_count=1 << 40)
            set_header(data, arc_count=1 << 40)
            reseal(data)
        self.hostile(bomb, "forward_targets", "zstd frame can hold")

    def test_truncated_frame(self):
        def truncate(data):
            e = entry(data, "forward_targets")
            set_entry(data, "forward_targets", stored_length=e["stored_length"] - 5)
            reseal(data)
        self.hostile(truncate, "forward_targets", "truncated or damaged")

    def test_frame_without_content_size(self):
        def streamed(data):
            e = entry(data, "forward_targets")
            raw = bytes(4 * e["row_count"])
            frame = subprocess.run(["zstd", "-q", "-c", "--no-content-size"], input=raw,
                                   capture_output=True).stdout
            self.assertLessEqual(len(frame), e["stored_length"])
            data[e["offset"]:e["offset"] + e["stored_length"]] = frame + bytes(
                e["stored_length"] - len(frame))
            set_entry(data, "forward_targets", stored_length=len(frame))
            reseal(data)
        self.hostile(streamed, "forward_targets", "does not declare its content size")

    def test_wrong_section_checksum(self):
        def flip(data):
            e = entry(data, "cost0") if any(x["name"] == "cost0" for x in entries(data)) else \
                [x for x in entries(data) if x["kind"] == 7][0]
            set_entry(data, e["name"], checksum=e["checksum"] ^ 1)
            reseal(data)
        self.hostile(flip, "checksum mismatch")

    def derived_hostile(self, mutate, *expected):
        """hostile() on a grid packed with its reverse CSR derived (encoding 4)."""
        self.ok("pack", self.converter_outputs()["grid"], "-o", self.path("p.mosb"))
        self.hostile(mutate, *expected)

    def test_derived_section_longer_than_its_source(self):
        def grow(data):
            e = entry(data, "reverse_arcs")
            set_entry(data, "reverse_arcs", row_count=e["row_count"] + 1)
            reseal(data)
        self.derived_hostile(grow, "reverse CSR cannot be derived",
                             "section 'reverse_arcs' declares")

    def test_derived_section_with_wrong_checksum(self):
        def flip(data):
            e = entry(data, "reverse_sources")
            set_entry(data, "reverse_sources", checksum=e["checksum"] ^ 1)
            reseal(data)
        self.derived_hostile(flip, "reverse_sources", "checksum mismatch")

    def test_derived_encoding_of_a_cost_column(self):
        def derive_costs(data):
            cost = [e for e in entries(data) if e["kind"] == 7][0]
            set_entry(data, cost["name"], encoding=4, stored_length=0)
            reseal(data)
        self.derived_hostile(derive_costs, "not part of the reverse CSR")


if __name__ == "__main__":
    unittest.main()
