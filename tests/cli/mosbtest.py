"""What every end-to-end suite in tests/cli shares: where the program and the data are, one way to
run the program, a temporary directory per test, the assertions on a refusal, and the byte-level
view of a .mosb file (spec/FORMAT.md) that the suites use to read or damage one on purpose.

Its byte-level functions (header, entries, payload, metadata, reseal, ...) are written from
spec/FORMAT.md alone, never from the C++ sources, and the suites also read files through
spec/reference/mosb_reader.py, the spec's independent second implementation: what the program writes
is checked by code that does not share its mistakes. Keep both that way: a change here follows the
spec, not the library.

The suites import it as a sibling module: ctest runs each one by path, so its directory is
sys.path[0]. They need /usr/bin/python3 with python3-numpy and python3-xxhash.
"""

import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

import xxhash

HERE = os.path.dirname(os.path.abspath(__file__))
REPOSITORY = os.path.normpath(os.path.join(HERE, "..", ".."))
DATA = os.path.normpath(os.path.join(REPOSITORY, "..", "shared", "data"))  # real inputs, optional
GOLDEN = os.path.join(REPOSITORY, "spec", "golden")

# The tests run the program from their temporary directories, so the path is made absolute.
MOSB = os.path.abspath(os.environ["MOSB"]) if os.environ.get("MOSB") else ""

# The solvers these tests run talk to the tests through files of the test's directory (pids,
# arguments, flags), which a sealed query cannot write (spec/RUN.md §4.1): they run unsealed unless
# a test asks for the seal (--isolation seal, test_seal.py), which every user gets by default.
os.environ.setdefault("MOSB_ISOLATION", "none")

# The independent reader of spec/reference, which several suites compare the program against.
sys.path.insert(0, os.path.join(REPOSITORY, "spec", "reference"))
import mosb_reader  # noqa: E402,F401


# A skip for want of something CI always has (../shared, nginx, Chromium, SLURM, root, a writable
# cgroup-v1 memory controller, private mounts, a tool tools/install-deps.sh installs) carries this
# prefix: main() then exits SKIP_EXIT, ctest (SKIP_RETURN_CODE) reports the suite as skipped, not
# passed, and .ci/run fails on it. A skip by design (a case that cannot mean anything under a
# sanitizer) is a plain unittest skip and passes.
MISSING = "missing: "
SKIP_EXIT = 77


def missing(what):
    """The skip of a test for want of `what` (see MISSING)."""
    return unittest.SkipTest(MISSING + what)


def main(**options):
    """Every suite's entry point: unittest.main(**options), exiting 1 on a failure, SKIP_EXIT when
    a test was skipped for want of something CI has (listed on stderr), else 0."""
    result = unittest.main(exit=False, **options).result
    if not result.wasSuccessful():
        sys.exit(1)
    wanting = [(str(test), reason) for test, reason in result.skipped if reason.startswith(MISSING)]
    if wanting:
        print("SKIPPED, %d test(s) for want of what CI has:" % len(wanting), file=sys.stderr)
        for test, reason in wanting:
            print("  %s: %s" % (test, reason), file=sys.stderr)
        sys.exit(SKIP_EXIT)
    sys.exit(0)


def setUpModule():
    """Imported by every suite: without the program no test can mean anything."""
    if not MOSB:
        raise RuntimeError("set the environment variable MOSB to the path of the mosb binary")
    if not (os.path.isfile(MOSB) and os.access(MOSB, os.X_OK)):
        raise RuntimeError("MOSB=%r is not an executable file" % MOSB)


def alive(pid):
    """Whether process `pid` exists and is not a zombie."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (FileNotFoundError, ProcessLookupError):
        return False


def run(*args, program=None, check=False, **options):
    """Runs mosb (or `program`) with `args`, stdout and stderr captured as text unless `options`
    say otherwise; with `check`, a non-zero exit raises AssertionError with the stderr."""
    options.setdefault("stdout", subprocess.PIPE)
    options.setdefault("stderr", subprocess.PIPE)
    program = program or MOSB
    result = subprocess.run([program, *args], text=True, errors="replace", **options)
    if check and result.returncode != 0:
        raise AssertionError("%s %s failed: %s" % (os.path.basename(program), " ".join(args),
                                                   result.stderr))
    return result


# The test helper tests/cli/write_solution.cpp: solution files written by SolutionWriter.
WRITE_SOLUTION = os.environ.get("WRITE_SOLUTION", "mosb_test_write_solution")


def write_solution(path, instance, view, spec, *extra, env=None):
    """Solution file `path` for `instance`'s `view`, from the helper's text `spec` on stdin."""
    run(instance, view, path, *extra, program=WRITE_SOLUTION, input=spec, check=True, env=env)
    return path


def read(path, mode="rb"):
    with open(path, mode, **({} if "b" in mode else {"encoding": "utf-8"})) as f:
        return f.read()


def files_under(directory):
    return sorted(os.path.join(root, f) for root, dirs, files in os.walk(directory) for f in files)


def finished_code(test, r, solution_files):
    """The exit status a finished `mosb run` or `experiment run` must have given for the solution
    files it wrote (spec/RUN.md §9): 3, with one stderr line naming the most common reason, when
    queries ran and none completed (solved or disconnected), else 0. Asserts the line."""
    completed = ran = 0
    for path in solution_files:
        statuses = json.loads(run("solutions", "inspect", "--json", path).stdout)["statuses"]
        completed += statuses.get("solved", 0) + statuses.get("disconnected", 0)
        ran += sum(statuses.values()) - statuses.get("not-run", 0)
    if ran > 0 and completed == 0:
        test.assertIn("mosb: no query completed (", r.stderr, r)
        return 3
    test.assertNotIn("no query completed", r.stderr, r)
    return 0


def assert_finished(test, r, code, solution_files):
    """`r` ended as `code` says: FINISHED is the status finished_code gives for the files, any
    other number exactly that status."""
    if code == FINISHED:
        test.assertIn(r.returncode, (0, 3), r)
        code = finished_code(test, r, solution_files)
    test.assertEqual(r.returncode, code, r)


# `code=FINISHED` in the run helpers: the run finished (0, or 3 when no query completed).
FINISHED = "finished"


class CliTest(unittest.TestCase):
    """A fresh directory self.dir per test, removed afterwards. At the end it must hold no
    temporary of an atomic write (`.NAME.tmp-PID-XXXXXX`) unless the class sets
    `leaves_temporaries` (runs killed on purpose)."""

    leaves_temporaries = False

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="mosb-%s-" % type(self).__name__)
        self.addCleanup(self._remove_directory)

    def tearDown(self):
        if not self.leaves_temporaries:
            leftovers = [os.path.join(root, f) for root, dirs, files in os.walk(self.dir)
                         for f in files + dirs if ".tmp-" in f]
            self.assertEqual(leftovers, [], "temporary files left behind")

    def _remove_directory(self):
        # A test may have made a directory read-only.
        for root, dirs, _ in os.walk(self.dir):
            for d in dirs:
                os.chmod(os.path.join(root, d), 0o755)
        os.chmod(self.dir, 0o755)
        shutil.rmtree(self.dir, True)

    def skip_unless_present(self, *paths):
        """Skips the test, saying what is missing, unless every path exists: the real data files
        of ../shared are not part of the repository."""
        absent = [p for p in paths if not os.path.exists(p)]
        if absent:
            raise missing("shared data: %s" % ", ".join(absent))

    def path(self, *names):
        return os.path.join(self.dir, *names)

    def write(self, name, data):
        """Writes text (as is, no newline translation) or bytes to `name` in self.dir, making
        its directory if needed."""
        path = self.path(name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        if isinstance(data, str):
            with open(path, "w", encoding="utf-8", newline="") as f:
                f.write(data)
        else:
            with open(path, "wb") as f:
                f.write(data)
        return path

    def mosb(self, *args, timeout=600, **options):
        """Runs mosb in self.dir. Never a hang (no exit within `timeout` seconds; the default
        leaves room for a sanitizer build on real data), never a crash: no signal, no sanitizer
        report."""
        try:
            r = run(*args, cwd=self.dir, timeout=timeout, **options)
        except subprocess.TimeoutExpired:
            self.fail("mosb %s blocked: no exit within %s s" % (" ".join(args), timeout))
        self.assertGreaterEqual(r.returncode, 0, "killed by a signal: %r" % r)
        for stream in (r.stdout, r.stderr):
            self.assertNotIn("Sanitizer", stream or "", r)
            self.assertNotIn("runtime error", stream or "", r)
        return r

    def ok(self, *args, **options):
        r = self.mosb(*args, **options)
        self.assertEqual(r.returncode, 0, r)
        return r

    def assert_one_line_error(self, r, *expected, code=1):
        """`r` exited with `code` and wrote one line to stderr containing every `expected`."""
        self.assertEqual(r.returncode, code, r)
        lines = r.stderr.splitlines()
        self.assertEqual(len(lines), 1, r)
        for text in expected:
            self.assertIn(text, lines[0], r)
        return lines[0]

    def assert_error(self, r, message, code=1):
        """`r` exited with `code` and its stderr is exactly the line 'mosb: <message>'."""
        self.assertEqual(r.returncode, code, r.stderr)
        self.assertEqual(r.stderr, "mosb: " + message + "\n")


# ---------------------------------------------------------------------------------------------
# Byte-level helpers (operate on a bytearray holding a whole file)

# §2: the 128-byte header; §3: the 64-byte section table entry.
HEADER = struct.Struct("<8sIHHIIQQQQIIQQ40sQ")
HEADER_FIELDS = ("magic", "byte_order_mark", "version_major", "version_minor", "header_size",
                 "file_kind", "required_features", "optional_features", "file_size",
                 "table_offset", "section_count", "objective_count", "vertex_count", "arc_count",
                 "reserved", "header_checksum")
ENTRY = struct.Struct("<24sHBBIQQQQ")
ENTRY_FIELDS = ("name", "kind", "element_type", "encoding", "row_width", "row_count", "offset",
                "stored_length", "checksum")
assert HEADER.size == 128 and ENTRY.size == 64
MAGIC = b"\x89MOS\r\n\x1a\n"
CHECKSUM_OFFSET = 120
F32 = 9  # §5 element type codes
F64 = 10
METADATA_KIND = 1  # §4 section kinds
QUERIES_KIND = 10


def header(data):
    return dict(zip(HEADER_FIELDS, HEADER.unpack_from(data, 0)))


def set_header(data, **fields):
    h = header(data)
    h.update(fields)
    HEADER.pack_into(data, 0, *(h[f] for f in HEADER_FIELDS))


def entries(data):
    """The section table as a list of dicts; 'pos' is the entry's file offset."""
    h = header(data)
    result = []
    for i in range(h["section_count"]):
        pos = h["table_offset"] + i * ENTRY.size
        e = dict(zip(ENTRY_FIELDS, ENTRY.unpack_from(data, pos)))
        e["name"] = e["name"].rstrip(b"\0").decode("ascii")
        e["pos"] = pos
        result.append(e)
    return result


def entry(data, name):
    (e,) = [e for e in entries(data) if e["name"] == name]
    return e


def set_entry(data, name, **fields):
    e = entry(data, name)
    e.update(fields)
    values = [e[f] for f in ENTRY_FIELDS]
    values[0] = e["name"].encode("ascii")
    ENTRY.pack_into(data, e["pos"], *values)


def payload(data, name):
    e = entry(data, name)
    return data[e["offset"]:e["offset"] + e["stored_length"]]


def metadata(data):
    """The metadata section (§6) as a dict; {} when the file has none."""
    for e in entries(data):
        if e["kind"] == METADATA_KIND:
            text = bytes(data[e["offset"]:e["offset"] + e["stored_length"]]).decode()
            return dict(line.split("=", 1) for line in text.splitlines())
    return {}


def reseal(data):
    """Recompute the header checksum: XXH3-64 of header bytes [0, 120) + the section table."""
    h = header(data)
    table = data[h["table_offset"]:h["table_offset"] + ENTRY.size * h["section_count"]]
    struct.pack_into("<Q", data, CHECKSUM_OFFSET,
                     xxhash.xxh3_64_intdigest(bytes(data[:CHECKSUM_OFFSET]) + bytes(table)))


def write_payload(data, name, new_payload):
    """Replace a section's payload in place (same length), fix its checksum and the header's."""
    e = entry(data, name)
    assert len(new_payload) == e["stored_length"]
    data[e["offset"]:e["offset"] + len(new_payload)] = new_payload
    set_entry(data, name, checksum=xxhash.xxh3_64_intdigest(bytes(new_payload)))
    reseal(data)


def patch_values(data, name, fmt, index, value):
    """Set element `index` (struct format `fmt`, e.g. '<I') of a section, checksums recomputed."""
    body = bytearray(payload(data, name))
    struct.pack_into(fmt, body, index * struct.calcsize(fmt), value)
    write_payload(data, name, body)


def values(data, name, fmt):
    body = payload(data, name)
    return list(struct.unpack("<%d%s" % (len(body) // struct.calcsize(fmt), fmt), body))


def move_payload_to_end(data, name, body, **fields):
    """Give section `name` the payload `body`, which need not fit in its old place: it is appended
    where the table was and the table moves after it (a reader relies only on the table's offsets,
    §1). The old payload is zeroed, since bytes belonging to no section are zero. `fields` are
    further entry fields to set; the section checksum is recomputed unless `fields` give one, the
    header checksum always."""
    h = header(data)
    old = entry(data, name)
    table = bytes(data[h["table_offset"]:])
    data[old["offset"]:old["offset"] + old["stored_length"]] = bytes(old["stored_length"])
    new_offset = h["table_offset"]
    padded = body + bytes(-len(body) % 64)
    del data[new_offset:]
    data += padded + table
    set_header(data, table_offset=new_offset + len(padded), file_size=len(data))
    changed = dict(offset=new_offset, stored_length=len(body),
                   checksum=xxhash.xxh3_64_intdigest(body))
    changed.update(fields)
    set_entry(data, name, **changed)
    reseal(data)


def set_metadata(data, **values):
    """Give the metadata section (§7: sorted, unique `key=value` lines) the keys `values` (keys
    with dots are passed as **{"map.width": "5"}), the section moved to the end of the file."""
    meta = metadata(data)
    meta.update(values)
    text = "".join("%s=%s\n" % (k, meta[k]) for k in sorted(meta)).encode()
    (e,) = [e for e in entries(data) if e["kind"] == METADATA_KIND]
    move_payload_to_end(data, e["name"], text, row_count=len(text))


def relocate_as_f32(data, name, costs):
    """Turn cost section `name` into an f32 column holding `costs`."""
    relocate_as_float(data, name, costs, F32)


def relocate_as_float(data, name, costs, element_type):
    """Turn cost section `name` into an F32 or F64 column holding `costs`."""
    assert entry(data, name)["row_count"] == len(costs)
    code = {F32: "f", F64: "d"}[element_type]
    move_payload_to_end(data, name, struct.pack("<%d%s" % (len(costs), code), *costs),
                        element_type=element_type)
