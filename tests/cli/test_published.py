#!/usr/bin/python3
"""References in a store (spec/MANIFEST.md, "Solution files"): `store add` of solution files,
`store verify` of their bindings, `store pull` of references after their instances (from Debian's
nginx on 127.0.0.1, as test_pull serves stores), and `eval RESULTS --reference STORE|URL` against
the table made from the local references. Every way a reference can be wrong is refused in one
line naming the file, with nothing placed.

    MOSB=build/release/tools/mosb EXAMPLES=build/release/examples \
        /usr/bin/python3 tests/cli/test_published.py
"""

import json
import os
import shutil
import struct
import subprocess
import tempfile
import unittest

import mosbtest
import test_pull
from mosbtest import CliTest, read, run, setUpModule  # noqa: F401

EXAMPLES = os.environ.get("EXAMPLES", "")
TEMPLATE = "%s {instance} --view {view} --query {source} {target} --protocol"


def ok(*args, cwd=None):
    r = run(*args, cwd=cwd)
    assert r.returncode == 0, r
    return r


class Published(CliTest):
    """Once per class: a suite of four grids, an experiment of the example NAMOA* and BOA* on
    it, the references of three of the four instances (the fourth has none), and an approximate
    file (NAMOA* claiming ε = 0.1)."""

    @classmethod
    def setUpClass(cls):
        cls.base = tempfile.mkdtemp(prefix="mosb-published-")
        b = cls.base
        ok("generate", "grid", "--suite", os.path.join(b, "suite"), "--sizes", "10,12", "--seed",
           "1")
        with open(os.path.join(b, "exp.toml"), "w") as f:
            f.write('name = "t"\nstore = "%s"\nbenchmarks = ["Grid_2"]\n'
                    'limits = { time = "20s" }\n'
                    '[[solver]]\nname = "namoa"\ntemplate = "%s"\n'
                    '[[solver]]\nname = "boa"\ntemplate = "%s"\n'
                    % (os.path.join(b, "suite"), TEMPLATE % os.path.join(EXAMPLES, "namoa"),
                       TEMPLATE % os.path.join(EXAMPLES, "boa_star")))
        ok("experiment", "run", "exp.toml", "-o", "res", cwd=b)
        ok("solutions", "reference", "res", "--solvers", "namoa,boa", "-o", "refs", cwd=b)
        cls.instances = sorted(os.path.join(b, "suite", n) for n in os.listdir(os.path.join(
            b, "suite")) if n.endswith(".mosb"))
        cls.refs = sorted(os.path.join(b, "refs", n) for n in os.listdir(os.path.join(b, "refs")))
        assert len(cls.instances) == 4 and len(cls.refs) == 4, (cls.instances, cls.refs)
        first = cls.instances[0]
        cls.approximate = os.path.join(b, "approx.sol")
        ok("run", first, "--view", "Grid_2", "--solver", TEMPLATE % os.path.join(EXAMPLES, "namoa"),
           "--solver-name", "namoa", "--epsilon", "0.1", "-o", cls.approximate)
        cls.local = ok("eval", "res", "--reference", "refs", "--eps", "0,0.1", "--csv",
                       cwd=b).stdout

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.base, ignore_errors=True)

    def store(self, name="store", references=3):
        """A store of the four instances and the first `references` references."""
        path = self.path(name)
        self.ok("store", "init", path)
        self.ok("store", "add", path, *self.instances, *self.refs[:references])
        return path

    def manifest(self, store):
        lines = read(os.path.join(store, "MANIFEST"), "r").splitlines()
        return json.loads(lines[0]), [json.loads(x) for x in lines[1:]]

    def eval_table(self, reference):
        return self.ok("eval", os.path.join(self.base, "res"), "--reference", reference, "--eps",
                       "0,0.1", "--csv")


@unittest.skipUnless(os.path.isfile(os.path.join(EXAMPLES, "namoa")),
                     mosbtest.MISSING + "the example solvers (EXAMPLES)")
class InAStore(Published):
    def test_references_are_listed_with_their_binding_and_verified(self):
        store = self.store()
        header, entries = self.manifest(store)
        self.assertEqual(header, {"format": "mosb-manifest", "version": 2})
        solutions = [e for e in entries if e.get("kind") == "solutions"]
        self.assertEqual(len(solutions), 3)
        digests = {e["digest"]: e for e in entries if "kind" not in e}
        for e in solutions:
            self.assertIn(e["instance"], digests)
            self.assertEqual(e["benchmark"], digests[e["instance"]]["benchmark"])
            self.assertEqual((e["epsilon"], e["solver"], e["solvers"]),
                             ("0", "reference", ["namoa", "boa"]))
            self.assertEqual(e["views"], ["Grid_2"])
            self.assertEqual(sum(e["statuses"].values()), 1)
        listed = json.loads(self.ok("store", "list", "--json", store).stdout)["entries"]
        self.assertEqual(sorted(e["kind"] for e in listed), ["instance"] * 4 + ["solutions"] * 3)
        self.assertIn("exact", self.ok("store", "list", store).stdout)
        self.assertTrue(json.loads(self.ok("store", "verify", "--json", store).stdout)["ok"])
        # The same files again are a retry: accepted, the MANIFEST unchanged.
        before = read(os.path.join(store, "MANIFEST"))
        self.ok("store", "add", store, *self.refs[:3])
        self.assertEqual(read(os.path.join(store, "MANIFEST")), before)

    def test_packed_references_verify_evaluate_and_unpack_to_their_bytes(self):
        # spec/SOLUTIONS.md §1 (format 1.6): --pack packs solution files as it packs instances.
        store = self.path("packed")
        self.ok("store", "init", store)
        self.ok("store", "add", "--pack", store, *self.instances, *self.refs)
        _, entries = self.manifest(store)
        solutions = [e for e in entries if e.get("kind") == "solutions"]
        self.assertEqual(len(solutions), 4)
        for e in solutions:
            self.assertEqual((e["packed"], e["format_version"]), (True, "1.6"), e["file"])
            with open(os.path.join(store, e["file"]), "rb") as f:
                self.assertEqual(f.read(16)[12:16], bytes([1, 0, 6, 0]), e["file"])
        self.assertTrue(json.loads(self.ok("store", "verify", "--json", store).stdout)["ok"])
        self.assertEqual(self.eval_table(store).stdout.splitlines()[1:],
                         self.local.splitlines()[1:])
        for ref in self.refs:
            stored = os.path.join(store, os.path.basename(ref))
            self.ok("unpack", stored, "-o", self.path("back.sol"))
            self.assertEqual(read(self.path("back.sol")), read(ref), ref)
        # A packed reference damaged in its frames is found by store verify, and eval refuses it.
        name = solutions[0]["file"]
        data = bytearray(read(os.path.join(store, name)))
        table, count = struct.unpack_from("<QI", data, 48)
        frames = [struct.unpack_from("<QQ", data, table + 64 * i + 40)
                  for i in range(count) if data[table + 64 * i + 27] != 0]
        self.assertTrue(frames)
        offset, length = frames[0]
        data[offset + length // 2] ^= 0xFF  # inside the first zstd frame
        with open(os.path.join(store, name), "wb") as f:
            f.write(data)
        r = self.mosb("store", "verify", store)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn(name, r.stdout + r.stderr)

    def test_an_instance_is_removed_only_with_or_after_its_references(self):
        store = self.store()
        _, entries = self.manifest(store)
        instance = os.path.basename(self.instances[0])
        reference = next(e["file"] for e in entries if e.get("kind") == "solutions"
                         and e["instance"] == next(x["digest"] for x in entries
                                                   if x["file"] == instance))
        before = read(os.path.join(store, "MANIFEST"))
        r = self.mosb("store", "remove", store, instance)
        self.assert_one_line_error(r, instance, "its references stay in the store", reference)
        r = self.mosb("store", "remove", store, "nosuch.mosb")
        self.assert_one_line_error(r, "nosuch.mosb", "not listed")
        self.assertEqual(read(os.path.join(store, "MANIFEST")), before)
        self.assertTrue(os.path.exists(os.path.join(store, instance)))
        # Another listed copy of the instance (the same content digest) keeps the reference bound.
        shutil.copy(self.instances[0], self.path("copy.mosb"))
        self.ok("store", "add", store, self.path("copy.mosb"))
        self.ok("store", "remove", store, "copy.mosb")
        self.assertEqual(read(os.path.join(store, "MANIFEST")), before)
        # With its reference, in one command: both gone, the store whole.
        r = self.ok("store", "remove", "--json", store, instance, reference)
        self.assertEqual(sorted(e["file"] for e in json.loads(r.stdout)["removed"]),
                         sorted([instance, reference]))
        for name in (instance, reference):
            self.assertFalse(os.path.exists(os.path.join(store, name)))
        _, left = self.manifest(store)
        self.assertEqual(len(left), len(entries) - 2)
        self.assertTrue(json.loads(self.ok("store", "verify", "--json", store).stdout)["ok"])
        # Every reference gone: the MANIFEST is version 1 again; a packed entry's unpacked copy goes
        # with it.
        refs = [e["file"] for e in left if e.get("kind") == "solutions"]
        self.ok("store", "remove", store, *refs)
        self.assertEqual(self.manifest(store)[0]["version"], 1)
        packed = self.path("packed-store")
        self.ok("store", "init", packed)
        self.ok("store", "add", "--pack", packed, self.instances[1])
        name = os.path.basename(self.instances[1])
        benchmark = self.manifest(packed)[1][0]["benchmark"]
        self.ok("store", "instance", packed, benchmark)
        self.assertTrue(os.path.exists(os.path.join(packed, ".cache", name)))
        self.ok("store", "remove", packed, name)
        self.assertFalse(os.path.exists(os.path.join(packed, ".cache", name)))
        self.assertEqual(self.manifest(packed)[1], [])

    def test_a_reference_without_its_instance_is_refused_and_nothing_placed(self):
        store = self.path("s")
        self.ok("store", "init", store)
        before = sorted(os.listdir(store)), read(os.path.join(store, "MANIFEST"))
        r = self.mosb("store", "add", store, self.instances[1], self.refs[0])
        self.assert_one_line_error(r, self.refs[0], "which the store does not list")
        self.assertEqual((sorted(os.listdir(store)), read(os.path.join(store, "MANIFEST"))),
                         before)

    def test_a_second_exact_file_of_one_binding_is_refused(self):
        store = self.store()
        # NAMOA*'s own exact fronts of the instance the first reference answers.
        namoa = shutil.copy(os.path.join(self.base, "res", "cells", "namoa",
                                         os.path.basename(self.refs[0])), self.path("namoa.sol"))
        before = read(os.path.join(store, "MANIFEST"))
        r = self.mosb("store", "add", store, namoa)
        self.assert_one_line_error(r, "exact fronts of instance", "already holds")
        self.assertEqual(read(os.path.join(store, "MANIFEST")), before)

    def test_damaged_or_truncated_references_are_refused_and_nothing_placed(self):
        data = read(self.refs[0])
        meta = data.find(b"solution.instance_digest")
        # Every class of byte the instance tests flip: header, section table, a payload (the
        # statuses and fronts at the end), the metadata; and three truncations.
        cases = {"header": 30, "table": 130, "payload": len(data) - 9, "metadata": meta + 3}
        files = []
        for what, at in cases.items():
            bad = bytearray(data)
            bad[at] ^= 0x01
            files.append((what, self.write("bad/%s/%s" % (what, os.path.basename(self.refs[0])),
                                           bytes(bad))))
        for size in (0, 100, len(data) - 1):
            files.append(("truncated to %d" % size,
                          self.write("cut/%d/%s" % (size, os.path.basename(self.refs[0])),
                                     data[:size])))
        store = self.store(references=0)
        before = read(os.path.join(store, "MANIFEST"))
        for what, path in files:
            with self.subTest(what):
                r = self.mosb("store", "add", store, path)
                self.assert_one_line_error(r, path)
                self.assertEqual(read(os.path.join(store, "MANIFEST")), before)
                self.assertNotIn(os.path.basename(path), os.listdir(store))

    def test_store_verify_finds_a_changed_reference_and_an_unbound_one(self):
        store = self.store()
        name = os.path.basename(self.refs[0])
        data = bytearray(read(os.path.join(store, name)))
        data[-9] ^= 0x01
        with open(os.path.join(store, name), "wb") as f:
            f.write(data)
        # A hand-edited MANIFEST that no longer lists the instance of the second reference.
        header, entries = self.manifest(store)
        second = next(e for e in entries if e["file"] == os.path.basename(self.refs[1]))
        kept = [e for e in entries if e["digest"] != second["instance"]]
        with open(os.path.join(store, "MANIFEST"), "w") as f:
            for record in [header] + kept:
                f.write(json.dumps(record, sort_keys=True, separators=(",", ":")) + "\n")
        r = self.mosb("store", "verify", "--json", store)
        self.assertEqual(r.returncode, 1, r)
        problems = {f["file"]: sorted(p["kind"] for p in f["problems"])
                    for f in json.loads(r.stdout)["files"] if f["problems"]}
        self.assertEqual(problems[name], ["damaged", "wrong-sha256"])
        self.assertEqual(problems[second["file"]], ["unbound"])
        # eval refuses the changed file rather than reading it.
        r = self.mosb("eval", os.path.join(self.base, "res"), "--reference", store)
        self.assert_one_line_error(r, name, "not used as a reference")

    def test_eval_against_a_store_is_the_table_of_the_local_references(self):
        def body(text):  # the table without its caption, which names the source
            return text.splitlines()[1:]
        full = self.store("full", references=4)
        r = self.eval_table(full)
        self.assertEqual(body(r.stdout), body(self.local))
        self.assertEqual(r.stderr, "")
        # The fourth instance has no reference in this store: said, not skipped silently.
        r = self.eval_table(self.store())
        self.assertEqual(r.stderr.count("has no reference for"), 1, r.stderr)
        self.assertIn(os.path.basename(self.instances[3]), r.stderr)
        self.assertNotEqual(body(r.stdout), body(self.local))


@unittest.skipUnless(os.path.isfile(os.path.join(EXAMPLES, "namoa")),
                     mosbtest.MISSING + "the example solvers (EXAMPLES)")
class Released(Published):
    def release(self, name, references=None):
        return self.mosb("suite", "release", os.path.join(self.base, "res"), "--references",
                         references or os.path.join(self.base, "refs"), "-o", self.path(name))

    def test_a_release_is_a_verified_store_with_its_summary_and_readme_and_reproducible(self):
        r = self.release("rel")
        self.assertEqual(r.returncode, 0, r)
        self.assertIn("4 instances, 4 references", r.stdout)
        header, entries = self.manifest(self.path("rel"))
        self.assertEqual(header["version"], 2)
        # The instances packed, the references raw unless --pack-references (format 1.6).
        self.assertEqual([e["packed"] for e in entries], ["kind" not in e for e in entries])
        self.assertEqual(sum(1 for e in entries if e.get("kind") == "solutions"), 4)
        self.assertTrue(json.loads(self.ok("store", "verify", "--json",
                                           self.path("rel")).stdout)["ok"])
        # SUMMARY.csv is the report's suite table of the same results and references.
        self.ok("report", os.path.join(self.base, "res"), "--reference",
                os.path.join(self.base, "refs"), "-o", self.path("r.html"), "--csv",
                self.path("tables"))
        self.assertEqual(read(self.path("rel", "SUMMARY.csv")),
                         read(self.path("tables", "suite.csv")))
        text = read(self.path("rel", "README.md"), "r")
        for expected in ("# t: instances and reference fronts", "Limits per query: `time=20s",
                         "Solver `namoa`", "Solver `boa`", "executable SHA-256",
                         "exact solvers namoa, boa where they agree",
                         "per-query statistics of namoa", "- Machine: ", "4 instances"):
            self.assertIn(expected, text)
        # The same inputs give the same bytes.
        self.assertEqual(self.release("again").returncode, 0)
        for name in sorted(os.listdir(self.path("rel"))):
            self.assertEqual(read(self.path("rel", name)), read(self.path("again", name)), name)
        # An existing, non-empty directory is refused.
        self.assert_one_line_error(self.release("rel"), "exists and is not empty")
        # --pack-references: the same store, its references packed, the same table from it.
        r = self.mosb("suite", "release", os.path.join(self.base, "res"), "--references",
                      os.path.join(self.base, "refs"), "-o", self.path("packed"),
                      "--pack-references")
        self.assertEqual(r.returncode, 0, r)
        _, packed = self.manifest(self.path("packed"))
        self.assertTrue(all(e["packed"] for e in packed))
        self.assertEqual([e["digest"] for e in packed], [e["digest"] for e in entries])
        self.assertIn("(`.sol`, packed)", read(self.path("packed", "README.md"), "r"))
        self.assertEqual(self.eval_table(self.path("packed")).stdout.splitlines()[1:],
                         self.local.splitlines()[1:])

    def test_an_approximate_or_foreign_reference_is_refused_before_anything_is_written(self):
        self.assert_one_line_error(self.release("approx", self.approximate), "approx.sol",
                                   "claims epsilon 0.1")
        self.assertFalse(os.path.exists(self.path("approx")))
        # A reference of an instance the experiment did not run.
        ok("generate", "grid", "--width", "5", "--height", "5", "--seed", "9", "-o",
           self.path("other.mosb"))
        ok("run", self.path("other.mosb"), "--view", "Grid_2", "--solver",
           TEMPLATE % os.path.join(EXAMPLES, "namoa"), "--solver-name", "namoa", "-o",
           self.path("other.sol"))
        self.assert_one_line_error(self.release("foreign", self.path("other.sol")), "other.sol",
                                   "which the experiment did not run")
        self.assertFalse(os.path.exists(self.path("foreign")))

    def test_an_instance_left_without_a_reference_is_said(self):
        refs = self.path("three")
        os.makedirs(refs)
        for path in self.refs[:3]:
            shutil.copy(path, refs)
        r = self.release("rel", refs)
        self.assertEqual(r.returncode, 0, r)
        missing = os.path.basename(self.instances[3])
        self.assertIn("mosb: note: %s has no reference" % missing, r.stderr)
        self.assertIn("Instances without a reference: `%s`" % missing,
                      read(self.path("rel", "README.md"), "r"))


@unittest.skipUnless(os.path.isfile(os.path.join(EXAMPLES, "namoa")),
                     mosbtest.MISSING + "the example solvers (EXAMPLES)")
@unittest.skipIf(test_pull.NGINX is None, mosbtest.MISSING + "nginx is not installed "
                 "(Debian package nginx-light; tools/install-deps.sh installs it)")
class Served(Published):
    def setUp(self):
        super().setUp()
        # nginx serves self.dir/www/ at /pub/, as in test_pull: the experiment released (issue
        # 45: the instances and references a publisher serves, as suite release writes them).
        self.published = self.path("www")
        self.ok("suite", "release", os.path.join(self.base, "res"), "--references",
                os.path.join(self.base, "refs"), "-o", self.published)
        if os.path.exists(os.path.join(self.published, ".lock")):
            os.remove(os.path.join(self.published, ".lock"))
        os.makedirs(self.path("tmp"))
        self.port = test_pull.free_port()
        with open(test_pull.NGINX_CONF) as f:
            conf = f.read()
        conf = conf.replace("@DIR@", self.dir).replace("@PORT@", str(self.port))
        conf = conf.replace("@USER@", "user root;" if os.geteuid() == 0 else "")
        with open(self.path("nginx.conf"), "w") as f:
            f.write(conf)
        nginx = subprocess.Popen(
            [test_pull.NGINX, "-p", self.dir, "-e", self.path("error.log"), "-c",
             self.path("nginx.conf")],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        self.addCleanup(test_pull.stop, nginx)
        test_pull.wait_for_port(self.port, nginx, "nginx")
        test_pull.wait_for_pid_file(self.path("nginx.pid"), nginx)
        self.url = "http://127.0.0.1:%d/pub/" % self.port
        self.env = dict(os.environ, MOSB_STORE_CACHE=self.path("cache"))

    def test_pulled_verified_and_evaluated_by_url_as_from_the_local_references(self):
        store = self.path("pulled")
        r = self.ok("store", "pull", store, self.url, "--json")
        fetched = [e["file"] for e in json.loads(r.stdout)["fetched"]]
        self.assertEqual(len(fetched), 8)
        self.assertTrue(json.loads(self.ok("store", "verify", "--json", store).stdout)["ok"])
        for name in fetched:
            self.assertEqual(read(os.path.join(store, name)),
                             read(os.path.join(self.published, name)), name)
        # Graphs alone.
        bare = self.path("bare")
        r = self.ok("store", "pull", bare, self.url, "--no-references", "--json")
        self.assertEqual(sorted(e["file"] for e in json.loads(r.stdout)["fetched"]),
                         sorted(os.path.basename(p) for p in self.instances))
        # eval by URL: the references of the results' instances pulled into the cache, checked,
        # and the table equal to the one of the local references; a second eval fetches nothing.
        r = self.ok("eval", os.path.join(self.base, "res"), "--reference", self.url, "--eps",
                    "0,0.1", "--csv", env=self.env)
        self.assertEqual(r.stdout.splitlines()[1:], self.local.splitlines()[1:])
        self.assertIn("pulled 8 files", r.stderr)
        again = self.ok("eval", os.path.join(self.base, "res"), "--reference", self.url, "--eps",
                        "0,0.1", "--csv", env=self.env)
        self.assertEqual(again.stdout, r.stdout)
        self.assertEqual(again.stderr, "")
        # The release with its references packed (format 1.6): pulled, checked and evaluated by
        # URL to the same table.
        shutil.rmtree(self.published)
        self.ok("suite", "release", os.path.join(self.base, "res"), "--references",
                os.path.join(self.base, "refs"), "-o", self.published, "--pack-references")
        if os.path.exists(os.path.join(self.published, ".lock")):
            os.remove(os.path.join(self.published, ".lock"))
        packed = self.path("pulled-packed")
        self.ok("store", "pull", packed, self.url)
        self.assertTrue(all(e["packed"] for e in self.manifest(packed)[1]))
        self.assertTrue(json.loads(self.ok("store", "verify", "--json", packed).stdout)["ok"])
        r = self.ok("eval", os.path.join(self.base, "res"), "--reference", self.url, "--eps",
                    "0,0.1", "--csv", env=dict(self.env, MOSB_STORE_CACHE=self.path("cache2")))
        self.assertEqual(r.stdout.splitlines()[1:], self.local.splitlines()[1:])

    def test_a_published_manifest_that_lies_about_a_reference_is_refused(self):
        header, entries = self.manifest(self.published)
        name = os.path.basename(self.refs[0])
        for what, edit, expected in (
                ("an approximate file offered as exact", None, "describes other fronts"),
                ("another epsilon", ("epsilon", "0.5"), "describes other fronts"),
                ("an instance called a solution file", "kind", "lists as an instance")):
            with self.subTest(what):
                listed = [dict(e) for e in entries]
                if edit is None:
                    # approx.sol under the reference's name, listed with its own size, SHA-256
                    # and digest (as a store of its own lists it), as the exact reference.
                    own = self.path("own-%d" % len(what))
                    self.ok("store", "init", own)
                    self.ok("store", "add", own, self.instances[0], self.approximate)
                    mine = next(x for x in self.manifest(own)[1] if x["file"] == "approx.sol")
                    self.assertEqual(mine["epsilon"], "0.1")
                    shutil.copy(self.approximate, os.path.join(self.published, name))
                    e = next(x for x in listed if x["file"] == name)
                    e.update({k: mine[k] for k in ("size", "sha256", "digest")})
                elif edit == "kind":
                    shutil.copy(self.refs[0], os.path.join(self.published, name))
                    e = next(x for x in listed if x["file"] == name)
                    del e["kind"]
                else:
                    shutil.copy(self.refs[0], os.path.join(self.published, name))
                    e = next(x for x in listed if x["file"] == name)
                    e[edit[0]] = edit[1]
                with open(os.path.join(self.published, "MANIFEST"), "w") as f:
                    for record in [header] + listed:
                        f.write(json.dumps(record, sort_keys=True, separators=(",", ":")) + "\n")
                store = self.path("pulled-%d" % len(what))
                r = self.mosb("store", "pull", store, self.url)
                self.assertEqual(r.returncode, 1, r)
                refused = [x for x in r.stderr.splitlines() if x.startswith("mosb: refused")]
                self.assertEqual(len(refused), 1, r.stderr)
                self.assertIn(name, refused[0])
                self.assertIn(expected, refused[0])
                self.assertNotIn(name, os.listdir(store))

    def test_a_manifest_listing_a_reference_twice_is_refused_before_any_fetch(self):
        lines = read(os.path.join(self.published, "MANIFEST"), "r").splitlines()
        twice = next(x for x in lines if '"kind":"solutions"' in x)
        with open(os.path.join(self.published, "MANIFEST"), "w") as f:
            f.write("\n".join(lines + [twice]) + "\n")
        r = self.mosb("store", "pull", self.path("s"), self.url)
        self.assert_one_line_error(r, "MANIFEST", "listed twice")
        self.assertFalse(os.path.exists(self.path("s")))


if __name__ == "__main__":
    mosbtest.main()
