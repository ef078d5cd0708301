#!/usr/bin/python3
"""End-to-end tests of the store and its MANIFEST (spec/MANIFEST.md): `mosb store`, `mosb verify
--manifest/--sources`, `--expect-digest`, `mosb suite build`.

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_store.py
"""

import hashlib
import json
import os
import random
import shutil
import signal
import subprocess
import time

import mosbtest
from mosbtest import MOSB, CliTest, entry, read, run, setUpModule  # noqa: F401

GR = "p sp 4 5\na 1 2 5\na 2 3 7\na 3 1 2\na 3 4 1\na 4 1 9\n"


def grid(path, width, height=4, seed=1):
    r = run("generate", "grid", "--width", str(width), "--height", str(height), "--seed",
            str(seed), "-o", path)
    assert r.returncode == 0, r
    return path


class Base(CliTest):
    def records(self, manifest):
        lines = read(manifest).decode().splitlines()
        return json.loads(lines[0]), [json.loads(line) for line in lines[1:]]

    def store_with(self, *widths):
        store = self.path("store")
        self.ok("store", "init", store)
        files = [grid(self.path("g%d.mosb" % w), w) for w in widths]
        self.ok("store", "add", store, *files)
        return store

    def verify_json(self, *args):
        r = run(*args, "--json")
        return r.returncode, json.loads(r.stdout)

    def problems(self, report):
        return sorted((f["file"], p["kind"]) for f in report["files"] for p in f["problems"])


class Manifest(Base):
    def test_add_writes_sorted_json_lines_with_sha256_and_metadata(self):
        store = self.store_with(7, 5)
        header, entries = self.records(os.path.join(store, "MANIFEST"))
        self.assertEqual(header, {"format": "mosb-manifest", "version": 1})
        self.assertEqual([e["file"] for e in entries], ["g5.mosb", "g7.mosb"])
        for e in entries:
            data = read(os.path.join(store, e["file"]))
            self.assertEqual(e["sha256"], hashlib.sha256(data).hexdigest())
            self.assertEqual(e["size"], len(data))
            self.assertEqual(e["views"], ["Grid_2", "Grid_3"])
            self.assertEqual(e["benchmark"], "Grid-%dx4" % (5 if e["file"] == "g5.mosb" else 7))
            self.assertFalse(e["packed"])
            self.assertEqual(e["format_version"], "1.0")
            self.assertEqual(list(e), sorted(e), "keys sorted")
        # Copies, not moves, by default; --move removes the source.
        self.assertTrue(os.path.exists(self.path("g5.mosb")))
        grid(self.path("g9.mosb"), 9)
        self.ok("store", "add", "--move", store, self.path("g9.mosb"))
        self.assertFalse(os.path.exists(self.path("g9.mosb")))
        listed = json.loads(self.ok("store", "list", "--json", store).stdout)
        self.assertEqual([e["file"] for e in listed["entries"]], ["g5.mosb", "g7.mosb", "g9.mosb"])

    def test_verify_reports_every_kind_of_wrong_entry(self):
        store = self.store_with(3, 4, 5, 6, 7, 8)
        code, report = self.verify_json("store", "verify", store)
        self.assertEqual(code, 0, report)
        self.assertEqual(self.problems(report), [])
        s = lambda name: os.path.join(store, name)
        os.remove(s("g3.mosb"))                                   # missing
        grid(s("extra.mosb"), 2)                                  # extra
        with open(s("g4.mosb"), "ab") as f:                       # wrong size (and sha256)
            f.write(b"\0" * 64)
        header, entries = self.records(s("MANIFEST"))
        for e in entries:                                         # wrong sha256 / digest listed
            if e["file"] == "g5.mosb":
                e["sha256"] = "0" * 64
            if e["file"] == "g6.mosb":
                e["digest"] = "0" * 32
        with open(s("MANIFEST"), "w") as f:
            f.write("".join(json.dumps(r, sort_keys=True) + "\n" for r in [header] + entries))
        data = bytearray(read(s("g7.mosb")))                      # damaged payload
        data[-(len(data) // 3)] ^= 0xFF
        with open(s("g7.mosb"), "wb") as f:
            f.write(data)
        os.chmod(s("g8.mosb"), 0)                                 # unreadable
        code, report = self.verify_json("store", "verify", store)
        self.assertEqual(code, 1)
        found = self.problems(report)
        self.assertIn(("g3.mosb", "missing"), found)
        self.assertIn(("extra.mosb", "extra"), found)
        self.assertIn(("g4.mosb", "wrong-size"), found)
        self.assertIn(("g4.mosb", "wrong-sha256"), found)
        self.assertIn(("g5.mosb", "wrong-sha256"), found)
        self.assertIn(("g6.mosb", "wrong-digest"), found)
        self.assertIn(("g7.mosb", "wrong-sha256"), found)
        self.assertTrue({("g7.mosb", "damaged"), ("g7.mosb", "wrong-digest")} & set(found), found)
        if os.geteuid() != 0:  # root reads a mode-0 file
            self.assertIn(("g8.mosb", "unreadable"), found)
        # The text report names each file and ends non-zero.
        r = run("store", "verify", store)
        self.assertEqual(r.returncode, 1)
        self.assertIn("FAIL missing: " + s("g3.mosb"), r.stdout)
        self.assertIn("FAIL wrong-digest: " + s("g6.mosb"), r.stdout)

    def test_verify_manifest_checks_downloads_without_a_store(self):
        store = self.store_with(3, 4)
        download = self.path("download")
        os.mkdir(download)
        shutil.copy(os.path.join(store, "g3.mosb"), download)
        shutil.copy(os.path.join(store, "g4.mosb"), download)
        manifest = os.path.join(store, "MANIFEST")
        self.ok("verify", "--manifest", manifest, os.path.join(download, "g3.mosb"),
                os.path.join(download, "g4.mosb"))
        with open(os.path.join(download, "g4.mosb"), "r+b") as f:
            f.seek(200)
            byte = f.read(1)
            f.seek(200)
            f.write(bytes([byte[0] ^ 1]))
        grid(os.path.join(download, "other.mosb"), 2)
        r = run("verify", "--json", "--manifest", manifest, os.path.join(download, "g3.mosb"),
                os.path.join(download, "g4.mosb"), os.path.join(download, "other.mosb"))
        self.assertEqual(r.returncode, 1)
        found = self.problems(json.loads(r.stdout))
        self.assertIn(("g4.mosb", "wrong-sha256"), found)
        self.assertIn(("other.mosb", "extra"), found)
        self.assertNotIn("g3.mosb", [f for f, _ in found])
        # Without paths: the files beside the manifest.
        self.ok("verify", "--manifest", manifest)

    def test_verify_manifest_knows_the_other_form_of_a_listed_file(self):
        store = self.store_with(3)  # g3.mosb listed unpacked
        packed_store = self.path("packed")
        self.ok("store", "init", packed_store)
        self.ok("store", "add", "--pack", packed_store, os.path.join(store, "g3.mosb"))
        unpacked, packed = self.path("unpacked"), self.path("repacked")
        os.mkdir(unpacked)
        os.mkdir(packed)
        # The unpacked form of the listed packed file, and the packed form of the listed unpacked.
        self.ok("unpack", os.path.join(packed_store, "g3.mosb"), "-o", os.path.join(unpacked, "g3.mosb"))
        self.ok("pack", os.path.join(store, "g3.mosb"), "-o", os.path.join(packed, "g3.mosb"))
        for manifest, copy, note in (
                (os.path.join(packed_store, "MANIFEST"), os.path.join(unpacked, "g3.mosb"),
                 "unpacked form of the listed packed file"),
                (os.path.join(store, "MANIFEST"), os.path.join(packed, "g3.mosb"),
                 "packed form of the listed unpacked file")):
            r = run("verify", "--manifest", manifest, copy)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertIn("OK   g3.mosb: " + note, r.stdout)
            report = json.loads(run("verify", "--json", "--manifest", manifest, copy).stdout)
            self.assertEqual(report["files"][0]["note"], note)
        # Other content in the other form is still refused, by its digest.
        grid(self.path("other.mosb"), 2)
        self.ok("pack", self.path("other.mosb"), "-o", os.path.join(packed, "g3.mosb"))
        r = run("verify", "--manifest", os.path.join(store, "MANIFEST"), os.path.join(packed, "g3.mosb"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("FAIL wrong-digest", r.stdout)
        # A store holds the listed bytes themselves: there the other form is a failure.
        os.replace(os.path.join(unpacked, "g3.mosb"), os.path.join(packed_store, "g3.mosb"))
        r = run("store", "verify", packed_store)
        self.assertEqual(r.returncode, 1)
        self.assertIn("FAIL wrong-sha256", r.stdout)

    def test_old_tsv_manifest_is_read_and_converted_on_the_next_write(self):
        store = self.path("store")
        os.mkdir(store)
        g = grid(os.path.join(store, "a.mosb"), 3)
        digest = json.loads(self.ok("inspect", "--json", g).stdout)["digest"]
        with open(os.path.join(store, "MANIFEST"), "w") as f:
            f.write("Grid-3x4\ta.mosb\t%d\t%s\n" % (os.path.getsize(g), digest))
        listed = json.loads(self.ok("store", "list", "--json", store).stdout)["entries"]
        self.assertEqual([(e["file"], e["digest"], e["sha256"]) for e in listed],
                         [("a.mosb", digest, "")])
        self.ok("store", "verify", store)
        self.ok("verify", "--manifest", os.path.join(store, "MANIFEST"))
        with open(os.path.join(store, "MANIFEST"), "w") as f:
            f.write("Grid-3x4\ta.mosb\t%d\t%s\n" % (os.path.getsize(g), "1" * 32))
        self.assertEqual(run("store", "verify", store).returncode, 1)
        with open(os.path.join(store, "MANIFEST"), "w") as f:
            f.write("Grid-3x4\ta.mosb\t%d\t%s\n" % (os.path.getsize(g), digest))
        self.ok("store", "add", store, grid(self.path("b.mosb"), 4))
        header, entries = self.records(os.path.join(store, "MANIFEST"))
        self.assertEqual(header["format"], "mosb-manifest")
        self.assertEqual([e["file"] for e in entries], ["a.mosb", "b.mosb"])

    def test_a_malformed_manifest_is_one_line_naming_the_file(self):
        store = self.path("store")
        os.mkdir(store)
        with open(os.path.join(store, "MANIFEST"), "w") as f:
            f.write('{"format":"mosb-manifest","version":1}\n{"file":"a.mosb"\n')
        r = run("store", "list", store)
        self.assertEqual(r.returncode, 1)
        self.assertRegex(r.stderr, r"^mosb: .*MANIFEST:2: not JSON")
        self.assertEqual(len(r.stderr.splitlines()), 1)
        # A number beyond every JSON number type (it escaped as an "internal error" naming no file).
        with open(os.path.join(store, "MANIFEST"), "w") as f:
            f.write('{"format":"mosb-manifest","version":1,"x":1e999}\n')
        r = run("store", "list", store)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stderr, "mosb: %s:1: not JSON: number overflow parsing '1e999'\n"
                         % os.path.join(store, "MANIFEST"))
        # Numbers that are no integer of the field's range (a float out of range was converted
        # with undefined behaviour, found by the fuzzer under UBSan).
        for value in ("1e30", "4294967296", "1.5"):
            with open(os.path.join(store, "MANIFEST"), "w") as f:
                f.write('{"format":"mosb-manifest","version":%s}\n' % value)
            r = run("store", "list", store)
            self.assertEqual(r.returncode, 1, value)
            self.assertEqual(r.stderr, "mosb: %s:1: key 'version' is not an integer in range\n"
                             % os.path.join(store, "MANIFEST"), value)

    def test_add_refuses_a_damaged_file_and_leaves_the_store_as_it_was(self):
        store = self.store_with(3)
        before = read(os.path.join(store, "MANIFEST"))
        bad = bytearray(read(grid(self.path("bad.mosb"), 5)))
        bad[-(len(bad) // 3)] ^= 0xFF
        with open(self.path("bad.mosb"), "wb") as f:
            f.write(bad)
        r = run("store", "add", store, self.path("bad.mosb"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("bad.mosb", r.stderr)
        self.assertEqual(read(os.path.join(store, "MANIFEST")), before)
        self.assertEqual(sorted(os.listdir(store)), [".lock", "MANIFEST", "g3.mosb"])

    def test_read_only_store_is_listed_and_verified_without_writing(self):
        store = self.store_with(3, 4)
        os.chmod(store, 0o555)
        before = sorted(os.listdir(store))
        self.ok("store", "list", store)
        self.ok("store", "verify", store)
        self.ok("verify", "--manifest", os.path.join(store, "MANIFEST"))
        self.assertEqual(sorted(os.listdir(store)), before)


def read_only_bind(directory):
    """A command prefix that runs its command with `directory` bind-mounted read-only in a private
    mount namespace (root ignores permission bits, so a read-only file system is the only way to
    show a root-run test what a read-only store is); None when this machine does not allow it."""
    if os.geteuid() != 0:
        return None
    probe = subprocess.run(["unshare", "-m", "sh", "-c", 'mount --bind "$0" "$0" && mount -o '
                            'remount,bind,ro "$0" "$0" && ! touch "$0/.probe" 2>/dev/null',
                            directory], capture_output=True)
    if probe.returncode != 0:
        return None
    return ["unshare", "-m", "sh", "-c", 'mount --bind "$0" "$0" && mount -o remount,bind,ro "$0" '
            '"$0" && shift && exec "$@"', directory, "--"]


class Packed(Base):
    def packed_store(self):
        store = self.path("store")
        self.ok("store", "init", store)
        original = grid(self.path("g5.mosb"), 5)
        self.ok("store", "add", "--pack", store, original)
        return store, original

    def test_add_pack_stores_the_packed_form_and_unpack_restores_the_original(self):
        store, original = self.packed_store()
        _, entries = self.records(os.path.join(store, "MANIFEST"))
        self.assertEqual([(e["file"], e["packed"]) for e in entries], [("g5.mosb", True)])
        stored = os.path.join(store, "g5.mosb")
        self.assertEqual(entries[0]["sha256"], hashlib.sha256(read(stored)).hexdigest())
        self.assertLess(len(read(stored)), len(read(original)))
        self.ok("unpack", stored, "-o", self.path("back.mosb"))
        self.assertEqual(read(self.path("back.mosb")), read(original))
        self.assertEqual(sorted(os.listdir(store)), [".lock", "MANIFEST", "g5.mosb"])  # no staging
        self.ok("store", "verify", store)

    def test_add_pack_of_a_name_listed_with_other_content_changes_nothing(self):
        store = self.store_with(3)
        before = read(os.path.join(store, "MANIFEST")), read(os.path.join(store, "g3.mosb"))
        os.makedirs(self.path("other"))
        r = run("store", "add", "--pack", store, grid(self.path("other", "g3.mosb"), 3, seed=2))
        self.assertEqual(r.returncode, 1, r)
        self.assertIn("already lists a different 'g3.mosb'", r.stderr)
        self.assertEqual((read(os.path.join(store, "MANIFEST")),
                          read(os.path.join(store, "g3.mosb"))), before)
        self.assertEqual(sorted(os.listdir(store)), [".lock", "MANIFEST", "g3.mosb"])

    def damaged_packed_copy(self):
        """A packed file with one byte of a zstd frame changed (the header and table intact)."""
        self.ok("pack", grid(self.path("g9.mosb"), 9, height=9), "-o", self.path("p.mosb"))
        data = bytearray(read(self.path("p.mosb")))
        data[len(data) // 2] ^= 0x55
        with open(self.path("bad.mosb"), "wb") as f:
            f.write(data)
        self.ok("inspect", self.path("bad.mosb"))  # still opens: only decoding finds the damage
        return self.path("bad.mosb")

    def test_add_decodes_and_verifies_a_packed_file(self):
        store = self.store_with(3)
        r = run("store", "add", store, self.damaged_packed_copy())
        self.assertEqual(r.returncode, 1, r)
        self.assertIn("bad.mosb", r.stderr)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertEqual(sorted(os.listdir(store)), [".lock", "MANIFEST", "g3.mosb"])

    def test_verify_decodes_packed_entries(self):
        # The damaged file is listed with its own size and SHA-256: only decoding can find it.
        store, _ = self.packed_store()
        bad = self.damaged_packed_copy()
        shutil.copy(bad, os.path.join(store, "g5.mosb"))
        manifest = os.path.join(store, "MANIFEST")
        header, entries = self.records(manifest)
        entries[0].update(size=os.path.getsize(bad), sha256=hashlib.sha256(read(bad)).hexdigest(),
                          digest=json.loads(run("inspect", "--json", bad).stdout)["digest"])
        with open(manifest, "w") as f:
            f.write("".join(json.dumps(x, separators=(",", ":")) + "\n" for x in [header] + entries))
        code, report = self.verify_json("store", "verify", store)
        self.assertEqual(code, 1, report)
        self.assertEqual(self.problems(report), [("g5.mosb", "damaged")])

    def test_instance_unpacks_into_the_cache_once_and_remakes_a_bad_copy(self):
        store, original = self.packed_store()
        first = json.loads(self.ok("store", "instance", "--json", store, "Grid_3").stdout)
        cached = os.path.join(store, ".cache", "g5.mosb")
        self.assertEqual(os.path.realpath(first["path"]), os.path.realpath(cached))
        self.assertEqual((first["view"], first["query_set"]), ("Grid_3", "default"))
        self.assertEqual(read(cached), read(original))
        inode = os.stat(cached).st_ino
        self.ok("store", "instance", store, "Grid-5x4/Grid_2")
        self.assertEqual(os.stat(cached).st_ino, inode)  # mapped, not made again
        data = bytearray(read(cached))
        data[len(data) // 2] ^= 0x55
        with open(cached, "wb") as f:
            f.write(data)
        self.ok("store", "instance", store, "Grid_3")
        self.assertEqual(read(cached), read(original))
        self.ok("store", "verify", store)  # the cache is the store's own, not an extra file

    def test_instance_of_a_read_only_store_gives_the_unpacked_copy_or_refuses(self):
        # A solver maps the path printed: without an unpacked copy a read-only store has none to
        # give (the packed file would be the wrong bytes), so it says so and fails.
        store, _ = self.packed_store()
        before = sorted(os.listdir(store))
        prefix = read_only_bind(store)
        if prefix is None and os.geteuid() == 0:
            raise mosbtest.missing("running as root and no private read-only mount is allowed here")
        if prefix is None:
            os.chmod(store, 0o555)
            prefix = []
        for options in ([], ["--json"]):
            r = subprocess.run(prefix + [MOSB, "store", "instance", *options, store, "Grid_3"],
                               capture_output=True, text=True)
            cached = os.path.join(store, ".cache", "g5.mosb")
            self.assert_one_line_error(r, cached + ": cannot unpack there")
            self.assertEqual(r.stdout, "")
            self.assertEqual(sorted(os.listdir(store)), before)
        if not prefix:
            os.chmod(store, 0o755)
        self.ok("store", "instance", store, "Grid_3")  # writable: the copy is made
        if not prefix:
            os.chmod(store, 0o555)
        r = subprocess.run(prefix + [MOSB, "store", "instance", "--json", store, "Grid_3"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r)
        self.assertEqual(json.loads(r.stdout)["path"], cached)


class KilledAdd(Base):
    def test_kill_9_during_add_leaves_a_valid_manifest(self):
        store = self.store_with(3)
        big = grid(self.path("big.mosb"), 1000, 1000)
        small = [grid(self.path("s%d.mosb" % i), 4 + i) for i in range(3)]
        old = read(os.path.join(store, "MANIFEST"))
        rng = random.Random(5)
        states = set()
        for attempt in range(6):
            p = subprocess.Popen([MOSB, "store", "add", store, big, *small],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            time.sleep(rng.uniform(0.0, 0.4))
            p.send_signal(signal.SIGKILL)
            p.wait()
            manifest = read(os.path.join(store, "MANIFEST"))
            header, entries = self.records(os.path.join(store, "MANIFEST"))
            self.assertEqual(header["format"], "mosb-manifest")
            names = [e["file"] for e in entries]
            states.add(tuple(names))
            self.assertIn(names, [["g3.mosb"], ["big.mosb", "g3.mosb", "s0.mosb", "s1.mosb",
                                                "s2.mosb"]])
            # Every listed file checks out; only the files being added can be extra.
            code, report = self.verify_json("store", "verify", store)
            for f in report["files"]:
                for problem in f["problems"]:
                    self.assertEqual(problem["kind"], "extra", report)
                    self.assertIn(f["file"], ["big.mosb", "s0.mosb", "s1.mosb", "s2.mosb"])
            if manifest != old:
                break
        # A later add completes (reusing what an interrupted one copied) and leaves no temporary.
        self.ok("store", "add", store, big, *small)
        code, report = self.verify_json("store", "verify", store)
        self.assertEqual(code, 0, report)
        self.assertEqual([n for n in os.listdir(store) if n.startswith(".")], [".lock"])


class DamagedEntries(Base):
    """`store instance` on an entry file damaged after it was added, plain and packed, text and
    --json: exit 1 and one line 'mosb: <entry file>: ...', nothing on stdout, no cache copy made
    from it, never a hang. A damaged copy in the cache is made again from the packed entry."""

    ENTRIES = (("g5.mosb", "Grid-5x4/Grid_3", False), ("g7.mosb", "Grid-7x4/Grid_3", True))

    def mixed_store(self):
        """A plain g5.mosb and a packed g7.mosb; made anew on each call."""
        store = self.path("store")
        shutil.rmtree(store, True)
        self.ok("store", "init", store)
        self.ok("store", "add", store, grid(self.path("g5.mosb"), 5))
        self.ok("store", "add", "--pack", store, grid(self.path("g7.mosb"), 7))
        return store

    def instance(self, store, name, *options):
        return self.mosb("store", "instance", *options, store, name, timeout=20)

    def check_refused(self, damage):
        """damage(path, packed) spoils one entry file of a fresh store; every query refuses it."""
        for file, name, packed in self.ENTRIES:
            for options in ([], ["--json"]):
                with self.subTest(file=file, packed=packed, options=options):
                    store = self.mixed_store()
                    target = os.path.join(store, file)
                    damage(target, packed)
                    r = self.instance(store, name, *options)
                    line = self.assert_one_line_error(r, target)
                    self.assertTrue(line.startswith("mosb: " + target + ": "), r)
                    self.assertEqual(r.stdout, "", r)
                    self.assertFalse(os.path.lexists(os.path.join(store, ".cache", file)),
                                     "a cache copy was made from a damaged entry")

    def test_truncated_entry(self):
        def truncate(path, packed):
            data = read(path)
            with open(path, "wb") as f:
                f.write(data[:len(data) // 2])
        self.check_refused(truncate)

    def test_entry_replaced_by_a_directory(self):
        def directory(path, packed):
            os.remove(path)
            os.mkdir(path)
        self.check_refused(directory)

    def test_entry_replaced_by_a_fifo(self):
        def fifo(path, packed):
            os.remove(path)
            os.mkfifo(path)
        self.check_refused(fifo)

    def test_flipped_byte_in_forward_offsets(self):
        def flip(path, packed):
            data = bytearray(read(path))
            e = entry(data, "forward_offsets")
            # In the packed entry the payload is a zstd frame (spec/FORMAT.md §6).
            self.assertEqual(e["encoding"] != 0, packed, e)
            data[e["offset"] + e["stored_length"] // 2] ^= 0x04
            with open(path, "wb") as f:
                f.write(data)
        self.check_refused(flip)

    def check_cache_remade(self, damage):
        """damage(path) spoils the cache copy of the packed entry; instance makes it again."""
        for options in ([], ["--json"]):
            with self.subTest(options=options):
                store = self.mixed_store()
                self.assertEqual(self.instance(store, "Grid-7x4/Grid_3").returncode, 0)
                cached = os.path.join(store, ".cache", "g7.mosb")
                self.ok("unpack", os.path.join(store, "g7.mosb"), "-o", self.path("g7-back.mosb"))
                self.assertEqual(read(cached), read(self.path("g7-back.mosb")))
                damage(cached)
                r = self.instance(store, "Grid-7x4/Grid_3", *options)
                self.assertEqual(r.returncode, 0, r)
                self.assertEqual(r.stderr, "", r)
                if options:
                    self.assertEqual(json.loads(r.stdout)["path"], cached)
                else:
                    self.assertEqual(r.stdout.splitlines()[0], cached, r)
                self.assertEqual(read(cached), read(self.path("g7-back.mosb")))
                self.ok("store", "verify", store)

    def test_truncated_cache_copy_is_made_again(self):
        def truncate(path):
            data = read(path)
            with open(path, "wb") as f:
                f.write(data[:len(data) // 2])
        self.check_cache_remade(truncate)

    def test_empty_cache_copy_is_made_again(self):
        self.check_cache_remade(lambda path: open(path, "wb").close())

    def test_cache_copy_with_a_flipped_byte_in_forward_offsets_is_made_again(self):
        def flip(path):
            data = bytearray(read(path))
            e = entry(data, "forward_offsets")
            data[e["offset"] + e["stored_length"] // 2] ^= 0x04
            with open(path, "wb") as f:
                f.write(data)
        self.check_cache_remade(flip)

    def test_cache_copy_replaced_by_a_fifo_is_made_again(self):
        def fifo(path):
            os.remove(path)
            os.mkfifo(path)
        self.check_cache_remade(fifo)

    def test_directory_in_place_of_the_cache_copy_is_left_alone(self):
        # rename cannot replace a directory and the store deletes nothing it did not make: no
        # unpacked copy can be made, so instance says so (the packed file is no path to map).
        for options in ([], ["--json"]):
            with self.subTest(options=options):
                store = self.mixed_store()
                cached = os.path.join(store, ".cache", "g7.mosb")
                os.makedirs(os.path.join(cached, "inside"))
                r = self.instance(store, "Grid-7x4/Grid_3", *options)
                self.assert_one_line_error(r, cached + ": cannot unpack there")
                self.assertEqual(r.stdout, "")
                self.assertTrue(os.path.isdir(os.path.join(cached, "inside")))
                self.assertEqual(os.listdir(os.path.join(store, ".cache")), ["g7.mosb"])


class Safety(Base):
    """The store never loses what it lists and never writes or deletes outside its directory:
    reserved names, concurrent writers, planted symlinks, leftovers of interrupted runs."""

    def snapshot(self, directory):
        """Every path under `directory` with its bytes (None for a directory or a symlink)."""
        out = {}
        for root, dirs, files in os.walk(directory):
            for name in dirs + files:
                path = os.path.join(root, name)
                plain = os.path.isfile(path) and not os.path.islink(path)
                out[os.path.relpath(path, directory)] = read(path) if plain else None
        return out

    def test_reserved_names_are_refused_before_anything_is_placed(self):
        store = self.store_with(3)
        os.makedirs(self.path("in"))
        before = self.snapshot(store)
        for name in ("MANIFEST", ".MANIFEST.tmp-123-abcdef", ".cache", ".staging", ".lock",
                     ".hidden.mosb", "README.md", "SUMMARY.csv"):
            source = grid(self.path("in", name), 4)
            for options in ([], ["--move"], ["--pack"]):
                with self.subTest(name=name, options=options):
                    r = self.mosb("store", "add", *options, store, source)
                    self.assert_one_line_error(r, source, "cannot be added as '%s'" % name,
                                               "keeps MANIFEST, README.md, SUMMARY.csv and names "
                                               "starting with '.'")
                    self.assertEqual(self.snapshot(store), before)
                    self.assertTrue(os.path.exists(source))
            os.remove(source)
        listed = json.loads(self.ok("store", "list", "--json", store).stdout)["entries"]
        self.assertEqual([e["file"] for e in listed], ["g3.mosb"])

    def test_a_manifest_listing_a_reserved_name_is_refused(self):
        store = self.store_with(3)
        manifest = os.path.join(store, "MANIFEST")
        header, entries = self.records(manifest)
        entries[0]["file"] = ".cache"
        with open(manifest, "w") as f:
            f.write("".join(json.dumps(x) + "\n" for x in [header] + entries))
        for command in ("list", "verify"):
            r = self.mosb("store", command, store)
            self.assert_one_line_error(r, manifest + ": lists '.cache', a name the store keeps")

    def test_entry_names_a_terminal_would_not_show_as_themselves_are_refused(self):
        # Issue 36 item 10: C1 controls and bidirectional overrides or isolates passed the name
        # rule, and `store list` printed them raw.
        store = self.store_with(3)
        manifest = os.path.join(store, "MANIFEST")
        header, entries = self.records(manifest)
        for name, shown in (("g\u0085.mosb", "g\\u{0085}.mosb"),
                            ("g\u202egsom.exe", "g\\u{202e}gsom.exe"),
                            ("g\u2066.mosb", "g\\u{2066}.mosb"), ("g\u200f.mosb", "g\\u{200f}.mosb"),
                            # Invisible format characters: a name that prints like another.
                            ("g\u200b.mosb", "g\\u{200b}.mosb"), ("g\ufeff.mosb", "g\\u{feff}.mosb"),
                            ("g\u00ad.mosb", "g\\u{00ad}.mosb")):
            entries[0]["file"] = name
            with open(manifest, "w", encoding="utf-8") as f:
                f.write("".join(json.dumps(x) + "\n" for x in [header] + entries))
            for command in ("list", "verify"):
                with self.subTest(name=shown, command=command):
                    r = self.mosb("store", command, store)
                    line = self.assert_one_line_error(
                        r, manifest + ":2: invalid file name '%s' (a base name: UTF-8" % shown)
                    self.assertNotIn(name[1], line)
        # store add refuses such a file before it reads it; a name that only looks like an escape
        # (a backslash, then x1b) is printed escaped, so it cannot pass for the escape of an ESC.
        added = self.path("added")
        self.ok("store", "init", added)
        os.makedirs(self.path("in"))
        for name in ("g\u0085.mosb", "g\u202egsom.mosb", "g\u2069.mosb"):
            with self.subTest(add=name):
                source = grid(self.path("in", name), 4)
                r = self.mosb("store", "add", added, source)
                line = self.assert_one_line_error(r, "cannot be an entry's name (a base name")
                self.assertNotIn(name[1], line)
        literal = grid(self.path("in", "g\\x1b.mosb"), 4)
        self.assertIn("added g\\\\x1b.mosb (digest ", self.ok("store", "add", added, literal).stdout)
        self.assertIn("\ng\\\\x1b.mosb  ", "\n" + self.ok("store", "list", added).stdout)
        self.assertTrue(self.ok("store", "instance", added, "Grid-4x4/Grid_2").stdout
                        .startswith(os.path.join(added, "g\\\\x1b.mosb\n")))

    def test_names_from_the_files_are_printed_escaped(self):
        # Issue 36 item 10: benchmark, view and query set names come from the files (or a
        # MANIFEST) and were printed raw by `store list`.
        store = self.store_with(3)
        manifest = os.path.join(store, "MANIFEST")
        header, entries = self.records(manifest)
        entries[0]["benchmark"] = "Grid\u202e3x4"
        entries[0]["views"] = ["Grid_2\u0085", "Grid_3\x1b[31m"]
        entries[0]["query_sets"] = ["default\u2066"]
        with open(manifest, "w", encoding="utf-8") as f:
            f.write("".join(json.dumps(x) + "\n" for x in [header] + entries))
        out = self.ok("store", "list", store).stdout
        self.assertIn("benchmark Grid\\u{202e}3x4  views Grid_2\\u{0085},Grid_3\\x1b[31m  queries "
                      "default\\u{2066}  digest ", out)
        for raw in ("\u202e", "\u0085", "\x1b", "\u2066"):
            self.assertNotIn(raw, out)

    def test_forty_concurrent_adds_are_all_listed(self):
        store = self.path("store")
        self.ok("store", "init", store)
        os.makedirs(self.path("in"))
        files = [grid(self.path("in", "c%02d.mosb" % i), 2 + i % 3, height=2, seed=i)
                 for i in range(40)]
        # Half of them packed: each add stages its packed file in .staging at the same time.
        procs = [subprocess.Popen([MOSB, "store", "add", *(["--pack"] if i % 2 else []), store,
                                   f], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                 for i, f in enumerate(files)]
        errors = [(p.wait(timeout=120), p.stderr.read()) for p in procs]
        for p in procs:
            p.stderr.close()
        self.assertEqual([e for e in errors if e[0] != 0], [])
        listed = json.loads(self.ok("store", "list", "--json", store).stdout)["entries"]
        self.assertEqual([e["file"] for e in listed], ["c%02d.mosb" % i for i in range(40)])
        self.assertEqual([e["packed"] for e in listed], [i % 2 == 1 for i in range(40)])
        code, report = self.verify_json("store", "verify", store)
        self.assertEqual(code, 0, report)
        self.assertEqual(len(report["files"]), 40)
        self.assertEqual(sorted(n for n in os.listdir(store) if n.startswith(".")), [".lock"])

    def outside(self):
        """A directory outside the store holding a file, and that file's bytes."""
        outside = self.path("outside")
        os.makedirs(outside, exist_ok=True)
        victim = grid(os.path.join(outside, "g5.mosb"), 6)
        shutil.copy(victim, os.path.join(outside, "g7.mosb"))
        return outside, self.snapshot(outside)

    def test_symlinked_staging_is_refused(self):
        store = self.store_with(3)
        outside, before = self.outside()
        os.symlink(outside, os.path.join(store, ".staging"))
        source = grid(self.path("g5.mosb"), 5)
        r = self.mosb("store", "add", "--pack", store, source)
        self.assert_one_line_error(r, os.path.join(store, ".staging") + ": is a symbolic link")
        self.assertEqual(self.snapshot(outside), before)
        self.assertTrue(os.path.islink(os.path.join(store, ".staging")))

    def test_symlinked_cache_and_cache_copy_are_refused(self):
        store = self.path("store")
        self.ok("store", "init", store)
        self.ok("store", "add", "--pack", store, grid(self.path("g7.mosb"), 7))
        outside, before = self.outside()
        cache = os.path.join(store, ".cache")
        os.symlink(outside, cache)
        r = self.mosb("store", "instance", store, "Grid-7x4/Grid_3")
        self.assert_one_line_error(r, cache + ": is a symbolic link")
        self.assertEqual(self.snapshot(outside), before)
        os.remove(cache)
        os.mkdir(cache)
        os.symlink(os.path.join(outside, "g7.mosb"), os.path.join(cache, "g7.mosb"))
        r = self.mosb("store", "instance", store, "Grid-7x4/Grid_3")
        self.assert_one_line_error(r, os.path.join(cache, "g7.mosb") + ": is a symbolic link")
        self.assertEqual(self.snapshot(outside), before)

    def test_symlinked_entry_and_lock_are_refused(self):
        store = self.store_with(5)
        outside, before = self.outside()
        entry_path = os.path.join(store, "g5.mosb")
        os.remove(entry_path)
        os.symlink(os.path.join(outside, "g5.mosb"), entry_path)
        r = self.mosb("store", "add", store, self.path("g5.mosb"))
        self.assert_one_line_error(r, entry_path + ": is a symbolic link")
        r = self.mosb("store", "instance", store, "Grid-5x4/Grid_3")
        self.assert_one_line_error(r, entry_path + ": is a symbolic link")
        code, report = self.verify_json("store", "verify", store)
        self.assertEqual((code, self.problems(report)), (1, [("g5.mosb", "unreadable")]))
        self.assertEqual(self.snapshot(outside), before)
        os.remove(entry_path)
        shutil.copy(self.path("g5.mosb"), entry_path)
        lock = os.path.join(store, ".lock")
        os.remove(lock)
        os.symlink(os.path.join(outside, "g7.mosb"), lock)
        r = self.mosb("store", "add", store, grid(self.path("g4.mosb"), 4))
        self.assert_one_line_error(r, lock + ": is a symbolic link")
        self.assertEqual(self.snapshot(outside), before)
        listed = json.loads(self.ok("store", "list", "--json", store).stdout)["entries"]
        self.assertEqual([e["file"] for e in listed], ["g5.mosb"])

    def test_staging_left_by_ended_processes_is_swept(self):
        store = self.store_with(3)
        ended = subprocess.Popen(["true"])
        ended.wait()
        staging = os.path.join(store, ".staging")
        dead = os.path.join(staging, "%d-AbC123" % ended.pid)
        alive = os.path.join(staging, "%d-XyZ789" % os.getpid())
        foreign = os.path.join(staging, "not-ours")
        for d in (dead, alive, foreign):
            os.makedirs(d)
            shutil.copy(os.path.join(store, "g3.mosb"), d)
        self.ok("store", "add", store, grid(self.path("g4.mosb"), 4))
        self.assertEqual(sorted(os.listdir(staging)), sorted(os.path.basename(d)
                                                             for d in (alive, foreign)))
        shutil.rmtree(alive)
        shutil.rmtree(foreign)
        self.ok("store", "add", "--pack", store, grid(self.path("g6.mosb"), 6))
        self.assertFalse(os.path.lexists(staging), "an empty .staging is removed")

    def test_interrupted_pack_leaves_nothing_after_the_next_add(self):
        store = self.store_with(3)
        big = grid(self.path("big.mosb"), 300, 300)
        staging = os.path.join(store, ".staging")
        for sig in (signal.SIGINT, signal.SIGKILL):
            with self.subTest(signal=sig):
                p = subprocess.Popen([MOSB, "store", "add", "--pack", store, big],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                deadline = time.time() + 30
                while not (os.path.isdir(staging) and os.listdir(staging)) and p.poll() is None \
                        and time.time() < deadline:
                    time.sleep(0.002)
                p.send_signal(sig)  # while it packs (seconds at the default level)
                p.wait()
                # Its own staging directory, which it had no chance to remove.
                self.assertEqual(len(os.listdir(staging)), 1)
                self.ok("store", "add", store, grid(self.path("g4.mosb"), 4))
                left = [n for n in os.listdir(store) if n.startswith(".") and n != ".lock"]
                self.assertEqual(left, [])
                listed = json.loads(self.ok("store", "list", "--json", store).stdout)["entries"]
                self.assertEqual([e["file"] for e in listed], ["g3.mosb", "g4.mosb"])

    def test_a_refused_packed_entry_leaves_no_empty_cache(self):
        store = self.path("store")
        self.ok("store", "init", store)
        self.ok("store", "add", "--pack", store, grid(self.path("g7.mosb"), 7, height=7))
        target = os.path.join(store, "g7.mosb")
        data = bytearray(read(target))
        e = entry(data, "forward_offsets")
        data[e["offset"] + e["stored_length"] // 2] ^= 0x04
        with open(target, "wb") as f:
            f.write(data)
        r = self.mosb("store", "instance", store, "Grid_3")
        self.assert_one_line_error(r, target)
        self.assertFalse(os.path.lexists(os.path.join(store, ".cache")))

    def test_move_keeps_the_source_until_its_copy_is_listed(self):
        # A destination that cannot take the file (here a directory where it goes): the add
        # fails and the source is still there, the manifest as it was.
        store = self.store_with(3)
        os.mkdir(os.path.join(store, "g5.mosb"))
        source = grid(self.path("g5.mosb"), 5)
        data = read(source)
        before = read(os.path.join(store, "MANIFEST"))
        r = self.mosb("store", "add", "--move", store, source)
        self.assert_one_line_error(r, "g5.mosb")
        self.assertEqual(read(source), data)
        self.assertEqual(read(os.path.join(store, "MANIFEST")), before)

    def test_move_onto_a_full_disk_keeps_the_source(self):
        # The store on a small tmpfs (another file system: --move copies), too small for the file.
        if os.geteuid() != 0:
            raise mosbtest.missing("needs root for a private tmpfs mount")
        small = self.path("small")
        os.mkdir(small)
        source = grid(self.path("big.mosb"), 200, 200)
        data = read(source)
        script = ('mount -t tmpfs -o size=256k tmpfs "$1" || exit 77; "$0" store init "$1/s" && '
                  '"$0" store add "$1/s" "$3"; "$0" store add --move "$1/s" "$2"; echo "rc=$?"; '
                  'cat "$1/s/MANIFEST"; ls -A "$1/s"')
        r = subprocess.run(["unshare", "-m", "sh", "-c", script, MOSB, small, source,
                            grid(self.path("g3.mosb"), 3)], capture_output=True, text=True)
        if r.returncode == 77 or "rc=" not in r.stdout:
            raise mosbtest.missing("no private tmpfs mount allowed here: %s" % r.stderr)
        self.assertIn("No space left on device", r.stderr)
        self.assertIn("rc=1", r.stdout)
        self.assertNotIn("big.mosb", r.stdout)  # not listed, no file, no temporary left
        self.assertIn('"file":"g3.mosb"', r.stdout)
        self.assertEqual(read(source), data)


class Sources(Base):
    def test_verify_sources_says_a_fifo_is_not_a_regular_file(self):
        raw = self.path("raw")
        os.mkdir(raw)
        gr = os.path.join(raw, "tiny.gr")
        with open(gr, "w") as f:
            f.write(GR)
        out = self.path("tiny.mosb")
        self.ok("convert", "dimacs", "--gr", gr, "-o", out)
        os.remove(gr)
        os.mkfifo(gr)
        r = run("verify", "--sources", raw, out, timeout=60)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stdout, "FAIL " + gr + ": not a regular file\n")

    def test_verify_sources_names_missing_and_changed_raw_files(self):
        raw = self.path("raw")
        os.mkdir(raw)
        gr = os.path.join(raw, "tiny.gr")
        with open(gr, "w") as f:
            f.write(GR)
        out = self.path("tiny.mosb")
        self.ok("convert", "dimacs", "--gr", gr, "-o", out)
        r = self.ok("verify", "--sources", raw, out)
        self.assertIn("OK   " + gr, r.stdout)
        with open(gr, "w") as f:
            f.write(GR.replace("a 1 2 5", "a 1 2 6"))  # same size, other bytes
        r = run("verify", "--sources", raw, out)
        self.assertEqual(r.returncode, 1)
        self.assertIn("FAIL " + gr + ": XXH3", r.stdout)
        with open(gr, "w") as f:
            f.write(GR + "c comment\n")
        r = run("verify", "--sources", raw, out)
        self.assertIn("FAIL " + gr + ": %d bytes" % (len(GR) + 10), r.stdout)
        os.remove(gr)
        r = run("verify", "--sources", raw, out, "--json")
        self.assertEqual(r.returncode, 1)
        report = json.loads(r.stdout)
        self.assertEqual([(s["name"], s["ok"]) for s in report["sources"]], [("tiny.gr", False)])
        self.assertIn("missing", report["sources"][0]["problem"])


class ExpectDigest(Base):
    def test_right_digest_writes_wrong_digest_writes_nothing(self):
        gr = self.path("tiny.gr")
        with open(gr, "w") as f:
            f.write(GR)
        first = self.path("first.mosb")
        self.ok("convert", "dimacs", "--gr", gr, "-o", first)
        digest = json.loads(self.ok("inspect", "--json", first).stdout)["digest"]
        second = self.path("second.mosb")
        self.ok("convert", "dimacs", "--gr", gr, "-o", second, "--expect-digest", digest.upper())
        self.assertEqual(read(first), read(second))
        wrong = "0" * 32
        before = sorted(os.listdir(self.dir))
        r = run("convert", "dimacs", "--gr", gr, "-o", self.path("third.mosb"),
                "--expect-digest", wrong)
        self.assertEqual(r.returncode, 1)
        self.assertIn(digest, r.stderr)
        self.assertIn(wrong, r.stderr)
        self.assertEqual(len(r.stderr.splitlines()), 1)
        self.assertEqual(sorted(os.listdir(self.dir)), before, "nothing written, no temporary")
        # An existing output is left as it was.
        r = run("convert", "dimacs", "--gr", gr, "-o", first, "--expect-digest", wrong)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(read(first), read(second))
        # Generators take it too; a malformed digest is a usage error.
        g = grid(self.path("g.mosb"), 3)
        gd = json.loads(self.ok("inspect", "--json", g).stdout)["digest"]
        self.ok("generate", "grid", "--width", "3", "--height", "4", "-o", self.path("g2.mosb"),
                "--expect-digest", gd)
        self.assertEqual(run("generate", "netmaker", "--vertices", "100", "-o", self.path("n.mosb"),
                             "--expect-digest", wrong).returncode, 1)
        self.assertFalse(os.path.exists(self.path("n.mosb")))
        self.assertEqual(run("generate", "grid", "-o", self.path("x.mosb"), "--expect-digest",
                             "xyz").returncode, 2)


class SuiteBuild(Base):
    def test_two_builds_give_the_same_manifest_bytes(self):
        # The full suite takes minutes; the same code path over a subset is what `suite build`
        # runs (converters::run_suite), so the determinism check here uses the subset generators.
        for name, threads in (("a", "1"), ("b", "2")):
            self.ok("generate", "grid", "--suite", self.path(name), "--sizes", "20,30", "--threads",
                    threads)
        self.assertEqual(read(self.path("a", "MANIFEST")), read(self.path("b", "MANIFEST")))
        self.ok("store", "verify", self.path("a"))

    def test_benchmark_patterns_select_what_is_built(self):
        r = self.ok("suite", "build", self.path("s"), "--benchmark", "Grid-300x30*", "--benchmark",
                    "NetMaker-N10000-I20-1", "--json")
        names = [i["name"] for i in json.loads(r.stdout)["instances"]]
        self.assertEqual(names, ["Grid-300x300", "NetMaker-N10000-I20-1"])
        self.ok("store", "verify", self.path("s"))
        r = run("suite", "build", self.path("t"), "--benchmark", "Grid-9*")
        self.assertEqual(r.returncode, 2)
        self.assertIn("'Grid-9*' matches no benchmark", r.stderr)
        self.assertFalse(os.path.exists(self.path("t", "MANIFEST")))

    def test_a_second_build_adds_to_the_manifest(self):
        s = self.path("s")
        self.ok("suite", "build", s, "--benchmark", "NetMaker-N10000-I20-1")
        r = self.ok("suite", "build", s, "--benchmark", "Grid-300x300", "--json")
        listed = [(i["name"], i["kept"]) for i in json.loads(r.stdout)["instances"]]
        self.assertEqual(listed, [("Grid-300x300", False), ("NetMaker-N10000-I20-1", True)])
        _, entries = self.records(self.path("s", "MANIFEST"))
        self.assertEqual([e["file"] for e in entries],
                         ["Grid-300x300.mosb", "NetMaker-N10000-I20-1.mosb"])
        self.assertIn("0 with problems", self.ok("store", "verify", s).stdout)
        # A kept entry is checked: a damaged one refuses the build before anything is written.
        manifest = read(self.path("s", "MANIFEST"))
        with open(self.path("s", "NetMaker-N10000-I20-1.mosb"), "r+b") as f:
            f.seek(200)
            byte = f.read(1)
            f.seek(200)
            f.write(bytes([byte[0] ^ 1]))
        r = run("suite", "build", s, "--benchmark", "Grid-300x300")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("NetMaker-N10000-I20-1.mosb", r.stderr)
        self.assertIn("--replace", r.stderr)
        self.assertEqual(read(self.path("s", "MANIFEST")), manifest)
        # --replace lists the built instances only.
        self.ok("suite", "build", s, "--benchmark", "Grid-300x300", "--replace")
        _, entries = self.records(self.path("s", "MANIFEST"))
        self.assertEqual([e["file"] for e in entries], ["Grid-300x300.mosb"])

    def test_a_packed_suite_is_a_store_of_packed_files(self):
        self.ok("generate", "grid", "--suite", self.path("p"), "--sizes", "20,30", "--pack")
        _, entries = self.records(self.path("p", "MANIFEST"))
        self.assertEqual(len(entries), 4)
        self.assertTrue(all(e["packed"] for e in entries))
        self.ok("store", "verify", self.path("p"))
        found = json.loads(self.ok("store", "instance", "--json", self.path("p"),
                                   "Grid-20x30/Grid_2").stdout)
        self.ok("generate", "grid", "--suite", self.path("u"), "--sizes", "20,30")
        self.assertEqual(read(found["path"]), read(self.path("u", "Grid-20x30.mosb")))
        r = run("generate", "grid", "--width", "5", "--pack", "-o", self.path("x.mosb"))
        self.assertEqual(r.returncode, 2, r)  # --pack is a suite option


if __name__ == "__main__":
    mosbtest.main()
