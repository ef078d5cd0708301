#!/usr/bin/python3
"""End-to-end tests of `mosb store pull` (spec/MANIFEST.md, "Publishing a store and pulling it")
against real servers on 127.0.0.1: Debian's nginx (nginx-light) with tests/store/nginx.conf, and
tests/store/fault_server.py for the faults nginx does not make. Each server listens on a free port
and is stopped by its PID when the test ends. Without nginx installed the nginx tests are skipped,
saying so (tools/install-deps.sh installs it).

    MOSB=build/release/tools/mosb /usr/bin/python3 tests/cli/test_pull.py
"""

import hashlib
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import tempfile
import time
import unittest

import mosbtest
from mosbtest import MOSB, CliTest, read, run, setUpModule  # noqa: F401

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
NGINX_CONF = os.path.join(HERE, "..", "store", "nginx.conf")
FAULT_SERVER = os.path.join(HERE, "..", "store", "fault_server.py")
NGINX = shutil.which("nginx") or next((p for p in ("/usr/sbin/nginx",) if os.path.exists(p)), None)


def mosb_ok(*args):
    r = run(*args)
    assert r.returncode == 0, r
    return r


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for_port(port, process, what):
    deadline = time.time() + 10
    while time.time() < deadline:
        if process.poll() is not None:
            raise AssertionError("%s ended at start: %s" % (what, process.stderr.read()))
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
            return
        except OSError:
            time.sleep(0.02)
    raise AssertionError("%s does not listen on port %d" % (what, port))


def wait_for_pid_file(path, process):
    """nginx writes its pid file (tests/store/nginx.conf) as it starts, maybe after it listens:
    waited for, so that a test comparing its directory before and after sees it in both."""
    deadline = time.time() + 10
    while not os.path.exists(path):
        if process.poll() is not None or time.time() > deadline:
            raise AssertionError("nginx wrote no %s" % path)
        time.sleep(0.01)


def stop(process):
    """Stops a server started by the test, by its PID."""
    if process.poll() is None:
        os.kill(process.pid, signal.SIGTERM)
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.kill(process.pid, signal.SIGKILL)
            process.wait()
    for stream in (process.stdout, process.stderr):
        if stream:
            stream.close()


class Published(CliTest):
    """A store written by mosb (two unpacked grids, one packed, one bigger for the slow
    transfers), published once per class; each test serves its own copy of it."""

    @classmethod
    def setUpClass(cls):
        cls.published = tempfile.mkdtemp(prefix="mosb-published-")
        src = os.path.join(cls.published, "src")
        os.mkdir(src)
        pub = os.path.join(cls.published, "pub")
        mosb_ok("store", "init", pub)
        files = []
        for name, width, height in (("g3.mosb", 3, 4), ("g4.mosb", 4, 4), ("big.mosb", 170, 170)):
            files.append(os.path.join(src, name))
            mosb_ok("generate", "grid", "--width", str(width), "--height", str(height), "--seed",
                    "1", "-o", files[-1])
        mosb_ok("store", "add", pub, *files)
        packed = os.path.join(src, "p5.mosb")
        mosb_ok("generate", "grid", "--width", "5", "--height", "5", "--seed", "2", "-o", packed)
        mosb_ok("store", "add", "--pack", pub, packed)
        cls.names = sorted(n for n in os.listdir(pub) if n.endswith(".mosb"))
        for lock in (".lock",):
            os.remove(os.path.join(pub, lock))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.published, ignore_errors=True)

    def publish(self):
        """This test's copy of the published store: self.www."""
        self.www = self.path("www")
        shutil.copytree(os.path.join(self.published, "pub"), self.www)
        self.store = self.path("store")

    def pull(self, url, *options, store=None):
        return self.mosb("store", "pull", store or self.store, url, *options, timeout=120)

    def pull_json(self, url, *options, code=0):
        r = self.pull(url, "--json", *options)
        self.assertEqual(r.returncode, code, r)
        return json.loads(r.stdout)

    def listed(self, store=None):
        out = self.ok("store", "list", "--json", store or self.store).stdout
        return [e["file"] for e in json.loads(out)["entries"]]

    def assert_identical(self, names=None):
        for name in names or self.names:
            self.assertEqual(read(os.path.join(self.store, name)), read(os.path.join(self.www, name)),
                             name)

    def assert_verifies(self):
        r = self.ok("store", "verify", "--json", self.store)
        self.assertTrue(json.loads(r.stdout)["ok"])

    def assert_no_staging(self):
        self.assertEqual(sorted(n for n in os.listdir(self.store) if n.startswith(".")),
                         [".lock"])

    def partial(self, name):
        return os.path.join(self.store, ".staging", "pull", name, name)


@unittest.skipIf(NGINX is None, mosbtest.MISSING + "nginx is not installed (Debian package nginx-light; "
                                "tools/install-deps.sh installs it)")
class AgainstNginx(Published):
    def setUp(self):
        super().setUp()
        self.publish()
        self.server = self.dir  # its www/ is the published store
        os.makedirs(os.path.join(self.server, "tmp"))
        self.port = free_port()
        with open(NGINX_CONF) as f:
            conf = f.read()
        conf = conf.replace("@DIR@", self.server).replace("@PORT@", str(self.port))
        conf = conf.replace("@USER@", "user root;" if os.geteuid() == 0 else "")
        with open(os.path.join(self.server, "nginx.conf"), "w") as f:
            f.write(conf)
        self.nginx = subprocess.Popen(
            [NGINX, "-p", self.server, "-e", os.path.join(self.server, "error.log"), "-c",
             os.path.join(self.server, "nginx.conf")],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        self.addCleanup(stop, self.nginx)
        wait_for_port(self.port, self.nginx, "nginx")
        wait_for_pid_file(os.path.join(self.server, "nginx.pid"), self.nginx)
        self.url = "http://127.0.0.1:%d/pub/" % self.port
        self.slow = "http://127.0.0.1:%d/slow" % self.port

    def requests(self, until=lambda log: True):
        """The access log: (method, uri, status, range, if-range) per request so far. nginx logs a
        request after its response is sent, so a client may exit first: the log is read again
        until `until(log)` holds (10 s at most)."""
        deadline = time.time() + 10
        while True:
            log = self.access_log()
            if until(log) or time.time() > deadline:
                return log
            time.sleep(0.01)

    def access_log(self):
        path = os.path.join(self.server, "access.log")
        if not os.path.exists(path):
            return []
        out = []
        for line in read(path, "r").splitlines():
            method, uri, status, _, wanted, if_range = re.match(
                r'(\S+) (\S+) (\d+) (\d+) "(.*)" "(.*)"$', line).groups()
            # nginx logs an absent header as "-", a quote inside one as \x22.
            out.append((method, uri, int(status),
                        *("" if x == "-" else x.replace("\\x22", '"') for x in (wanted, if_range))))
        return out

    def test_full_pull_is_byte_identical_then_nothing_is_fetched_again(self):
        report = self.pull_json(self.url, "--unpack", "--jobs", "3")
        self.assertEqual(sorted(e["file"] for e in report["fetched"]), self.names)
        self.assertEqual((report["present"], report["refused"]), ([], []))
        self.assertEqual(report["bytes"], sum(os.path.getsize(os.path.join(self.www, n))
                                              for n in self.names + ["MANIFEST"]))
        self.assert_identical()
        # The store lists what the publisher listed: the same MANIFEST bytes.
        self.assertEqual(read(os.path.join(self.store, "MANIFEST")),
                         read(os.path.join(self.www, "MANIFEST")))
        self.assert_verifies()
        # --unpack: the packed entry is mmap-ready in the cache.
        found = json.loads(self.ok("store", "instance", "--json", self.store, "Grid-5x5/Grid_2")
                           .stdout)
        self.assertEqual(found["path"], os.path.join(self.store, ".cache", "p5.mosb"))
        self.assert_no_staging_but_cache()
        before = len(self.requests())
        r = self.pull(self.url)
        self.assertEqual(r.returncode, 0, r)
        self.assertEqual(self.requests(lambda log: len(log) > before)[before:],
                         [("GET", "/pub/MANIFEST", 200, "", "")], "a second pull fetches no entry")
        self.assertIn("0 fetched, 4 present, 0 refused", r.stdout)

    def assert_no_staging_but_cache(self):
        self.assertEqual(sorted(n for n in os.listdir(self.store) if n.startswith(".")),
                         [".cache", ".lock"])

    def killed_midway(self):
        """Kills (SIGKILL) a rate-limited pull of big.mosb midway; returns the bytes it kept."""
        p = subprocess.Popen([MOSB, "store", "pull", self.store, self.slow, "--file", "big.mosb"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        partial = self.partial("big.mosb")
        deadline = time.time() + 30
        while time.time() < deadline and p.poll() is None:
            if os.path.exists(partial) and os.path.getsize(partial) > 100000:
                break
            time.sleep(0.005)
        p.kill()
        p.wait()
        reached = os.path.getsize(partial)
        size = os.path.getsize(os.path.join(self.www, "big.mosb"))
        self.assertTrue(100000 < reached < size, (reached, size))
        self.assertNotIn("big.mosb", self.listed())
        return reached

    def test_kill_9_midway_then_the_next_pull_continues_with_a_range_request(self):
        reached = self.killed_midway()
        size = os.path.getsize(os.path.join(self.www, "big.mosb"))
        report = self.pull_json(self.slow, "--file", "big.mosb")
        self.assertEqual(report["fetched"], [{"file": "big.mosb", "size": size,
                                              "received": size - reached,
                                              "resumed_from": reached, "restarted": ""}])
        last = [r for r in self.requests(lambda log: any(r[2] == 206 for r in log))
                if r[1] == "/slow/big.mosb"][-1]
        self.assertEqual(last[2:4], (206, "bytes=%d-" % reached))
        self.assertTrue(last[4].startswith('"') and last[4].endswith('"'),
                        "If-Range carries the ETag: %r" % (last,))
        self.assert_identical(["big.mosb"])
        self.assertEqual(self.listed(), ["big.mosb"])
        self.assert_verifies()
        self.assert_no_staging()

    def test_a_file_changed_on_the_server_after_a_kill_is_read_again_from_zero(self):
        self.killed_midway()
        target = os.path.join(self.www, "big.mosb")
        original = read(target)
        changed = bytearray(original)
        changed[-1] ^= 1
        with open(target, "wb") as f:
            f.write(changed)
        os.utime(target, (time.time() + 5, time.time() + 5))  # a new Last-Modified and ETag
        # If-Range no longer matches: nginx sends the whole file, the pull starts from zero, and
        # the changed bytes are refused against the MANIFEST.
        report = self.pull_json(self.slow, "--file", "big.mosb", code=1)
        self.assertIn("SHA-256 ", report["refused"][0]["reason"])
        last = [r for r in self.requests(lambda log: any(r[3] for r in log))
                if r[1] == "/slow/big.mosb"][-1]
        self.assertEqual(last[2], 200)
        self.assertTrue(last[3].startswith("bytes="), last)
        self.assertFalse(os.path.exists(self.partial("big.mosb")), "wrong bytes are not kept")
        with open(target, "wb") as f:
            f.write(original)
        report = self.pull_json(self.slow, "--file", "big.mosb")
        self.assertEqual(report["fetched"][0]["resumed_from"], 0)
        self.assert_identical(["big.mosb"])

    def test_a_partial_that_can_never_be_continued_is_swept(self):
        self.killed_midway()
        # A pull of another file leaves it: the next pull of big.mosb continues it.
        self.pull_json(self.slow, "--file", "g3.mosb")
        self.assertTrue(os.path.exists(self.partial("big.mosb")))
        # The publisher drops big.mosb: its partial can never be continued, and goes.
        manifest = os.path.join(self.www, "MANIFEST")
        lines = [line for line in read(manifest, "r").splitlines(True)
                 if '"file":"big.mosb"' not in line]
        with open(manifest, "w") as f:
            f.writelines(lines)
        self.pull_json(self.slow, "--file", "g4.mosb")
        self.assertFalse(os.path.exists(os.path.dirname(self.partial("big.mosb"))))
        self.assert_no_staging()

    def test_a_file_altered_on_the_server_is_refused_and_the_others_placed(self):
        target = os.path.join(self.www, "g4.mosb")
        data = bytearray(read(target))
        data[len(data) // 2] ^= 1
        with open(target, "wb") as f:
            f.write(data)
        r = self.pull(self.url)
        self.assertEqual(r.returncode, 1, r)
        lines = r.stderr.splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn("refused g4.mosb: SHA-256 ", lines[0])
        self.assertIn(", the MANIFEST says ", lines[0])
        self.assertFalse(os.path.exists(os.path.join(self.store, "g4.mosb")))
        self.assertEqual(self.listed(), [n for n in self.names if n != "g4.mosb"])
        self.assert_verifies()
        self.assert_no_staging()

    def test_a_manifest_that_is_not_json_lines_is_refused_before_any_fetch(self):
        for text in ('{"format": "mosb-manifest", "version": 1}\nnot json\n',
                     "<html><body>Not Found</body></html>\n"):
            with self.subTest(text=text):
                with open(os.path.join(self.www, "MANIFEST"), "w") as f:
                    f.write(text)
                before = len(self.requests())
                r = self.pull(self.url)
                self.assert_one_line_error(r, "/pub/MANIFEST:1" if "html" in text else
                                           "/pub/MANIFEST:2: not JSON")
                fetched = self.requests(lambda log: len(log) > before)[before:]
                self.assertEqual([x[1] for x in fetched], ["/pub/MANIFEST"])
                self.assertFalse(os.path.exists(self.store), "nothing written")

    def test_entry_names_escaping_the_store_are_refused_before_any_fetch(self):
        manifest = os.path.join(self.www, "MANIFEST")
        lines = read(manifest, "r").splitlines()
        outside = self.path("x")
        with open(outside, "w") as f:
            f.write("mine")
        for name in ("../x", "/tmp/x", "MANIFEST", ".cache", ".."):
            with self.subTest(name=name):
                record = json.loads(lines[1])
                record["file"] = name
                with open(manifest, "w") as f:
                    f.write("\n".join([lines[0], json.dumps(record)] + lines[2:]) + "\n")
                before = sorted(os.listdir(self.dir))
                r = self.pull(self.url)
                self.assert_one_line_error(r, "/pub/MANIFEST")
                self.assertIn(name if name != ".." else "'..'", r.stderr)
                self.assertEqual(sorted(os.listdir(self.dir)), before)
                self.assertEqual(read(outside, "r"), "mine")
                self.assertEqual([x[1] for x in self.requests()][-1], "/pub/MANIFEST")
                self.assertFalse(os.path.exists(self.store))

    def published_with_name(self, name):
        """The published MANIFEST, its first entry renamed `name`."""
        manifest = os.path.join(self.www, "MANIFEST")
        lines = read(manifest, "r").splitlines()
        record = json.loads(lines[1])
        record["file"] = name
        with open(manifest, "w") as f:
            f.write("\n".join([lines[0], json.dumps(record)] + lines[2:]) + "\n")

    def test_names_with_c1_controls_or_bidi_overrides_are_refused_before_any_fetch(self):
        # Issue 36 item 10: each passed the name rule, and `store list` printed it raw.
        for name, shown in (("g\u0085.mosb", "g\\u{0085}.mosb"),
                            ("g\u009b2J.mosb", "g\\u{009b}2J.mosb"),
                            ("g\u202ebsom.exe", "g\\u{202e}bsom.exe"),
                            ("g\u2066.mosb", "g\\u{2066}.mosb"), ("g\u2069.mosb", "g\\u{2069}.mosb"),
                            ("g\u200bid.mosb", "g\\u{200b}id.mosb")):
            with self.subTest(name=shown):
                self.published_with_name(name)
                before = len(self.requests())
                r = self.pull(self.url)
                line = self.assert_one_line_error(
                    r, "/pub/MANIFEST:2: invalid file name '%s' (a base name: UTF-8" % shown)
                self.assertNotIn(name[1], line)
                fetched = self.requests(lambda log: len(log) > before)[before:]
                self.assertEqual([x[1] for x in fetched], ["/pub/MANIFEST"])
                self.assertFalse(os.path.exists(self.store), "nothing written")

    def test_a_nul_in_an_entry_name_is_shown_whole_and_escaped(self):
        # Issue 36 item 11: the message ended at the NUL ("invalid file name 'g").
        self.published_with_name("g\u0000evil.mosb")
        r = self.pull(self.url)
        self.assert_one_line_error(
            r, "/pub/MANIFEST:2: invalid file name 'g\\x00evil.mosb' (a base name: UTF-8, no")
        self.assertFalse(os.path.exists(self.store), "nothing written")

    def test_dry_run_and_selection(self):
        r = self.ok("store", "pull", self.store, self.url, "--dry-run", "--benchmark", "Grid-[34]x4")
        self.assertIn("would fetch g3.mosb", r.stdout)
        self.assertIn("would fetch g4.mosb", r.stdout)
        self.assertIn("2 to fetch", r.stdout)
        self.assertFalse(os.path.exists(self.store))
        report = self.pull_json(self.url, "--view", "Grid_3", "--file", "*4*")
        self.assertEqual([e["file"] for e in report["fetched"]], ["g4.mosb"])
        report = self.pull_json(self.url, "--dry-run")
        self.assertEqual(sorted(e["file"] for e in report["would_fetch"]),
                         [n for n in self.names if n != "g4.mosb"])
        self.assertEqual([e["file"] for e in report["present"]], ["g4.mosb"])
        self.assertEqual(self.listed(), ["g4.mosb"])

    def test_concurrent_pulls_and_an_add_lose_nothing(self):
        self.ok("store", "init", self.store)
        added = self.path("added.mosb")
        self.ok("generate", "grid", "--width", "6", "--seed", "9", "-o", added)
        pulls = [subprocess.Popen([MOSB, "store", "pull", self.store, self.slow, "--json"],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                 for _ in range(2)]
        time.sleep(0.3)  # both are transferring big.mosb through the rate limit
        self.ok("store", "add", self.store, added)
        for p in pulls:
            out, err = p.communicate(timeout=60)
            self.assertEqual(p.returncode, 0, err)
            report = json.loads(out)
            self.assertEqual(sorted([e["file"] for e in report["fetched"]] +
                                    [e["file"] for e in report["present"]]), self.names)
        self.assertEqual(self.listed(), sorted(self.names + ["added.mosb"]))
        self.assert_identical()
        self.assert_verifies()
        self.assert_no_staging()


class AgainstFaults(Published):
    """Faults of tests/store/fault_server.py, one per test."""

    def serve(self, faults):
        self.publish()
        with open(os.path.join(self.www, ".faults"), "w") as f:
            json.dump(faults, f)
        self.log = self.path("requests.log")
        server = subprocess.Popen(["/usr/bin/python3", FAULT_SERVER, self.www, self.log],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.addCleanup(stop, server)
        port = int(server.stdout.readline())
        wait_for_port(port, server, "the fault server")
        return "http://127.0.0.1:%d" % port

    def requests(self, name):
        return [line.split(" ", 3)[2:] for line in read(self.log, "r").splitlines()
                if line.split(" ")[1] == "/" + name]

    def pulled_all(self, url, *options):
        report = self.pull_json(url, *options)
        self.assertEqual(sorted(e["file"] for e in report["fetched"]), self.names)
        self.assert_identical()
        self.assert_verifies()
        self.assert_no_staging()
        return report

    def test_connection_closed_midway_is_continued_with_a_range(self):
        url = self.serve({"big.mosb": ["close-after:50000"]})
        self.pulled_all(url)
        got = self.requests("big.mosb")
        self.assertEqual([g[0] for g in got], ["200", "206"])
        self.assertTrue(got[1][1].startswith('"bytes=50000-" ""'), got)

    def test_503_or_429_then_200_is_retried_after_retry_after(self):
        url = self.serve({"g3.mosb": ["503-once"], "g4.mosb": ["429-once"]})
        started = time.time()
        self.pulled_all(url)
        self.assertEqual([g[0] for g in self.requests("g3.mosb")], ["503", "200"])
        self.assertEqual([g[0] for g in self.requests("g4.mosb")], ["429", "200"])
        self.assertGreaterEqual(time.time() - started, 1, "Retry-After: 1 is honoured")

    def test_404_for_one_entry_refuses_it_and_places_the_others(self):
        url = self.serve({"g4.mosb": ["404"]})
        r = self.pull(url)
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual(r.stderr.splitlines(),
                         ["mosb: refused g4.mosb: %s/g4.mosb: HTTP 404" % url])
        self.assertEqual([g[0] for g in self.requests("g4.mosb")], ["404"], "no retry on a 404")
        self.assertEqual(self.listed(), [n for n in self.names if n != "g4.mosb"])
        self.assert_verifies()
        self.assert_no_staging()

    def test_a_server_ignoring_range_is_read_again_from_zero(self):
        url = self.serve({"big.mosb": ["close-after:50000", "ignore-range"]})
        report = self.pulled_all(url)
        got = self.requests("big.mosb")
        self.assertEqual([(g[0], g[1].split('" "')[0]) for g in got],
                         [("200", '"'), ("200", '"bytes=50000-')])
        big = [e for e in report["fetched"] if e["file"] == "big.mosb"][0]
        self.assertEqual(big["received"], 50000 + big["size"])

    def killed_after(self, url, at):
        """A pull of big.mosb killed (SIGKILL) once `at` bytes are in its staging file (the server
        stalls there on its first request): the partial file the next pull continues."""
        p = subprocess.Popen([MOSB, "store", "pull", self.store, url, "--file", "big.mosb"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.time() + 30
        while time.time() < deadline and p.poll() is None:
            if os.path.exists(self.partial("big.mosb")) and \
                    os.path.getsize(self.partial("big.mosb")) >= at:
                break
            time.sleep(0.005)
        p.kill()
        p.wait()
        self.assertEqual(os.path.getsize(self.partial("big.mosb")), at)

    def test_a_resume_answered_from_byte_0_says_so(self):
        # Issue 36 item 9: a resume the server answered from byte 0 was reported "resumed at
        # byte 50000" while every byte came again from zero.
        for fault, answer in (("ignore-range", "HTTP 200 and the whole file"),
                              ("wrong-range", "HTTP 206 for other bytes than asked")):
            with self.subTest(fault=fault):
                shutil.rmtree(self.path("www"), ignore_errors=True)
                shutil.rmtree(self.path("store"), ignore_errors=True)
                if os.path.exists(self.path("requests.log")):
                    os.remove(self.path("requests.log"))
                url = self.serve({"big.mosb": ["stall-after:50000"]})
                self.killed_after(url, 50000)
                with open(os.path.join(self.www, ".faults"), "w") as f:
                    json.dump({"big.mosb": [fault]}, f)
                size = os.path.getsize(os.path.join(self.www, "big.mosb"))
                said = ("the server answered the range from byte 50000 with %s: fetched from "
                        "byte 0" % answer)
                if fault == "ignore-range":
                    report = self.pull_json(url, "--file", "big.mosb")
                    fetched = report["fetched"][0]
                    self.assertEqual(
                        (fetched["received"], fetched["resumed_from"], fetched["restarted"]),
                        (size, 0, said))
                else:
                    r = self.pull(url, "--file", "big.mosb")
                    self.assertEqual(r.returncode, 0, r)
                    self.assertEqual(r.stdout.splitlines()[0],
                                     "fetched big.mosb (%d bytes; %s)" % (size, said))
                got = self.requests("big.mosb")
                self.assertEqual(got[1][1].split('" "')[0], '"bytes=50000-', got)
                self.assert_identical(["big.mosb"])
                self.assert_no_staging()

    def test_a_stalled_transfer_is_retried_after_the_stall_timeout(self):
        url = self.serve({"big.mosb": ["stall-after:20000"]})
        started = time.time()
        self.pulled_all(url, "--stall-timeout", "1")
        self.assertLess(time.time() - started, 20, "not waiting for the stalled server")
        got = self.requests("big.mosb")
        self.assertEqual([g[0] for g in got], ["200", "206"])
        self.assertTrue(got[1][1].startswith('"bytes=20000-"'), got)

    def test_an_absent_manifest_is_one_line_and_writes_nothing(self):
        url = self.serve({})
        r = self.pull(url + "/elsewhere/")
        self.assert_one_line_error(r, url + "/elsewhere/MANIFEST: HTTP 404")
        self.assertFalse(os.path.exists(self.store))

    def test_an_html_error_page_with_200_is_refused(self):
        url = self.serve({"g3.mosb": ["html"]})
        r = self.pull(url)
        self.assertEqual(r.returncode, 1, r)
        size = os.path.getsize(os.path.join(self.www, "g3.mosb"))
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertIn("mosb: refused g3.mosb: 41 bytes received, the MANIFEST says %d bytes"
                      % size, r.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.store, "g3.mosb")))
        self.assertEqual(self.listed(), [n for n in self.names if n != "g3.mosb"])
        self.assert_no_staging()


class FromADirectory(Published):
    def test_a_directory_and_a_file_url_are_pulled_like_a_server(self):
        self.publish()
        for url in (self.www, "file://" + self.www + "/"):
            with self.subTest(url=url):
                shutil.rmtree(self.store, ignore_errors=True)
                report = self.pull_json(url)
                self.assertEqual(sorted(e["file"] for e in report["fetched"]), self.names)
                self.assert_identical()
                self.assert_verifies()
                self.assert_no_staging()
        r = self.pull("ftp://example.org/store")
        self.assert_one_line_error(r, "ftp://example.org/store: not a place mosb pulls from")

    def test_what_a_pull_did_not_make_at_its_staging_file_is_replaced_never_followed(self):
        # Issue 36 item 13: a symlink there refused the entry ("Too many levels of symbolic
        # links") until removed by hand; a hard link to a file outside the store had that file
        # truncated and overwritten.
        self.publish()
        outside = self.path("outside")
        plants = {"symlink": lambda at: os.symlink(outside, at),
                  "hard link": lambda at: os.link(outside, at),
                  "directory": os.mkdir, "fifo": os.mkfifo}
        for kind, plant in plants.items():
            with self.subTest(kind=kind):
                shutil.rmtree(self.store, ignore_errors=True)
                with open(outside, "w") as f:
                    f.write("mine")
                staging = os.path.join(self.store, ".staging", "pull", "g3.mosb")
                os.makedirs(staging)
                plant(os.path.join(staging, "g3.mosb"))
                report = self.pull_json(self.www, "--file", "g3.mosb")
                self.assertEqual([e["file"] for e in report["fetched"]], ["g3.mosb"])
                self.assertEqual(read(outside, "r"), "mine")
                self.assert_identical(["g3.mosb"])
                self.assert_verifies()
                self.assert_no_staging()

    def test_in_a_small_check_memory_the_pull_is_the_same_and_refuses_a_bad_transpose(self):
        # 4 KiB: big.mosb's frames and transpose go through the spill file (an unnamed
        # temporary, so nothing is left in the store).
        self.publish()
        # A file whose reverse CSR is not the transpose, listed with its own size and SHA-256:
        # only the check that the store makes can refuse it.
        bad = os.path.join(ROOT, "spec", "golden", "1.0", "invalid", "not-transpose.mosb")
        shutil.copy(bad, os.path.join(self.www, "bad.mosb"))
        data = read(bad)
        digest = self.ok("verify", "--level", "header", bad).stdout.split("digest ")[1][:32]
        with open(os.path.join(self.www, "MANIFEST"), "a") as f:
            f.write(json.dumps({"benchmark": "", "digest": digest, "file": "bad.mosb",
                                "format_version": "1.0", "packed": False, "query_sets": [],
                                "sha256": hashlib.sha256(data).hexdigest(), "size": len(data),
                                "sources": [], "views": []}, sort_keys=True,
                               separators=(",", ":")) + "\n")
        for memory in ("4K", "64M"):
            with self.subTest(check_memory=memory):
                shutil.rmtree(self.store, ignore_errors=True)
                report = self.pull_json(self.www, "--check-memory", memory, code=1)
                self.assertEqual(sorted(e["file"] for e in report["fetched"]), self.names)
                [refused] = report["refused"]
                self.assertEqual(refused["file"], "bad.mosb")
                self.assertIn("reverse-transpose", refused["reason"])
                self.assert_identical()
                self.assert_verifies()
                self.assert_no_staging()
        r = self.pull(self.www, "--check-memory", "1K")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("--check-memory", r.stderr)

    def test_a_small_entry_whose_check_would_spill_far_more_is_refused_before_it_spills(self):
        # Issue 36 item 12: a packed entry of a few KiB whose arcs all repeat one pair is valid,
        # and its check in buckets spilled 12 bytes per arc: megabytes (with 40 million arcs,
        # 480 MB) from a download of kilobytes.
        self.publish()
        arcs = 300000
        gr = self.write("repeat.gr", "p sp 2 %d\n" % arcs + "a 1 2 1\n" * arcs)
        self.ok("convert", "dimacs", "--gr", gr, "-o", self.path("repeat.plain.mosb"))
        packed = self.path("repeat.mosb")
        self.ok("pack", self.path("repeat.plain.mosb"), "-o", packed)
        size = os.path.getsize(packed)
        self.assertLess(size, 8192)
        self.ok("store", "add", self.www, packed)  # in the default 32 MiB nothing spills
        r = self.pull(self.www, "--check-memory", "4K")
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertRegex(r.stderr, r"^mosb: refused repeat\.mosb: .*repeat\.mosb: checking it in 4096 "
                         r"bytes of memory needs up to (\d+) bytes of disk for its spill file, more "
                         r"than the limit of %d bytes \(the default: 64 times its %d bytes or 8 "
                         r"times the memory, whichever is more; --check-disk SIZE, or more "
                         r"--check-memory, allows it\)\n$" % (64 * size, size))
        needs = int(re.search(r"needs up to (\d+)", r.stderr).group(1))
        self.assertGreaterEqual(needs, 12 * arcs)
        self.assertEqual(sorted(self.listed()), self.names)
        self.assert_no_staging()
        # What the limit allows is checked and placed; `store add` takes the same option.
        report = self.pull_json(self.www, "--check-memory", "4K", "--check-disk", str(needs))
        self.assertEqual([e["file"] for e in report["fetched"]], ["repeat.mosb"])
        self.assert_no_staging()
        other = self.path("other")
        self.ok("store", "init", other)
        r = self.mosb("store", "add", other, packed, "--check-memory", "4K")
        self.assert_one_line_error(r, "needs up to %d bytes of disk" % needs)
        r = self.mosb("store", "add", other, packed, "--check-memory", "4K", "--check-disk",
                      str(needs - 1))
        self.assert_one_line_error(r, "more than the limit of %d bytes (as asked;" % (needs - 1))
        self.ok("store", "add", other, packed, "--check-memory", "4K", "--check-disk", "1G")

    def test_an_entry_the_store_lists_with_other_bytes_is_refused_without_a_transfer(self):
        self.publish()
        other = self.path("other", "g3.mosb")
        os.makedirs(os.path.dirname(other))
        self.ok("generate", "grid", "--width", "3", "--height", "4", "--seed", "7", "-o", other)
        self.ok("store", "init", self.store)
        self.ok("store", "add", self.store, other)
        r = self.pull(self.www)
        self.assertEqual(r.returncode, 1, r)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertIn("refused g3.mosb: the store already lists a different g3.mosb", r.stderr)
        self.assertEqual(read(os.path.join(self.store, "g3.mosb")), read(other))
        self.assertEqual(self.listed(), self.names)
        self.assert_verifies()


if __name__ == "__main__":
    mosbtest.main()
