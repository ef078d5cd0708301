#!/usr/bin/python3
"""Compare a .mosb file, read by mosb_reader, with a JSON dump written by the C++ code.

    /usr/bin/python3 compare_dump.py FILE.mosb DUMP.json

Exit 0 and print "OK ..." when every field and value agrees; exit 1 on the first
mismatch (or when the file cannot be read); exit 2 on bad usage.
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mosb_reader import FormatError, METADATA, open_instance  # noqa: E402


def _parse_int(text):
    # "-0" can only be a float printed with %.17g; keep its sign.
    return -0.0 if text == "-0" else int(text)


def _same_float(expected, found):
    e, f = float(expected), float(found)  # float("nan"/"inf"/"-inf") parses the strings
    if math.isnan(e) or math.isnan(f):
        return math.isnan(e) and math.isnan(f)
    return e == f and math.copysign(1.0, e) == math.copysign(1.0, f)


def compare(mosb_path, dump_path):
    """Return (ok, message)."""
    with open(dump_path) as f:
        dump = json.load(f, parse_int=_parse_int)
    inst = open_instance(mosb_path)

    def differ(what, expected, found):
        return False, "MISMATCH %s: %s: expected %r, found %r" % (mosb_path, what, expected, found)

    for what, expected, found in (("n", dump["n"], inst.n), ("m", dump["m"], inst.m),
                                  ("version", tuple(dump["version"]), inst.version),
                                  ("section count", len(dump["sections"]), len(inst.sections))):
        if expected != found:
            return differ(what, expected, found)
    if dump["metadata"] != inst.metadata:
        keys = sorted(set(dump["metadata"]) | set(inst.metadata))
        key = next(k for k in keys if dump["metadata"].get(k) != inst.metadata.get(k))
        return differ("metadata key %r" % key, dump["metadata"].get(key),
                      inst.metadata.get(key))
    total = 0
    for i, (d, s) in enumerate(zip(dump["sections"], inst.sections)):
        where = "section %d (%s)" % (i, s.name)
        found_fields = {"name": s.name, "kind": s.kind, "type": s.element_type,
                        "width": s.row_width, "rows": s.row_count,
                        "checksum": "%016x" % s.checksum}
        for field, found in found_fields.items():
            if d.get(field) != found:
                return differ("%s field %s" % (where, field), d.get(field), found)
        if s.kind == METADATA:
            continue
        if "values" not in d:
            return differ("%s values" % where, "(absent)", "a section with values")
        found = inst.array(s).reshape(-1).tolist()
        expected = d["values"]
        if len(expected) != len(found):
            return differ("%s value count" % where, len(expected), len(found))
        is_float = s.element_type in ("f32", "f64")
        if not is_float and expected == found and all(type(e) is int for e in expected):
            total += len(found)  # fast path; the loop below finds the first difference
            continue
        for j, (e, f) in enumerate(zip(expected, found)):
            if not (_same_float(e, f) if is_float else (type(e) is int and e == f)):
                return differ("%s index %d (row %d, column %d)"
                              % (where, j, j // s.row_width, j % s.row_width), e, f)
        total += len(found)
    return True, "OK %s: n=%d m=%d sections=%d values=%d" % (
        mosb_path, inst.n, inst.m, len(inst.sections), total)


def main(argv):
    if len(argv) != 3:
        print("usage: compare_dump.py FILE.mosb DUMP.json", file=sys.stderr)
        return 2
    try:
        ok, message = compare(argv[1], argv[2])
    except FormatError as e:
        ok, message = False, "FORMAT ERROR %s: %s" % (argv[1], e)
    print(message)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
