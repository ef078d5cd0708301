#!/usr/bin/python3
"""End-to-end tests of `mosb pack` and `mosb unpack` (lib/pack/include/mosb/pack.hpp,
spec/FORMAT.md §6):
exact round trips over the golden valid files and every converter's output, deterministic bytes,
packed files read by inspect and verify, hostile packed files refused in one line, damaged inputs
never written out (nor repaired), the padding of packed files, and decompression bombs refused
before anything is allocated.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_pack.py
"""

import glob
import json
import os
import struct
import subprocess
import time

import xxhash

import mosbtest
from mosbtest import (GOLDEN, CliTest, entries, entry, header, move_payload_to_end,  # noqa: F401
                      read, reseal, set_entry, set_header, setUpModule, values)
from test_fmi import TEN
from test_movingai import HAND_MADE

BLOCK = 128 << 10  # the largest zstd block


def zstd_frame(content_size, blocks):
    """A zstd frame built by hand (RFC 8878): single segment, an 8-byte declared content size, no
    checksum; `blocks` are (type, size, body), type 0 raw (body: the bytes), 1 RLE (body: the
    byte, repeated size times)."""
    out = bytearray(b"\x28\xb5\x2f\xfd" + bytes([0xE0]) + struct.pack("<Q", content_size))
    for i, (kind, size, body) in enumerate(blocks):
        last = 1 if i == len(blocks) - 1 else 0
        out += struct.pack("<I", last | kind << 1 | size << 3)[:3] + body
    return bytes(out)


def raw_frame(data):
    """The frame of `data` stored as raw blocks: what any zstd decoder expands to `data`."""
    chunks = [data[i:i + BLOCK] for i in range(0, len(data), BLOCK)] or [b""]
    return zstd_frame(len(data), [(0, len(c), c) for c in chunks])


def rle_frame(size):
    """A frame expanding to `size` zero bytes from 4 bytes per 128 KiB: a decompression bomb."""
    sizes = [BLOCK] * (size // BLOCK) + ([size % BLOCK] if size % BLOCK else [])
    return zstd_frame(size, [(1, n, b"\0") for n in sizes])


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


class DamagedInputTest(CliTest):
    """pack and unpack verify before they write: a damaged input leaves no output (and, with
    --in-place, the file as it was), exit 1, one line naming the input; pack never repairs."""

    converter_outputs = PackTest.converter_outputs

    def forged(self):
        """A packed grid whose forward_targets frame (plain zstd, raw blocks) decodes, with a
        matching checksum, to targets of which one is n: the checksums hold, the CSR does not."""
        source = self.converter_outputs()["grid"]
        packed = self.path("p.mosb")
        self.ok("pack", "--keep-reverse", source, "-o", packed)
        data = bytearray(read(packed))
        targets = values(read(source), "forward_targets", "I")
        targets[3] = header(data)["vertex_count"]
        body = struct.pack("<%dI" % len(targets), *targets)
        move_payload_to_end(data, "forward_targets", raw_frame(body), encoding=1,
                            checksum=xxhash.xxh3_64_intdigest(body))
        return self.write("forged.mosb", data)

    def assert_refused(self, args, original, target, *expected):
        r = self.mosb(*args)
        line = self.assert_one_line_error(r, *expected)
        self.assertIn("forged.mosb", line)
        if original is None:
            self.assertFalse(os.path.exists(target), args)
        else:
            self.assertEqual(read(target), original, args)
        leftovers = [f for f in os.listdir(self.dir) if ".tmp-" in f]
        self.assertEqual(leftovers, [], args)

    def test_broken_csr_with_good_checksums(self):
        forged = self.forged()
        original = read(forged)
        out = self.path("out.mosb")
        for command in ("unpack", "pack"):
            self.assert_refused([command, forged, "-o", out], None, out, "target-range",
                                "nothing written")
            self.assert_refused([command, "--in-place", forged], original, forged,
                                "target-range")
        r = self.mosb("verify", forged)
        self.assertEqual(r.returncode, 1)
        self.assertIn("target-range", r.stdout)

    def test_padding_of_packed_files(self):
        packed = self.path("p.mosb")
        self.ok("pack", self.converter_outputs()["grid"], "-o", packed)
        data = read(packed)
        frames = sorted((e["offset"], e["offset"] + e["stored_length"]) for e in entries(data)
                        if e["stored_length"])
        inside = {i for a, b in frames for i in range(a, b)}
        padding = [i for i in range(128, header(data)["table_offset"]) if i not in inside]
        self.assertTrue(padding)
        # Every padding byte is checked at level full (the unit test flips each); here, the first,
        # one between frames and the last, through verify, pack and unpack.
        for i in sorted({padding[0], padding[len(padding) // 2], padding[-1]}):
            bad = bytearray(data)
            bad[i] ^= 0x40
            forged = self.write("forged.mosb", bad)
            r = self.mosb("verify", forged)
            self.assertEqual(r.returncode, 1, (i, r.stdout))
            self.assertIn("[padding] byte %d " % i, r.stdout)
            self.ok("verify", "--level", "checksums", forged)
            out = self.path("out.mosb")
            for command in ("pack", "unpack"):
                self.assert_refused([command, forged, "-o", out], None, out, "[padding]")


class BombTest(CliTest):
    """Decompression bombs: a packed grid whose one section is an RLE frame of BOMB bytes (128 KiB
    on disk), the table and header resealed so that only the size checks can catch it."""

    converter_outputs = PackTest.converter_outputs

    BOMB = 4 << 30

    def measured(self, *args):
        """Runs mosb; returns (exit code, stdout + stderr, peak RSS in MB, seconds)."""
        with open(self.path("out.txt"), "w") as out, open(self.path("err.txt"), "w") as err:
            start = time.monotonic()
            child = subprocess.Popen([mosbtest.MOSB, *args], cwd=self.dir, stdout=out,
                                     stderr=err)
            _, status, usage = os.wait4(child.pid, 0)
            seconds = time.monotonic() - start
            child.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
        text = read(self.path("out.txt"), "r") + read(self.path("err.txt"), "r")
        return os.waitstatus_to_exitcode(status), text, usage.ru_maxrss / 1024, seconds

    def bomb(self, section, rows):
        """The grid, packed, with `section` declaring `rows` rows and holding the bomb frame."""
        source = self.converter_outputs()["grid"]
        self.ok("queries", "generate", source, "--set", "bombed", "--count", "3", "--seed", "1",
                "--in-place")
        packed = self.path("p.mosb")
        self.ok("pack", "--keep-reverse", source, "-o", packed)
        data = bytearray(read(packed))
        move_payload_to_end(data, section, rle_frame(self.BOMB), encoding=1, row_count=rows)
        return self.write("bomb.mosb", data)

    def assert_cheap(self, args, code, *expected):
        status, text, rss, seconds = self.measured(*args)
        self.assertEqual(status, code, (args, text))
        for fragment in expected:
            self.assertIn(fragment, text, args)
        self.assertLess(rss, 200, (args, text))
        self.assertLess(seconds, 30, args)
        self.assertFalse(os.path.exists(self.path("out.mosb")))

    def test_bomb_in_a_column_of_m_rows(self):
        # The cost column declares BOMB bytes, as its frame does; the arc count says otherwise.
        cost = [e for e in entries(read(self.converter_outputs()["grid"])) if e["kind"] == 7][0]
        bomb = self.bomb(cost["name"], self.BOMB // (cost["stored_length"] // cost["row_count"]))
        for level in ("header", "checksums", "structure", "full"):
            self.assert_cheap(["verify", "--level", level, bomb], 1, "but the arc count is")
        self.assert_cheap(["unpack", bomb, "-o", "out.mosb"], 1, "but the arc count is")

    def test_bomb_in_a_query_set(self):
        # A query set may hold any number of queries: only the memory cap bounds it.
        bomb = self.bomb("bombed", self.BOMB // 8)
        self.assert_cheap(["verify", "--level", "header", bomb], 0, "OK")
        for level in ("checksums", "structure", "full"):
            self.assert_cheap(["verify", "--level", level, "--max-memory", "1G", bomb], 1,
                              "more than the cap of 1073741824 bytes")
        self.assert_cheap(["unpack", "--max-memory", "1G", bomb, "-o", "out.mosb"], 1,
                          "more than the cap")
        self.assert_cheap(["pack", "--max-memory", "1G", bomb, "-o", "out.mosb"], 1,
                          "more than the cap")

    def test_frame_declaring_other_than_the_table(self):
        # The frame declares BOMB bytes, the table its true length: refused before decoding.
        bomb = self.bomb("bombed", 3)
        for level in ("checksums", "full"):
            self.assert_cheap(["verify", "--level", level, bomb], 1,
                              "zstd frame declares %d bytes" % self.BOMB)

    def test_max_memory_option(self):
        packed = self.path("p.mosb")
        self.ok("pack", self.converter_outputs()["grid"], "-o", packed)
        self.ok("verify", "--max-memory", "64M", packed)
        r = self.mosb("verify", "--max-memory", "1K", packed)
        self.assertEqual(r.returncode, 1)
        self.assertIn("more than the cap of 1024 bytes", r.stdout)
        r = self.mosb("unpack", "--max-memory", "lots", packed, "-o", self.path("u.mosb"))
        self.assertEqual(r.returncode, 2)


if __name__ == "__main__":
    mosbtest.main()
