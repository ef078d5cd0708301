#!/usr/bin/python3
"""End-to-end tests of the `mosb` command-line program.

Run with the system interpreter (it has the `xxhash` module, Debian package python3-xxhash):

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_cli.py

Files are corrupted deliberately following spec/FORMAT.md: header fields (§2), section table
entries (§3) and payloads. Where a test wants a *structural* error only, it recomputes the section
checksum and the header checksum (§8) so that every earlier check still passes.
"""

import json
import math
import os
import re
import struct
import subprocess

import xxhash

import mosbtest
from mosbtest import (CHECKSUM_OFFSET, MAGIC, MOSB, CliTest, entries, entry, header, patch_values,
                      payload, relocate_as_f32, reseal, set_entry, set_header, values,
                      write_payload)
from mosbtest import setUpModule  # noqa: F401

GRID = ["generate", "grid", "--width", "5", "--height", "4", "--objectives", "3", "--seed", "7"]
N = 5 * 4 + 2
M = 2 * ((5 - 1) * 4 + (4 - 1) * 5) + 2 * 4


class GridTest(CliTest):
    """The 5x4 grid with three objectives, and `mosb verify` as the judge."""

    def generate(self, name="g.mosb", *extra):
        path = self.path(name)
        r = self.mosb(*GRID, *extra, "-o", path)
        self.assertEqual(r.returncode, 0, r)
        return path

    def grid_bytes(self):
        with open(self.generate(), "rb") as f:
            return bytearray(f.read())

    def assert_ok(self, path, level):
        r = self.mosb("verify", path, "--level", level)
        self.assertEqual(r.returncode, 0, r)
        out = r.stdout.splitlines()
        self.assertEqual(len(out), 1, r)
        self.assertTrue(out[0].startswith("OK"), r)
        self.assertIn(path, out[0])
        return r

    def assert_fail(self, path, level, *expected):
        """verify exits exactly 1 with one line 'FAIL <path>: ...' containing every `expected`."""
        r = self.mosb("verify", path, "--level", level)
        self.assertEqual(r.returncode, 1, r)
        out = r.stdout.splitlines()
        self.assertEqual(len(out), 1, r)
        line = out[0]
        self.assertTrue(line.startswith("FAIL " + path + ": "), r)
        for text in expected:
            self.assertIn(text, line)
        self.assertEqual(r.stderr, "", r)
        return line


# ---------------------------------------------------------------------------------------------

class GenerateInspectVerify(GridTest):
    def test_generate_inspect_verify(self):
        path = self.path("g.mosb")
        r = self.mosb(*GRID, "-o", path)
        self.assertEqual(r.returncode, 0, r)
        self.assertIn("%d vertices, %d arcs, 3 objectives" % (N, M), r.stdout)

        text = self.mosb("inspect", path)
        self.assertEqual(text.returncode, 0, text)
        self.assertRegex(text.stdout, r"(?m)^vertices +%d$" % N)
        self.assertRegex(text.stdout, r"(?m)^arcs +%d$" % M)
        self.assertRegex(text.stdout, r"(?m)^objectives +3$")
        self.assertRegex(text.stdout, r"(?m)^format +1\.0$")

        r = self.mosb("inspect", path, "--json")
        self.assertEqual(r.returncode, 0, r)
        info = json.loads(r.stdout)
        self.assertEqual(info["vertices"], N)
        self.assertEqual(info["arcs"], M)
        self.assertEqual(info["format"], "1.0")
        self.assertEqual([o["name"] for o in info["objectives"]], ["c1", "c2", "c3"])
        self.assertEqual([o["type"] for o in info["objectives"]], ["u8"] * 3)
        self.assertEqual(info["query_sets"], [{"name": "default", "queries": 1}])
        meta = info["metadata"]
        self.assertEqual(meta["view.Grid_2.objectives"], "c1,c2")
        self.assertEqual(meta["view.Grid_3.objectives"], "c1,c2,c3")
        self.assertEqual(meta["view.Grid_2.queries"], "default")
        self.assertEqual(meta["view.Grid_3.queries"], "default")
        self.assertEqual(meta["source.param.seed"], "7")
        self.assertEqual(meta["benchmark"], "Grid-5x4")
        self.assertRegex(text.stdout, r"(?m)^digest +%s$" % info["digest"])

        # The JSON section list agrees with the table as read per spec §3.
        with open(path, "rb") as f:
            data = f.read()
        table = entries(data)
        self.assertEqual([(s["name"], s["offset"], s["bytes"], s["rows"], s["checksum"])
                          for s in info["sections"]],
                         [(e["name"], e["offset"], e["stored_length"], e["row_count"],
                           "%016x" % e["checksum"]) for e in table])

        for level in ("header", "checksums", "structure", "full"):
            with self.subTest(level=level):
                r = self.assert_ok(path, level)
                self.assertIn("(%s, digest %s)" % (level, info["digest"]), r.stdout.splitlines()[0])
        # Default level is full.
        r = self.mosb("verify", path)
        self.assertEqual(r.returncode, 0, r)
        self.assertTrue(r.stdout.splitlines()[0].startswith("OK"), r)
        self.assertIn("(full,", r.stdout)

    def test_layout_and_checksums_match_spec(self):
        data = bytes(self.grid_bytes())
        h = header(data)
        self.assertEqual(h["magic"], MAGIC)
        self.assertEqual(h["byte_order_mark"], 0x01020304)
        self.assertEqual((h["version_major"], h["version_minor"]), (1, 0))
        self.assertEqual(h["file_size"], len(data))
        self.assertEqual((h["vertex_count"], h["arc_count"], h["objective_count"]), (N, M, 3))
        self.assertEqual(h["reserved"], bytes(40))
        self.assertEqual(h["required_features"] | h["optional_features"], 0)
        self.assertEqual(h["table_offset"] + 64 * h["section_count"], len(data))
        table = bytes(data[h["table_offset"]:])
        self.assertEqual(h["header_checksum"],
                         xxhash.xxh3_64_intdigest(data[:CHECKSUM_OFFSET] + table))
        covered = bytearray(len(data))  # 1 where a byte belongs to the header, a payload or table
        covered[:128] = b"\1" * 128
        covered[h["table_offset"]:] = b"\1" * len(table)
        for e in entries(data):
            self.assertEqual(e["offset"] % 64, 0)
            self.assertEqual(e["encoding"], 0)
            body = data[e["offset"]:e["offset"] + e["stored_length"]]
            self.assertEqual(e["checksum"], xxhash.xxh3_64_intdigest(body), e["name"])
            covered[e["offset"]:e["offset"] + e["stored_length"]] = b"\1" * e["stored_length"]
        gaps = bytes(b for b, c in zip(data, covered) if not c)
        self.assertEqual(gaps, bytes(len(gaps)), "alignment gaps must be zero")
        # §8 content digest, as printed by inspect.
        normalized = bytearray(table)
        for i in range(h["section_count"]):
            base = i * 64
            normalized[base + 27] = 0
            normalized[base + 40:base + 56] = bytes(16)
        info = json.loads(self.mosb("inspect", "--json", self.path("g.mosb")).stdout)
        self.assertEqual(info["digest"], xxhash.xxh3_128_hexdigest(bytes(normalized)))


class Determinism(GridTest):
    def test_same_seed_same_bytes_other_seed_other_bytes(self):
        a = self.generate("a.mosb")
        b = self.generate("b.mosb")
        c = self.path("c.mosb")
        r = self.mosb(*GRID[:-1], "8", "-o", c)
        self.assertEqual(r.returncode, 0, r)
        with open(a, "rb") as fa, open(b, "rb") as fb, open(c, "rb") as fc:
            da, db, dc = fa.read(), fb.read(), fc.read()
        self.assertEqual(da, db)
        self.assertNotEqual(da, dc)
        self.assertEqual(len(da), len(dc))  # same shape, different costs
        for name in ("forward_targets", "reverse_arcs"):
            self.assertEqual(payload(da, name), payload(dc, name))
        self.assertNotEqual(payload(da, "c1"), payload(dc, "c1"))


class ChecksumLevel(GridTest):
    def test_flipped_byte_in_each_section(self):
        good = self.grid_bytes()
        table = [e for e in entries(good) if e["stored_length"] > 0]
        self.assertEqual(len(table), 10)
        for e in table:
            with self.subTest(section=e["name"]):
                data = bytearray(good)
                data[e["offset"] + e["stored_length"] // 2] ^= 0xFF
                path = self.write("flip-%s.mosb" % e["name"], data)
                self.assert_fail(path, "checksums", "section '%s': [checksum] mismatch" % e["name"])
                self.assert_fail(path, "full", "section '%s': [checksum]" % e["name"])
                # The open (header level) reads no payload beyond the CSR end points, which the
                # middle byte is not: the damage goes unnoticed there.
                self.assert_ok(path, "header")

    def test_flipped_metadata_byte_is_found_lazily(self):
        # Metadata is parsed on first use, not at open: header level passes, checksums names
        # the section, structure reports the parse error; inspect, which reads the metadata to
        # print it, fails on the parse, and with --verify on the checksum.
        data = self.grid_bytes()
        e = entry(data, "metadata")
        middle = e["offset"] + e["stored_length"] // 2
        self.assertTrue(chr(data[middle]).isalpha())  # inside a key, see below
        data[middle] ^= 0xFF
        path = self.write("meta.mosb", data)
        self.assert_ok(path, "header")
        self.assert_fail(path, "checksums", "section 'metadata': [checksum] mismatch")
        self.assert_fail(path, "structure", "section 'metadata': [metadata]", "invalid key")
        r = self.mosb("inspect", path)
        line = self.assert_one_line_error(r)
        self.assertEqual(r.stdout, "")
        self.assertTrue(line.startswith("mosb: %s: section 'metadata': metadata line " % path), r)
        self.assertIn("invalid key", line)
        r = self.mosb("inspect", "--verify", "checksums", path)
        line = self.assert_one_line_error(r)
        self.assertEqual(r.stdout, "")
        self.assertTrue(line.startswith(
            "mosb: %s: file is damaged: section 'metadata': [checksum] mismatch" % path), r)


class StructureLevel(GridTest):
    def check_structure_error(self, data, section, rule, *details):
        path = self.write("bad.mosb", data)
        line = self.assert_fail(path, "structure", "section '%s': [%s]" % (section, rule), *details)
        self.assert_fail(path, "full", "section '%s': [%s]" % (section, rule))
        self.assert_ok(path, "checksums")  # proves the checksums were recomputed correctly
        self.assert_ok(path, "header")
        return line

    def test_decreasing_forward_offset(self):
        data = self.grid_bytes()
        patch_values(data, "forward_offsets", "<Q", 1, M)
        self.check_structure_error(data, "forward_offsets", "offsets-monotonic",
                                   "decrease at vertex 1")

    def test_decreasing_reverse_offset(self):
        data = self.grid_bytes()
        roff = values(data, "reverse_offsets", "Q")
        patch_values(data, "reverse_offsets", "<Q", 3, roff[4] + 1)
        self.check_structure_error(data, "reverse_offsets", "offsets-monotonic",
                                   "decrease at vertex 3")

    def test_target_out_of_range(self):
        data = self.grid_bytes()
        patch_values(data, "forward_targets", "<I", 5, N)
        self.check_structure_error(data, "forward_targets", "target-range",
                                   "arc 5 is vertex %d, not below n = %d" % (N, N))

    def test_reverse_arc_names_wrong_arc(self):
        data = self.grid_bytes()
        rarcs = values(data, "reverse_arcs", "I")
        targets = values(data, "forward_targets", "I")
        wrong = next(a for a in range(M) if targets[a] != targets[rarcs[0]])
        patch_values(data, "reverse_arcs", "<I", 0, wrong)
        self.check_structure_error(data, "reverse_arcs", "reverse-transpose",
                                   "entry 0 ", "names arc %d" % wrong)

    def test_reverse_arcs_not_ascending(self):
        data = self.grid_bytes()
        roff = values(data, "reverse_offsets", "Q")
        rarcs = values(data, "reverse_arcs", "I")
        rsrc = values(data, "reverse_sources", "I")
        v = next(v for v in range(N) if roff[v + 1] - roff[v] >= 2)
        j = roff[v]
        body = bytearray(payload(data, "reverse_arcs"))
        struct.pack_into("<II", body, 4 * j, rarcs[j + 1], rarcs[j])
        write_payload(data, "reverse_arcs", body)
        body = bytearray(payload(data, "reverse_sources"))
        struct.pack_into("<II", body, 4 * j, rsrc[j + 1], rsrc[j])
        write_payload(data, "reverse_sources", body)
        self.check_structure_error(data, "reverse_arcs", "reverse-transpose",
                                   "entry %d " % (j + 1), "(%d then %d)" % (rarcs[j + 1], rarcs[j]))

    def test_reverse_source_out_of_range(self):
        data = self.grid_bytes()
        patch_values(data, "reverse_sources", "<I", 7, N + 3)
        self.check_structure_error(data, "reverse_sources", "source-range",
                                   "entry 7 is vertex %d" % (N + 3))

    def test_reverse_source_wrong_vertex(self):
        data = self.grid_bytes()
        rsrc = values(data, "reverse_sources", "I")
        patch_values(data, "reverse_sources", "<I", 0, (rsrc[0] + 1) % N)
        # The transpose check finds the disagreement while walking reverse_arcs and names that
        # section (the two columns are checked as one relation).
        self.check_structure_error(data, "reverse_arcs", "reverse-transpose",
                                   "entry 0 ", "leaves vertex %d" % ((rsrc[0] + 1) % N),
                                   "the forward CSR disagrees")

    def test_query_endpoint_out_of_range(self):
        data = self.grid_bytes()
        patch_values(data, "default", "<I", 1, N)
        self.check_structure_error(data, "default", "query-range",
                                   "endpoint 1 is vertex %d" % N)

    def check_metadata_line_replaced(self, old, new, rule, *details):
        data = self.grid_bytes()
        body = bytes(payload(data, "metadata"))
        self.assertEqual(body.count(old), 1)
        write_payload(data, "metadata", body.replace(old, new))
        self.check_structure_error(data, "metadata", rule, *details)

    def test_metadata_view_names_missing_objective(self):
        self.check_metadata_line_replaced(b"view.Grid_3.objectives=c1,c2,c3\n",
                                          b"view.Grid_3.objectives=c1,c2,c9\n", "metadata-views",
                                          "'c9'")

    def test_metadata_view_names_missing_query_set(self):
        self.check_metadata_line_replaced(b"view.Grid_2.queries=default\n",
                                          b"view.Grid_2.queries=defaulx\n", "metadata-views",
                                          "'defaulx'")

    def test_metadata_keys_unsorted(self):
        data = self.grid_bytes()
        body = bytes(payload(data, "metadata"))
        self.assertTrue(body.startswith(b"benchmark="))
        write_payload(data, "metadata", b"zenchmark=" + body[len(b"benchmark="):])
        self.check_structure_error(data, "metadata", "metadata", "line 2",
                                   "not in sorted order")

    # generate grid writes only u8 costs; an f32 column is made by relocating a cost section.
    def f32_grid(self, bad_value):
        data = self.grid_bytes()
        costs = [float(c) + 0.5 for c in values(data, "c2", "B")]
        if bad_value is not None:
            costs[11] = bad_value
        relocate_as_f32(data, "c2", costs)
        return data

    def test_f32_cost_control(self):
        # The relocation itself yields a valid file, so the two tests below test only the value.
        path = self.write("f32.mosb", self.f32_grid(None))
        self.assert_ok(path, "full")
        info = json.loads(self.mosb("inspect", "--json", path).stdout)
        self.assertEqual([o["type"] for o in info["objectives"]], ["u8", "f32", "u8"])

    def test_float_cost_nan(self):
        self.check_structure_error(self.f32_grid(math.nan), "c2", "cost-finite", "arc 11")

    def test_float_cost_infinite(self):
        self.check_structure_error(self.f32_grid(math.inf), "c2", "cost-finite", "arc 11")

    def test_float_cost_negative(self):
        self.check_structure_error(self.f32_grid(-1.0), "c2", "cost-nonnegative", "arc 11")


class OpenErrors(GridTest):
    """Failures at open: exit 1, one line naming the file, from both verify and inspect."""

    def check_open_error(self, path, *expected):
        for level in ("header", "full"):
            self.assert_fail(path, level, *expected)
        r = self.mosb("inspect", path)
        line = self.assert_one_line_error(r, *expected)
        self.assertEqual(r.stdout, "", r)
        self.assertTrue(line.startswith("mosb: " + path + ": "), r)

    def corrupt(self, change, *expected):
        data = self.grid_bytes()
        data = change(data) or data
        self.check_open_error(self.write("bad.mosb", data), *expected)

    def test_truncated(self):
        size = header(self.grid_bytes())["file_size"]
        self.corrupt(lambda d: d[:-64], "truncated",
                     "header says %d bytes, file has %d" % (size, size - 64))

    def test_truncated_below_header(self):
        self.corrupt(lambda d: d[:100], "not a mosb file", "100 bytes")

    def test_extended(self):
        self.corrupt(lambda d: d + bytes(64), "extended")

    def test_wrong_magic(self):
        def change(d):
            d[0:8] = b"GARBAGE!"
        self.corrupt(change, "not a mosb file (wrong magic)")

    def test_byte_swapped_magic(self):
        def change(d):
            d[0:8] = MAGIC[::-1]
        self.corrupt(change, "byte-swapped")

    def test_byte_swapped_byte_order_mark(self):
        def change(d):
            set_header(d, byte_order_mark=0x04030201)
        self.corrupt(change, "byte-swapped", "byte-order mark")

    def test_seven_bit_transfer(self):
        def change(d):
            d[0] &= 0x7F
        self.corrupt(change, "7-bit transfer")

    def test_crlf_to_lf(self):
        self.corrupt(lambda d: bytearray(bytes(d).replace(b"\r\n", b"\n")), "text-mode")

    def test_lf_to_crlf(self):
        self.corrupt(lambda d: bytearray(bytes(d).replace(b"\n", b"\r\n")), "text-mode")

    def test_newer_major_version(self):
        self.corrupt(lambda d: set_header(d, version_major=2),
                     "prepared with format 2.0", "reads format 1.x")

    def test_unknown_file_kind(self):
        self.corrupt(lambda d: set_header(d, file_kind=2), "file kind 2")

    def test_unknown_required_feature(self):
        def change(d):
            set_header(d, required_features=1 << 5)
            reseal(d)
        self.corrupt(change, "feature bit 5")

    def test_unknown_optional_feature_is_accepted(self):
        data = self.grid_bytes()
        set_header(data, optional_features=1 << 5)
        reseal(data)
        self.assert_ok(self.write("opt.mosb", data), "full")

    def test_overlapping_sections(self):
        def change(d):
            set_entry(d, "c2", offset=entry(d, "c1")["offset"])
            reseal(d)
        self.corrupt(change, "overlap", "'c1'", "'c2'")

    def test_misaligned_offset(self):
        def change(d):
            set_entry(d, "c3", offset=entry(d, "c3")["offset"] + 8)
            reseal(d)
        self.corrupt(change, "section 'c3'", "not 64-byte aligned")

    def test_payload_outside_data_area(self):
        def change(d):
            set_entry(d, "c3", offset=header(d)["table_offset"])
            reseal(d)
        self.corrupt(change, "section 'c3'", "outside the data area")

    def test_arc_count_disagrees(self):
        def change(d):
            set_header(d, arc_count=M - 1)
            reseal(d)
        self.corrupt(change, "section 'forward_targets'",
                     "has %d rows, but the arc count is %d" % (M, M - 1))

    def test_vertex_count_disagrees(self):
        def change(d):
            set_header(d, vertex_count=N + 1)
            reseal(d)
        self.corrupt(change, "section 'forward_offsets'", "has %d rows" % (N + 1),
                     "vertex count + 1 is %d" % (N + 2))

    def test_objective_count_disagrees(self):
        def change(d):
            set_header(d, objective_count=2)
            reseal(d)
        self.corrupt(change, "declares 2 objectives", "3 cost sections")

    def test_section_table_past_end(self):
        self.corrupt(lambda d: set_header(d, section_count=header(d)["section_count"] + 1),
                     "section table", "does not end at the end of the file")

    def test_section_table_misaligned(self):
        self.corrupt(lambda d: set_header(d, table_offset=header(d)["table_offset"] + 8),
                     "section table offset", "64-aligned")

    def test_bad_header_checksum(self):
        def change(d):
            d[80] ^= 0x01  # a reserved byte: only the checksum protects it
        self.corrupt(change, "header checksum mismatch")

    def test_damaged_table_entry(self):
        def change(d):
            d[entry(d, "c1")["pos"] + 56] ^= 0x01  # c1's section checksum, table not resealed
        self.corrupt(change, "header checksum mismatch")

    def test_bad_section_name(self):
        def change(d):
            d[entry(d, "c1")["pos"] + 1] = ord("/")
            reseal(d)
        self.corrupt(change, "section #6", "invalid name")

    def test_unknown_element_type(self):
        def change(d):
            set_entry(d, "c1", element_type=11)
            reseal(d)
        self.corrupt(change, "section 'c1'", "unknown element type 11")

    def test_signed_cost_type(self):
        def change(d):
            set_entry(d, "c1", element_type=5)  # i8: same size as u8, so the length still fits
            reseal(d)
        self.corrupt(change, "section 'c1'", "cost type i8 is not unsigned or float")

    def test_duplicate_objective_name(self):
        def change(d):
            e = entry(d, "c2")
            d[e["pos"]:e["pos"] + 2] = b"c1"
            reseal(d)
        self.corrupt(change, "section 'c1'", "a second cost section of that name")

    def test_forward_offsets_end_point(self):
        def change(d):
            patch_values(d, "forward_offsets", "<Q", N, M - 1)
        self.corrupt(change, "section 'forward_offsets'", "not from 0 to the arc count %d" % M)

    def test_empty_file(self):
        self.check_open_error(self.write("empty.mosb", b""), "not a mosb file", "0 bytes")

    def test_directory(self):
        path = self.path("a-directory")
        os.mkdir(path)
        self.check_open_error(path, "not a regular file")

    def test_missing_file(self):
        self.check_open_error(self.path("missing.mosb"), "cannot open", "No such file")


class SectionsFoundByKind(GridTest):
    def test_renamed_structural_sections(self):
        # §4: sections are found by kind; a reader must not require the writer's names.
        data = self.grid_bytes()
        for old, new in (("metadata", "meta"), ("forward_offsets", "fo"), ("reverse_arcs", "ra")):
            pos = entry(data, old)["pos"]
            data[pos:pos + 24] = new.encode().ljust(24, b"\0")
        reseal(data)
        path = self.write("renamed.mosb", data)
        self.assert_ok(path, "full")
        info = json.loads(self.mosb("inspect", "--json", path).stdout)
        self.assertEqual(info["metadata"]["benchmark"], "Grid-5x4")
        self.assertEqual([s["kind"] for s in info["sections"] if s["name"] == "ra"],
                         ["reverse_arcs"])

    def test_unknown_kind_is_ignored(self):
        data = self.grid_bytes()
        set_entry(data, "default", kind=99)
        reseal(data)
        path = self.write("kind99.mosb", data)
        # The view still names query set 'default', which is now no queries section.
        self.assert_ok(path, "checksums")
        self.assert_fail(path, "structure", "section 'metadata': [metadata-views]", "'default'")
        # A plain inspect shows the table (the unknown kind included) without judging it;
        # verified in full, the broken view makes it refuse the file, naming the problem.
        shown = json.loads(self.ok("inspect", "--json", path).stdout)
        self.assertIn("unknown(99)", [s["kind"] for s in shown["sections"]])
        self.assertIsNone(shown["verified"])
        r = self.mosb("inspect", "--json", "--verify", "full", path)
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual(r.stdout, "", r)
        self.assertIn("file is damaged: section 'metadata': [metadata-views]", r.stderr)


class PackedSections(GridTest):
    """Encoding 1 (zstd) with required bit 0: the open accepts it; verify decodes it first (at
    every level but header, which reads the header and the table alone), and the payload is not
    really zstd here, which is what is being checked.
    """

    def packed(self, name):
        data = self.grid_bytes()
        info = json.loads(self.mosb("inspect", "--json", self.path("g.mosb")).stdout)
        self.plain_digest = info["digest"]
        set_entry(data, name, encoding=1)
        set_header(data, required_features=1)
        reseal(data)
        return self.write("packed.mosb", data)

    def test_packed_cost_column(self):
        path = self.packed("c1")
        self.ok("verify", path, "--level", "header")  # no frame is decoded
        for level in ("checksums", "structure"):
            self.assert_fail(path, level, "section 'c1': stored bytes are not a zstd frame")
        info = json.loads(self.mosb("inspect", "--json", path).stdout)
        self.assertEqual(info["digest"], self.plain_digest)  # encoding and layout ignored (§8)
        self.assertEqual([s["name"] for s in info["sections"] if s["packed"]], ["c1"])

    def test_packed_metadata_cannot_be_inspected(self):
        path = self.packed("metadata")
        self.ok("verify", path, "--level", "header")
        self.assert_fail(path, "checksums",
                         "section 'metadata': stored bytes are not a zstd frame")
        r = self.mosb("inspect", path)
        self.assert_one_line_error(r, "section 'metadata' is zstd-packed")

    def test_zstd_section_without_feature_bit(self):
        data = self.grid_bytes()
        set_entry(data, "c1", encoding=1)
        reseal(data)
        self.assert_fail(self.write("bad.mosb", data), "header", "section 'c1'",
                         "lacks the zstd-sections feature")

    def test_feature_bit_without_zstd_section(self):
        data = self.grid_bytes()
        set_header(data, required_features=1)
        reseal(data)
        self.assert_fail(self.write("bad.mosb", data), "header",
                         "declares zstd-sections but no section is zstd-encoded")

    def test_unknown_encoding(self):
        data = self.grid_bytes()
        set_entry(data, "c1", encoding=5)  # 1-4 are §6's encodings
        reseal(data)
        self.assert_fail(self.write("bad.mosb", data), "header", "section 'c1'",
                         "unknown encoding 5")

    def test_known_encoding_without_its_feature_bit(self):
        data = self.grid_bytes()
        set_entry(data, "c1", encoding=4)
        reseal(data)
        self.assert_fail(self.write("bad.mosb", data), "header", "section 'c1'",
                         "transpose-encoded (encoding 4) but the header lacks the "
                         "transpose-sections feature (bit 3)")


class SpecConformance(GridTest):
    """Cases once found to depart from spec/FORMAT.md, kept as regression tests."""

    def test_metadata_must_be_utf8(self):
        # §7: the metadata payload is UTF-8 text; §9 structure: metadata well-formed (§7).
        # Today Metadata::parse accepts any bytes in a value, verify says OK and
        # `inspect --json` prints the raw byte, which is not valid JSON.
        data = self.grid_bytes()
        body = bytes(payload(data, "metadata"))
        self.assertEqual(body.count(b"=Grid-5x4\n"), 1)
        write_payload(data, "metadata", body.replace(b"=Grid-5x4\n", b"=Grid-5x\xff\n"))
        path = self.write("latin.mosb", data)
        self.assert_ok(path, "checksums")
        self.assert_fail(path, "structure", "section 'metadata': [metadata]")

    def test_inspect_json_is_valid_utf8(self):
        # A file name that is not UTF-8 must still give valid JSON (the byte becomes U+FFFD).
        source = os.fsencode(self.generate())
        path = source.replace(b".mosb", b"\xff.mosb")
        os.rename(source, path)
        completed = subprocess.run([os.fsencode(MOSB), b"inspect", b"--json", path], capture_output=True)
        self.assertEqual(completed.returncode, 0, completed)
        report = json.loads(completed.stdout.decode("utf-8"))  # raises on invalid UTF-8
        self.assertIn("\ufffd", report["file"])

    def test_zstd_section_needs_a_frame(self):
        # §3: for zstd, stored_length "is the frame's length, > 0".
        data = self.grid_bytes()
        set_entry(data, "c1", encoding=1, stored_length=0)
        set_header(data, required_features=1)
        reseal(data)
        self.assert_fail(self.write("empty-frame.mosb", data), "header", "section 'c1'")


class SeveralFiles(GridTest):
    def test_good_then_bad(self):
        good = self.generate()
        data = self.grid_bytes()
        data[0] ^= 0xFF
        bad = self.write("bad.mosb", data)
        r = self.mosb("verify", good, bad)
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual(len(r.stdout.splitlines()), 2, r)
        self.assertTrue(r.stdout.splitlines()[0].startswith("OK   " + good), r)
        self.assertTrue(r.stdout.splitlines()[1].startswith("FAIL " + bad + ": "), r)
        # A failure does not stop the run: the order is kept the other way round too.
        r = self.mosb("verify", bad, good)
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual([line[:4] for line in r.stdout.splitlines()], ["FAIL", "OK  "], r)

    def test_all_good(self):
        a, b = self.generate("a.mosb"), self.generate("b.mosb")
        r = self.mosb("verify", "--level", "checksums", a, b)
        self.assertEqual(r.returncode, 0, r)
        self.assertEqual([line[:2] for line in r.stdout.splitlines()], ["OK", "OK"], r)


class UsageErrors(GridTest):
    """Every usage error: exit 2, nothing on stdout, exactly one line on stderr starting 'mosb:'."""

    def check_usage_error(self, *args):
        before = sorted(os.listdir(self.dir))
        r = self.mosb(*args)
        line = self.assert_one_line_error(r, code=2)
        self.assertEqual(r.stdout, "", r)
        self.assertTrue(line.startswith("mosb: "), r)
        self.assertEqual(sorted(os.listdir(self.dir)), before, "a usage error wrote files")
        return r

    def test_no_arguments(self):
        self.check_usage_error()

    def test_no_subcommand_of_a_group(self):
        r = self.check_usage_error("convert")
        self.assertIn("convert", r.stderr)

    def test_unknown_subcommand(self):
        self.check_usage_error("frobnicate", "x.mosb")

    def test_a_mistyped_command_is_named_with_the_one_meant(self):
        for args, expected in ((["rnu"], "mosb: unknown command 'rnu' (did you mean 'run'?)"),
                               (["generate", "gird"], "mosb: generate: unknown command 'gird' "
                                                      "(did you mean 'grid'?)"),
                               (["solutions", "inspcet", "x.sol"],
                                "mosb: solutions: unknown command 'inspcet' (did you mean "
                                "'inspect'?)"),
                               (["solutions", "show", "x.sol"],
                                "mosb: solutions: unknown command 'show' (the commands: import, "
                                "export, inspect, verify, compare, merge, reference)")):
            with self.subTest(args=args):
                r = self.check_usage_error(*args)
                self.assertTrue(r.stderr.startswith(expected), r.stderr)

    def test_unknown_option(self):
        r = self.check_usage_error("inspect", "--frobnicate", "x.mosb")
        self.assertIn("--frobnicate", r.stderr)

    def test_missing_required_option(self):
        r = self.check_usage_error("convert", "dimacs", "-o", "x.mosb")
        self.assertIn("--gr", r.stderr)
        self.assertIn("convert dimacs", r.stderr)

    def test_missing_output(self):
        # Found after parsing (--output or --suite): still a usage error.
        r = self.check_usage_error(*GRID)
        self.assertIn("--output", r.stderr)

    def test_bad_level(self):
        path = self.generate()
        r = self.check_usage_error("verify", path, "--level", "bogus")
        self.assertIn("bogus", r.stderr)

    def test_bad_number(self):
        self.check_usage_error("generate", "grid", "--width", "many", "-o", "w.mosb")

    def test_width_out_of_range(self):
        self.check_usage_error("generate", "grid", "--width", "0", "-o", "w.mosb")

    def test_verify_without_files(self):
        self.check_usage_error("verify")

    def test_excluded_options(self):
        self.check_usage_error("generate", "grid", "--suite", "s", "--width", "10")

    def test_queries_need_a_destination(self):
        path = self.generate()
        r = self.check_usage_error("queries", "generate", path, "--set", "r")
        self.assertIn("--in-place", r.stderr)

    def test_runtime_error_is_exit_1(self):
        r = self.mosb("inspect", self.write("junk.mosb", b"not a mosb file"))
        self.assertTrue(self.assert_one_line_error(r).startswith("mosb: "), r)


class VersionAndHelp(GridTest):
    def test_version(self):
        with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "CMakeLists.txt")) as f:
            version = re.search(r"project\(mosb VERSION ([0-9.]+)", f.read()).group(1)
        for flag in ("--version", "-V"):
            r = self.mosb(flag)
            self.assertEqual(r.returncode, 0, r)
            self.assertEqual(r.stdout.splitlines(), ["mosb " + version], r)

    def test_help_documents_exit_codes(self):
        r = self.mosb("--help")
        self.assertEqual(r.returncode, 0, r)
        text = " ".join(r.stdout.split())
        self.assertIn("Exit status: 0 success; 1 failure while running", text)
        self.assertIn("2 usage error", text)

    def commands(self, prefix=()):
        """Every command path below `prefix`, read from --help's Subcommands lists."""
        r = self.mosb(*prefix, "--help")
        self.assertEqual(r.returncode, 0, r)
        if "Subcommands:" not in r.stdout:
            return []
        found = []
        for line in r.stdout.split("Subcommands:")[1].splitlines():
            m = re.match(r"  (\S+)\s", line)
            if m:
                path = prefix + (m.group(1),)
                found += [path] + self.commands(path)
        return found

    def test_bash_completion_offers_every_command_and_option(self):
        """`mosb completion bash`, sourced in bash, completes each level's subcommands and each
        command's options, as --help lists them."""
        script = self.write("mosb.bash", self.mosb("completion", "bash").stdout)
        commands = self.commands()
        self.assertIn(("solutions", "import"), commands)
        cases = [("mosb ru", "run"), ("mosb solutions imp", "import"),
                 ("mosb run --time-l", "--time-limit"), ("mosb store pull --no-r", "--no-references"),
                 ("mosb experiment run exp.toml --ex", "--executable")]
        for path in commands:  # every command completes from its first three letters
            cases.append(("mosb " + " ".join(path[:-1] + (path[-1][:3],)), path[-1]))
        lines = "".join('COMP_WORDS=(%s); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _mosb; '
                        'echo "${COMPREPLY[*]}"\n' % typed for typed, _ in cases)
        r = subprocess.run(["bash", "-c", "source %s\n%s" % (script, lines)], capture_output=True,
                           text=True, timeout=60)
        self.assertEqual(r.returncode, 0, r.stderr)
        for (typed, wanted), offered in zip(cases, r.stdout.splitlines()):
            self.assertIn(wanted, offered.split(), typed)
        self.assertEqual(len(r.stdout.splitlines()), len(cases))
        self.ok("completion", "bash", "-o", self.path("again.bash"))
        self.assertEqual(mosbtest.read(self.path("again.bash")), mosbtest.read(script))
        self.assertEqual(self.mosb("completion", "zsh").returncode, 2)

    def test_man_page_has_every_command_and_renders_without_warnings(self):
        page = self.mosb("man").stdout
        for path in self.commands():
            self.assertIn('.SS "mosb %s' % " ".join(path), page)
        self.assertIn("\\-\\-time\\-limit", page)
        self.assertIn(".SH \"EXIT STATUS\"", page)
        # groff (groff-base, a test dependency) reads it with every warning on: none.
        r = subprocess.run(["groff", "-man", "-Tutf8", "-ww"], input=page, capture_output=True,
                           text=True, timeout=60)
        self.assertEqual((r.returncode, r.stderr), (0, ""))
        self.assertIn("--time-limit", r.stdout.replace("\u2010", "-").replace("\u2212", "-"))
        self.assertIn("ε", r.stdout)

    def test_one_name_for_the_instance_argument(self):
        for command in (["inspect"], ["verify"], ["stats"], ["export", "dimacs"], ["queries", "import"],
                        ["queries", "generate"]):
            r = self.mosb(*command, "--help")
            self.assertEqual(r.returncode, 0, r)
            positionals = r.stdout.split("Positionals:")[1].split("Options:")[0]
            self.assertEqual(positionals.split()[0], "INSTANCE", command)
            for other in ("\n  FILE ", "\n  instance ", "\n  file "):
                self.assertNotIn(other, positionals, command)


class JsonReports(GridTest):
    """--json on every reporting command: one JSON object on stdout."""

    def json_of(self, *args, code=0):
        r = self.mosb(*args, "--json")
        self.assertEqual(r.returncode, code, r)
        return json.loads(r.stdout)

    def test_generate_and_convert(self):
        out = self.path("j.mosb")
        report = self.json_of(*GRID, "-o", out)
        self.assertEqual(report["file"], out)
        self.assertEqual(report["vertices"], 5 * 4 + 2)
        self.assertEqual(report["objectives"], 3)
        self.assertEqual(report["digest"], self.json_of("inspect", out)["digest"])
        with open(self.path("g.gr"), "w") as f:
            f.write("p sp 3 2\na 1 2 5\na 2 3 7\n")
        report = self.json_of("convert", "dimacs", "--gr", self.path("g.gr"), "-o", self.path("d.mosb"))
        self.assertEqual((report["vertices"], report["arcs"], report["objectives"]), (3, 2, 1))

    def test_verify(self):
        good = self.generate()
        data = self.grid_bytes()
        data[0] ^= 0xFF
        bad = self.write("bad.mosb", data)
        report = self.json_of("verify", good, bad, code=1)
        self.assertFalse(report["ok"])
        self.assertEqual(report["level"], "full")
        self.assertEqual([f["ok"] for f in report["files"]], [True, False])
        self.assertEqual(report["files"][0]["file"], good)
        self.assertIn("problem", report["files"][1])
        self.assertTrue(self.json_of("verify", good)["ok"])

    def test_queries_and_export(self):
        g = self.generate()
        report = self.json_of("queries", "generate", g, "--set", "r", "--count", "5", "-o", self.path("q.mosb"))
        self.assertEqual((report["file"], report["set"], report["queries"]), (self.path("q.mosb"), "r", 5))
        report = self.json_of("export", "dimacs", self.path("q.mosb"), "-o", self.path("text"))
        self.assertEqual(report["directory"], self.path("text"))
        self.assertTrue(all(os.path.exists(p) for p in report["wrote"]), report)
        self.assertIn(os.path.join(self.path("text"), "Grid-5x4-r.queries"), report["wrote"])

    def test_suite(self):
        report = self.json_of("generate", "grid", "--suite", self.path("s"), "--sizes", "3,4")
        self.assertEqual([i["name"] for i in report["instances"]],
                         ["Grid-3x3", "Grid-3x4", "Grid-4x3", "Grid-4x4"])
        self.assertEqual(report["instances"][0]["size"], os.path.getsize(self.path("s/Grid-3x3.mosb")))


class AtomicOutput(GridTest):
    def test_missing_directory(self):
        target = self.path("no-such-dir/out.mosb")
        r = self.mosb(*GRID, "-o", target)
        self.assert_one_line_error(r, target, "no-such-dir")
        self.assertEqual(r.stdout, "", r)
        self.assertEqual(os.listdir(self.dir), [])

    def test_target_is_a_directory(self):
        # Everything is written, then the rename fails: the temporary file must be removed.
        target = self.path("occupied")
        os.makedirs(os.path.join(target, "inside"))
        r = self.mosb(*GRID, "-o", target)
        self.assert_one_line_error(r, target)
        self.assertEqual(sorted(os.listdir(self.dir)), ["occupied"])
        self.assertEqual(os.listdir(target), ["inside"])

    def test_replaces_existing_file(self):
        target = self.write("g.mosb", b"old contents")
        self.generate("g.mosb")
        self.assert_ok(target, "full")
        self.assertEqual(os.listdir(self.dir), ["g.mosb"])

    def test_relative_output_in_working_directory(self):
        r = self.mosb(*GRID, "-o", "rel.mosb")
        self.assertEqual(r.returncode, 0, r)
        self.assertEqual(os.listdir(self.dir), ["rel.mosb"])


class StrictOptions(CliTest):
    """Issue 20 section 5: every unsigned-integer, real and epsilon option parsed strictly (exit
    2, the option named); control characters refused in free-text options."""

    def refused(self, args, *expected):
        r = self.mosb(*args)
        self.assert_one_line_error(r, *expected, code=2)
        return r

    def test_unsigned_options_neither_wrap_nor_saturate(self):
        out = self.path("g.mosb")
        grid = ("generate", "grid", "--width", "2", "--height", "2", "-o", out)
        self.refused(grid + ("--seed", "-1"), "--seed", "'-1'", "not an unsigned integer")
        self.refused(grid + ("--seed", "18446744073709551616"), "--seed", "largest allowed")
        self.refused(grid + ("--seed", "+1"), "--seed")
        self.refused(grid + ("--seed", " 1"), "--seed")
        self.refused(("generate", "grid", "--width", "4294967298", "--height", "2", "-o", out),
                     "--width", "largest allowed")
        self.assertFalse(os.path.exists(out))
        self.ok(*grid, "--seed", "18446744073709551615")
        self.refused(("plot", "front", "--solutions", out, "--query", "-1", "-o",
                      self.path("f.svg")), "--query", "not an unsigned integer")
        self.refused(("pack", out, "-o", self.path("p.mosb"), "--level", "-3"), "--level")

    def test_real_and_epsilon_options(self):
        out = self.path("g.mosb")
        self.ok("generate", "grid", "--width", "2", "--height", "2", "-o", out)
        for bad in ("nan", "inf", "-0.5", "abc"):
            self.refused(("plot", "front", "--solutions", out, "--query", "0", "--eps", bad, "-o",
                          self.path("f.svg")), "--eps")

    def test_control_characters_are_refused_in_free_text(self):
        out = self.path("g.mosb")
        self.ok("generate", "grid", "--width", "2", "--height", "2", "-o", out)
        for bad in ("a\nb", "a\x1bb"):
            self.refused(("plot", "correlation", out, "--title", bad, "-o", self.path("c.svg")),
                         "--title", "control character")
        self.assertFalse(os.path.exists(self.path("c.svg")))
        # '<' is fine: escaped in the SVG.
        self.ok("plot", "correlation", out, "--title", "a<b&c", "-o", self.path("c.svg"))
        with open(self.path("c.svg")) as f:
            svg = f.read()
        self.assertIn("a&lt;b&amp;c", svg)
        self.assertNotIn("a<b", svg)


class ManyViewsJsonTest(CliTest):
    """Issue 36 §8: every `--json` report that lists views, on a file of 20,000 views, completes
    and parses (the JSON writer scanned an object's keys for each key it added: 4.6 s for
    `inspect --json`). Not timed here: BENCHMARKS.md has the figures."""

    def test_every_json_report_of_twenty_thousand_views(self):
        views = [arg for i in range(20000) for arg in ("--view", "V%05d=c1,c2" % i)]
        g = self.path("views.mosb")
        written = json.loads(self.ok("generate", "grid", "--width", "3", "--height", "3",
                                     *views, "-o", g, "--json").stdout)
        self.assertEqual(written["vertices"], 11)
        inspect = json.loads(self.ok("inspect", "--json", g).stdout)
        named = [k for k in inspect["metadata"] if re.fullmatch(r"view\.[^.]*\.objectives", k)]
        self.assertEqual(len(named), 20002)  # Grid_2, Grid_3 and the 20,000
        self.assertEqual(inspect["metadata"]["view.V19999.objectives"], "c1,c2")
        stats = json.loads(self.ok("stats", "--json", "--view", "V19999", g).stdout)
        self.assertEqual(stats["view"], "V19999")
        verified = json.loads(self.ok("verify", "--json", "--level", "full", g).stdout)
        self.assertTrue(verified["ok"])
        store = self.path("store")
        self.ok("store", "init", store)
        added = json.loads(self.ok("store", "add", "--json", store, g).stdout)
        self.assertEqual(len(added["added"][0]["views"]), 20002)
        listed = json.loads(self.ok("store", "list", "--json", store).stdout)
        self.assertEqual(listed["entries"][0]["views"][-1], "V19999")
        found = json.loads(self.ok("store", "instance", "--json", store, "V19999").stdout)
        self.assertEqual(found["view"], "V19999")


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
