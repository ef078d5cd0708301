#!/usr/bin/python3
"""Independent reference reader for .mosb instance files (format 1.0).

Written from spec/FORMAT.md alone. Standard library + numpy + xxhash (the
header checksum is an open check, §9 step 5, so the reader refuses to run
without the `xxhash` module; Debian: python3-xxhash).

    inst = open_instance("grid.mosb")
    inst.n, inst.m, inst.version, inst.metadata
    inst.array(inst.section("forward_offsets"))   # zero-copy numpy.memmap
    inst.costs(), inst.queries()
    inst.verify("structure")   # §9 verification levels
"""
import collections
import os
import re
import struct
import sys

import numpy as np

try:
    import xxhash
except ImportError as e:  # §9 step 5 cannot be skipped: refuse to run rather than read unchecked
    raise ImportError("mosb_reader: the xxhash module is required for the header checksum "
                      "(FORMAT.md §9 step 5); install python3-xxhash") from e

MAGIC = b"\x89MOS\r\n\x1a\n"
BOM = 0x01020304
HEADER_SIZE = 128
ENTRY_SIZE = 64
ALIGN = 64
U64_LIMIT = 1 << 64

# §2: everything up to the reserved bytes, then the checksum at 120.
HEADER = struct.Struct("<8sIHHIIQQQQIIQQ40sQ")
# §3
ENTRY = struct.Struct("<24sHBBIQQQQ")

# §5: code -> (name, numpy little-endian dtype)
ELEMENT_TYPES = {
    1: ("u8", "<u1"), 2: ("u16", "<u2"), 3: ("u32", "<u4"), 4: ("u64", "<u8"),
    5: ("i8", "<i1"), 6: ("i16", "<i2"), 7: ("i32", "<i4"), 8: ("i64", "<i8"),
    9: ("f32", "<f4"), 10: ("f64", "<f8"),
}
UNSIGNED_OR_FLOAT = {"u8", "u16", "u32", "u64", "f32", "f64"}

METADATA, FORWARD_OFFSETS, FORWARD_TARGETS = 1, 2, 3
REVERSE_OFFSETS, REVERSE_SOURCES, REVERSE_ARCS = 4, 5, 6
COST, VERTEX_DATA, ARC_DATA, QUERIES = 7, 8, 9, 10
KIND_NAMES = {1: "metadata", 2: "forward_offsets", 3: "forward_targets",
              4: "reverse_offsets", 5: "reverse_sources", 6: "reverse_arcs",
              7: "cost", 8: "vertex_data", 9: "arc_data", 10: "queries"}
STRUCTURAL = (METADATA, FORWARD_OFFSETS, FORWARD_TARGETS,
              REVERSE_OFFSETS, REVERSE_SOURCES, REVERSE_ARCS)
ZSTD_SECTIONS = 1 << 0  # required bit 0 (§6)
KNOWN_REQUIRED_FEATURES = ZSTD_SECTIONS
ID_LIMIT = (1 << 32) - 2  # §4, §9 step 8: n and m at most 2^32-2
VERIFY_LEVELS = ("header", "checksums", "structure", "full")

NAME_RE = re.compile(rb"[A-Za-z0-9_.+-]{1,24}")
KEY_RE = re.compile(r"[A-Za-z0-9_.+-]+")


class FormatError(Exception):
    """The file violates spec/FORMAT.md."""


Section = collections.namedtuple(
    "Section", "index name kind kind_name element_type encoding row_width "
               "row_count offset stored_length checksum dtype")


def _decoded_length(s):
    return s.row_count * s.row_width * np.dtype(s.dtype).itemsize


def parse_metadata(data):
    """§7: bytes -> dict of key -> unescaped value. Raises FormatError."""
    try:
        text = bytes(data).decode("utf-8")
    except UnicodeDecodeError as e:
        raise FormatError("metadata is not valid UTF-8: %s" % e)
    if text and not text.endswith("\n"):
        raise FormatError("metadata: last line does not end in \\n")
    result, previous = {}, None
    for number, line in enumerate(text.split("\n")[:-1], 1):
        key, eq, raw = line.partition("=")
        if not eq or not KEY_RE.fullmatch(key):
            raise FormatError("metadata line %d is not key=value with a valid key: %r"
                              % (number, line))
        kb = key.encode()
        if previous is not None and kb <= previous:
            raise FormatError("metadata line %d: key %r is %s" % (
                number, key, "repeated" if kb == previous else "out of byte order"))
        previous = kb
        value, i = [], 0
        while i < len(raw):
            c = raw[i]
            if c == "\\":
                nxt = raw[i + 1:i + 2]
                if nxt not in ("\\", "n"):
                    raise FormatError("metadata line %d: invalid escape \\%s" % (number, nxt))
                value.append("\\" if nxt == "\\" else "\n")
                i += 2
            else:
                value.append(c)
                i += 1
        result[key] = "".join(value)
    return result


class Instance:
    def __init__(self, path, header, sections):
        self.path = path
        self.version = (header["version_major"], header["version_minor"])
        self.n = header["vertex_count"]
        self.m = header["arc_count"]
        self.required_features = header["required_features"]
        self.optional_features = header["optional_features"]
        self.sections = sections
        self.table_offset = header["table_offset"]
        self._metadata = None

    def section(self, name, kind=None):
        """The entry called `name` (of `kind`, if given; names are unique only per kind)."""
        found = [s for s in self.sections if s.name == name and kind in (None, s.kind)]
        if len(found) != 1:
            raise KeyError("%d sections named %r" % (len(found), name))
        return found[0]

    def of_kind(self, kind):
        return [s for s in self.sections if s.kind == kind]

    def array(self, s):
        """Zero-copy read-only view of a raw section: shape (rows,) or (rows, width)."""
        if isinstance(s, str):
            s = self.section(s)
        if s.encoding != 0:
            raise FormatError("section %r has encoding %d: the file is packed and cannot be "
                              "mapped zero-copy (unpack it first)" % (s.name, s.encoding))
        shape = (s.row_count,) if s.row_width == 1 else (s.row_count, s.row_width)
        if s.row_count == 0:  # mmap cannot map zero bytes; nothing to share anyway
            return np.zeros(shape, dtype=s.dtype)
        return np.memmap(self.path, dtype=s.dtype, mode="r", offset=s.offset, shape=shape)

    @property
    def metadata(self):
        if self._metadata is None:
            self._metadata = parse_metadata(self.array(self.of_kind(METADATA)[0]))
        return self._metadata

    def costs(self):
        """[(objective name, array)] in objective order (table order of the cost sections)."""
        return [(s.name, self.array(s)) for s in self.of_kind(COST)]

    def queries(self):
        return {s.name: self.array(s) for s in self.of_kind(QUERIES)}

    def verify_checksums(self):
        """Recompute every raw section's XXH3-64 (§8); FormatError on a mismatch."""
        for s in self.sections:
            if s.encoding != 0:
                raise FormatError("section %r is packed: its checksum covers the decoded "
                                  "elements, which this reader does not decode" % s.name)
            h = xxhash.xxh3_64_intdigest(np.ascontiguousarray(self.array(s)).tobytes())
            if h != s.checksum:
                raise FormatError("section %r: checksum mismatch: computed %016x, stored %016x"
                                  % (s.name, h, s.checksum))

    def verify_structure(self):
        """The structure level of §9: CSR, transpose, costs, queries, metadata and views."""
        n, m = self.n, self.m
        for kind, ids, bound, what in ((FORWARD_OFFSETS, None, None, None),
                                       (REVERSE_OFFSETS, None, None, None),
                                       (FORWARD_TARGETS, True, n, "target"),
                                       (REVERSE_SOURCES, True, n, "source"),
                                       (REVERSE_ARCS, True, m, "arc id")):
            s = self.of_kind(kind)[0]
            a = self.array(s)
            if ids is None:
                bad = np.flatnonzero(a[1:] < a[:-1])
                if bad.size:
                    raise FormatError("%s: offsets decrease at entry %d" % (s.name, bad[0] + 1))
            else:
                bad = np.flatnonzero(a >= bound)
                if bad.size:
                    raise FormatError("%s: entry %d is %s %d, not < %d"
                                      % (s.name, bad[0], what, a[bad[0]], bound))
        # The reverse CSR must be exactly the transpose (§4): in-arcs of v are the arcs with
        # head v in increasing arc id, and each entry's source is that arc's tail.
        offsets = self.array(self.of_kind(FORWARD_OFFSETS)[0]).astype(np.int64)
        targets = self.array(self.of_kind(FORWARD_TARGETS)[0])
        tails = np.repeat(np.arange(n, dtype=np.uint32), np.diff(offsets))
        expected_arcs = np.argsort(targets, kind="stable").astype(np.uint32)
        expected_offsets = np.concatenate(([0], np.cumsum(np.bincount(targets, minlength=n))))
        for kind, expected in ((REVERSE_OFFSETS, expected_offsets),
                               (REVERSE_ARCS, expected_arcs),
                               (REVERSE_SOURCES, tails[expected_arcs])):
            s = self.of_kind(kind)[0]
            bad = np.flatnonzero(self.array(s) != expected)
            if bad.size:
                raise FormatError("%s: entry %d is not the transpose of the forward CSR"
                                  % (s.name, bad[0]))
        for s in self.of_kind(COST):
            if s.element_type in ("f32", "f64"):
                a = self.array(s)
                bad = np.flatnonzero(~(np.isfinite(a) & (a >= 0)))
                if bad.size:
                    raise FormatError("cost %r: arc %d has %r, not finite and >= 0"
                                      % (s.name, bad[0], a[bad[0]]))
        for s in self.of_kind(QUERIES):
            a = self.array(s)
            bad = np.flatnonzero((a >= n).any(axis=1)) if a.size else []
            if len(bad):
                raise FormatError("query set %r: row %d has a vertex id not < n=%d"
                                  % (s.name, bad[0], n))
        metadata = self.metadata
        objectives = {s.name for s in self.of_kind(COST)}
        query_sets = {s.name for s in self.of_kind(QUERIES)}
        for key, value in metadata.items():
            if not key.startswith("view."):
                continue
            if key.endswith(".objectives"):
                missing = [o for o in value.split(",") if o not in objectives]
                if missing:
                    raise FormatError("metadata %s names objective %r, not a cost section"
                                      % (key, missing[0]))
            elif key.endswith(".queries") and value not in query_sets:
                raise FormatError("metadata %s names query set %r, not a queries section"
                                  % (key, value))
        # §9: keys whose value set §7 / QUERIES.md define.
        closed = {"id_base": ("0", "1"), "family": ("road", "synthetic", "games", "robots")}
        for key, value in metadata.items():
            allowed = closed.get(key)
            if key.startswith("queries.") and key.endswith((".id_base", ".allow_same")):
                allowed = ("0", "1")
            if allowed is not None and value not in allowed:
                raise FormatError("metadata %s is %r, not one of %s" % (key, value, ", ".join(allowed)))
        # §1: bytes of [128, table_offset) that no section stores are zero.
        with open(self.path, "rb") as f:
            data = f.read(self.table_offset)
        used = sorted((s.offset, s.offset + s.stored_length) for s in self.sections if s.stored_length)
        start = 128
        for begin, end in used + [(self.table_offset, self.table_offset)]:
            gap = data[start:begin]
            if gap.strip(b"\0"):
                bad = start + next(i for i, byte in enumerate(gap) if byte)
                raise FormatError("padding byte at offset %d is not zero" % bad)
            start = max(start, end)

    def verify(self, level="full"):
        """§9 verification levels: header (the open checks, already done), checksums,
        structure, full. FormatError on the first problem."""
        if level not in VERIFY_LEVELS:
            raise ValueError("level %r is not one of %s" % (level, ", ".join(VERIFY_LEVELS)))
        if level in ("checksums", "full"):
            self.verify_checksums()
        if level in ("structure", "full"):
            self.verify_structure()

    def content_digest(self):
        """§8: XXH3-128 of the table with encoding, offset, stored_length zeroed."""
        table = b"".join(ENTRY.pack(s.name.encode().ljust(24, b"\0"), s.kind,
                                    _type_code(s.element_type), 0, s.row_width,
                                    s.row_count, 0, 0, s.checksum) for s in self.sections)
        return xxhash.xxh3_128_hexdigest(table)


def _type_code(name):
    return next(c for c, (t, _) in ELEMENT_TYPES.items() if t == name)


def _check_magic(magic):
    if magic == MAGIC:
        return
    if magic == MAGIC[::-1]:
        raise FormatError("bad magic: the file was byte-swapped (magic reversed)")
    if magic[1:4] == b"MOS":
        if magic[0] != 0x89:
            raise FormatError("bad magic: first byte %02x, not 89: high bit stripped "
                              "by a 7-bit transfer" % magic[0])
        raise FormatError("bad magic: line-end bytes %s differ: the file was mangled by a "
                          "text-mode (CRLF/LF) transfer" % magic[4:].hex(" "))
    raise FormatError("bad magic %s: not a mosb file" % magic.hex(" "))


def open_instance(path):
    """Open and validate a .mosb file (§9 steps 1-9)."""
    with open(path, "rb") as f:
        actual_size = os.fstat(f.fileno()).st_size
        head = f.read(HEADER_SIZE)
        # 1. length, magic, byte-order mark
        if actual_size < HEADER_SIZE:
            raise FormatError("file is %d bytes, shorter than the %d-byte header"
                              % (actual_size, HEADER_SIZE))
        fields = HEADER.unpack(head)
        h = dict(zip("magic byte_order_mark version_major version_minor header_size "
                     "file_kind required_features optional_features file_size table_offset "
                     "section_count objective_count vertex_count arc_count reserved "
                     "header_checksum".split(), fields))
        _check_magic(h["magic"])
        if h["byte_order_mark"] != BOM:
            raise FormatError("byte-order mark is %08x, expected 01020304%s" % (
                h["byte_order_mark"],
                " (written big-endian)" if h["byte_order_mark"] == 0x04030201 else ""))
        # 2. version, header size, file kind
        if h["version_major"] != 1:
            raise FormatError("prepared with format %d.%d, this reader reads 1.x"
                              % (h["version_major"], h["version_minor"]))
        if h["header_size"] != HEADER_SIZE:
            raise FormatError("header_size is %d, expected 128" % h["header_size"])
        if h["file_kind"] != 1:
            # Kind 2 (solution files, SOLUTIONS.md) is a valid 1.1 kind this instance reader
            # refuses by name, as a caller's mistake rather than damage.
            raise FormatError("file_kind is %d%s, expected 1 (graph instance)" % (
                h["file_kind"], " (solution file)" if h["file_kind"] == 2 else ""))
        # 3. file size
        if h["file_size"] != actual_size:
            raise FormatError("file is %s: header says %d bytes, file has %d" % (
                "truncated" if actual_size < h["file_size"] else "extended",
                h["file_size"], actual_size))
        # 4. table bounds
        to, count = h["table_offset"], h["section_count"]
        if to % ALIGN or to < HEADER_SIZE or to + ENTRY_SIZE * count != h["file_size"]:
            raise FormatError("section table at %d with %d entries does not end the "
                              "%d-byte file on a 64-byte boundary after the header"
                              % (to, count, h["file_size"]))
        f.seek(to)
        table = f.read(ENTRY_SIZE * count)
    # 5. header checksum
    got = xxhash.xxh3_64_intdigest(head[:120] + table)
    if got != h["header_checksum"]:
        raise FormatError("header checksum mismatch: computed %016x, stored %016x"
                          % (got, h["header_checksum"]))
    # 6. required features (encodings are refused later, by array())
    unknown = h["required_features"] & ~KNOWN_REQUIRED_FEATURES
    if unknown:
        bits = [b for b in range(64) if unknown >> b & 1]
        raise FormatError("unknown required feature bit(s) %s" % bits)
    # 7. entries
    sections = []
    for i in range(count):
        raw_name, kind, etype, enc, width, rows, off, stored, csum = ENTRY.unpack_from(
            table, i * ENTRY_SIZE)
        name = raw_name.rstrip(b"\0")
        where = "section %d (%r)" % (i, name.decode("ascii", "replace"))
        if not NAME_RE.fullmatch(name):
            raise FormatError("%s: name is not 1-24 bytes of [A-Za-z0-9_.+-] padded "
                              "with NUL" % where)
        if etype not in ELEMENT_TYPES:
            raise FormatError("%s: invalid element type %d" % (where, etype))
        if enc not in (0, 1):
            raise FormatError("%s: invalid encoding %d" % (where, enc))
        if width < 1:
            raise FormatError("%s: row_width is 0" % where)
        tname, dtype = ELEMENT_TYPES[etype]
        s = Section(i, name.decode("ascii"), kind, KIND_NAMES.get(kind, "unknown"), tname,
                    enc, width, rows, off, stored, csum, dtype)
        length = _decoded_length(s)
        if length >= U64_LIMIT:
            raise FormatError("%s: decoded size %d overflows u64" % (where, length))
        if enc == 0 and stored != length:
            raise FormatError("%s: raw stored_length %d != rows*width*size %d"
                              % (where, stored, length))
        if enc == 1 and not h["required_features"] & ZSTD_SECTIONS:
            raise FormatError("%s: zstd encoding but required bit 0 (zstd-sections) "
                              "is not set" % where)
        if off % ALIGN or off < HEADER_SIZE or off + stored > to:
            raise FormatError("%s: payload [%d, %d) must start 64-aligned and lie in "
                              "[128, table_offset=%d)" % (where, off, off + stored, to))
        sections.append(s)
    # §6: bit 0 is set if and only if some section is zstd-encoded; both mismatches are refused.
    if h["required_features"] & ZSTD_SECTIONS and not any(s.encoding == 1 for s in sections):
        raise FormatError("required bit 0 (zstd-sections) is set but no section is "
                          "zstd-encoded")
    spans = sorted((s.offset, s.offset + s.stored_length, s.name)
                   for s in sections if s.stored_length)
    for (a0, a1, an), (b0, b1, bn) in zip(spans, spans[1:]):
        if b0 < a1:
            raise FormatError("payloads of %r [%d, %d) and %r [%d, %d) overlap"
                              % (an, a0, a1, bn, b0, b1))
    # 8. kinds, types, widths, counts
    n, m = h["vertex_count"], h["arc_count"]
    if n > ID_LIMIT or m > ID_LIMIT:
        raise FormatError("n=%d or m=%d too large (both must be at most 2^32-2)" % (n, m))
    expect = {  # kind: (allowed types or None, width or None, rows or None)
        METADATA: ({"u8"}, 1, None), FORWARD_OFFSETS: ({"u64"}, 1, n + 1),
        FORWARD_TARGETS: ({"u32"}, 1, m), REVERSE_OFFSETS: ({"u64"}, 1, n + 1),
        REVERSE_SOURCES: ({"u32"}, 1, m), REVERSE_ARCS: ({"u32"}, 1, m),
        COST: (UNSIGNED_OR_FLOAT, 1, m), VERTEX_DATA: (None, None, n),
        ARC_DATA: (None, None, m), QUERIES: ({"u32"}, 2, None)}
    seen = set()
    for s in sections:
        if (s.kind, s.name) in seen:
            raise FormatError("two sections of kind %d named %r" % (s.kind, s.name))
        seen.add((s.kind, s.name))
        if s.kind not in expect:
            continue  # unknown kinds are ignored (§4)
        types, width, rows = expect[s.kind]
        if types is not None and s.element_type not in types:
            raise FormatError("%s section %r has type %s, expected %s"
                              % (s.kind_name, s.name, s.element_type, "/".join(sorted(types))))
        if width is not None and s.row_width != width:
            raise FormatError("%s section %r has width %d, expected %d"
                              % (s.kind_name, s.name, s.row_width, width))
        if rows is not None and s.row_count != rows:
            raise FormatError("%s section %r has %d rows, expected %d (n=%d, m=%d)"
                              % (s.kind_name, s.name, s.row_count, rows, n, m))
    for kind in STRUCTURAL:
        found = sum(s.kind == kind for s in sections)
        if found != 1:
            raise FormatError("%d %s sections, expected exactly one" % (found, KIND_NAMES[kind]))
    costs = sum(s.kind == COST for s in sections)
    if costs != h["objective_count"]:
        raise FormatError("objective_count is %d but there are %d cost sections"
                          % (h["objective_count"], costs))
    inst = Instance(path, h, sections)
    # 9. CSR end points (raw sections only; a packed one would need decoding)
    for kind in (FORWARD_OFFSETS, REVERSE_OFFSETS):
        s = inst.of_kind(kind)[0]
        if s.encoding == 0:
            a = inst.array(s)
            if a[0] != 0 or a[n] != m:
                raise FormatError("%s[0] = %d and [n] = %d; expected 0 and m = %d"
                                  % (s.kind_name, a[0], a[n], m))
    return inst


def main(argv):
    level = "header"
    if len(argv) == 4 and argv[2] == "--level" and argv[3] in VERIFY_LEVELS:
        level = argv[3]
    elif len(argv) != 2:
        sys.exit("usage: mosb_reader.py FILE.mosb [--level %s]" % "|".join(VERIFY_LEVELS))
    try:
        inst = open_instance(argv[1])
        inst.verify(level)
    except FormatError as e:
        sys.exit("%s: %s" % (argv[1], e))
    print("n=%d m=%d version=%d.%d sections=%d" % (inst.n, inst.m, inst.version[0],
                                                     inst.version[1], len(inst.sections)))
    for s in inst.sections:
        print("  %-24s kind=%-2d %-15s %-3s enc=%d width=%d rows=%d offset=%d stored=%d "
              "checksum=%016x" % (s.name, s.kind, s.kind_name, s.element_type, s.encoding,
                                  s.row_width, s.row_count, s.offset, s.stored_length,
                                  s.checksum))


if __name__ == "__main__":
    main(sys.argv)
