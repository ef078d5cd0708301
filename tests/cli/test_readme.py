#!/usr/bin/python3
"""Every ```sh block of README.md runs, in README order, in one scratch directory, so the
documentation cannot drift from the program (issue 19 §5).

    MOSB_BUILD_DIR=build/release MOSB_SOURCE_DIR=. /usr/bin/python3 tests/cli/test_readme.py

A block runs under `bash -euo pipefail` with the build's `tools/` first on PATH (so `mosb` is the
program under test) and `build/release` in the scratch directory pointing at the build tree (for
the example solvers). What the README's commands read but a user would have downloaded is made
here, in `downloads/`:

* `solvers/multiobj`, `solvers/mohs`: A*pex and mohs as a user builds them, here their stand-ins
  (standin_solvers.py), which speak the same interfaces;
* `USA-road-NY-queries`: the real query file of PPA*'s repository (shared/data);
* `USA-road-d.NY.gr.gz`, `USA-road-t.NY.gr.gz`, `USA-road-d.NY.co.gz`: a synthetic stand-in for
  the DIMACS NY road network with the real file's vertex count (264,346), so that the real queries
  apply: a two-way ring plus random two-way chords, distances 1..1999, times about 3 x distance
  (the real files are 100+ MB; the commands are the same).

Two placeholders are filled in: `DIGEST` in `--expect-digest DIGEST` becomes the digest of what the
same command writes without that option (what a publisher's MANIFEST would list), and the URL
`https://mosb.example.org/suite/` becomes that of Debian's nginx on 127.0.0.1 (tests/store/nginx.conf,
a free port, stopped by its PID), serving the scratch directory's `published/`: the README's pull
goes over HTTP as a user's would.

Blocks in the sections of ELSEWHERE run in other tests or in CI itself; this test checks that each
still names its commands there, so that a changed block is noticed.
"""

import gzip
import json
import os
import random
import re
import shlex
import shutil
import socket
import subprocess
import tempfile
import time
import unittest
import mosbtest  # noqa: E402 (main: the suites' skip exit code)

SOURCE = os.path.abspath(os.environ.get("MOSB_SOURCE_DIR", "."))
BUILD = os.path.abspath(os.environ.get("MOSB_BUILD_DIR", os.path.join(SOURCE, "build", "release")))
DATA = os.path.join(SOURCE, "..", "shared", "data")
NY_QUERIES = os.path.join(DATA, "dimacs-queries", "USA-road-NY-queries")
NGINX_CONF = os.path.join(SOURCE, "tests", "store", "nginx.conf")
PUBLISHED_URL = "https://mosb.example.org/suite/"

# Section heading → (file, text it must contain): where that section's commands run.
ELSEWHERE = {
    "Quick start": [("tests/run-all.sh", "bash tools/quickstart.sh"), (".ci/run", "tests/run-all.sh")],
    "Python": [("tests/python/test_package.py", "'## Python' section")],
    "Use mosb in your solver": [("tests/install/test_install.py", "pkg-config"),
                                ("tests/install/test_install.py", "--libs")],
    "The same on SLURM": [("tests/cli/test_slurm.py", 'README_SECTION = "The same on SLURM"'),
                          ("tests/cli/CMakeLists.txt", "foreach(name cli_slurm")],
    "Building and testing by hand": [("tests/run-all.sh", "cmake --preset sanitize"),
                                     ("tests/run-all.sh", "ctest --preset release"),
                                     ("tests/run-all.sh", "tests/fuzz/run.sh")],
}


def sh_blocks():
    """(section heading, first line number, text) of every ```sh block, in order."""
    blocks, heading, block, start = [], None, None, 0
    with open(os.path.join(SOURCE, "README.md"), encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if block is not None:
                if line.startswith("```"):
                    blocks.append((heading, start, "".join(block)))
                    block = None
                else:
                    block.append(line)
            elif line.startswith("```sh"):
                block, start = [], number + 1
            elif line.startswith("#"):
                heading = line.lstrip("#").strip()
    return blocks


def write_synthetic_ny(directory):
    n, rng = 264346, random.Random(1)
    arcs = []
    for v in range(n):
        arcs += [(v, (v + 1) % n), ((v + 1) % n, v)]
    for _ in range(20000):
        a, b = rng.randrange(n), rng.randrange(n)
        arcs += [(a, b), (b, a)]
    distance = [rng.randrange(1, 2000) for _ in arcs]
    time = [3 * d + rng.randrange(50) for d in distance]
    for kind, costs in (("d", distance), ("t", time)):
        with gzip.open(os.path.join(directory, "USA-road-%s.NY.gr.gz" % kind), "wt") as f:
            f.write("c synthetic stand-in for USA-road-%s.NY\np sp %d %d\n" % (kind, n, len(arcs)))
            f.write("".join("a %d %d %d\n" % (u + 1, v + 1, c) for (u, v), c in zip(arcs, costs)))
    with gzip.open(os.path.join(directory, "USA-road-d.NY.co.gz"), "wt") as f:
        f.write("p aux sp co %d\n" % n)
        f.write("".join("v %d %d %d\n" % (v + 1, -74000000 + v, 40000000 + (v * 7919) % 1000000)
                        for v in range(n)))


class Readme(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="mosb-readme-")
        self.env = dict(os.environ, PATH=os.path.join(BUILD, "tools") + os.pathsep + os.environ["PATH"])
        self.env.pop("MOSB_ISOLATION", None)  # the README's commands run as a user's do: sealed
        # `eval --reference URL` pulls into this scratch directory, not the user's cache.
        self.env["MOSB_STORE_CACHE"] = os.path.join(self.dir, "store-cache")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def bash(self, script, where):
        done = subprocess.run(["bash", "-euo", "pipefail", "-c", script], cwd=self.dir, env=self.env,
                              capture_output=True, text=True, errors="replace", timeout=900)
        self.assertEqual(done.returncode, 0, "README.md:%s failed:\n%s\n--- stdout\n%s\n--- stderr\n%s"
                         % (where, script, done.stdout[-3000:], done.stderr[-3000:]))
        return done.stdout

    def serve_published(self):
        """nginx on a free loopback port serving DIR/published/ at /pub/; returns its URL."""
        nginx = shutil.which("nginx") or shutil.which("nginx", path="/usr/sbin:/sbin")
        self.assertIsNotNone(nginx, "nginx is not installed (tools/install-deps.sh installs it)")
        server = os.path.join(self.dir, ".nginx")
        os.makedirs(os.path.join(server, "tmp"))
        os.symlink(os.path.join(self.dir, "published"), os.path.join(server, "www"))
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        with open(NGINX_CONF) as f:
            conf = f.read().replace("@DIR@", server).replace("@PORT@", str(port))
        conf = conf.replace("@USER@", "user root;" if os.geteuid() == 0 else "")
        with open(os.path.join(server, "nginx.conf"), "w") as f:
            f.write(conf)
        nginx = subprocess.Popen([nginx, "-p", server, "-e", os.path.join(server, "error.log"),
                                  "-c", os.path.join(server, "nginx.conf")],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.addCleanup(self.stop_nginx, nginx)
        for _ in range(500):
            self.assertIsNone(nginx.poll(), "nginx ended at its start")
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                time.sleep(0.01)
        return "http://127.0.0.1:%d/pub/" % port

    @staticmethod
    def stop_nginx(nginx):
        """SIGTERM: the master stops its workers (a SIGKILL would leave them running)."""
        nginx.terminate()
        try:
            nginx.wait(timeout=10)
        except subprocess.TimeoutExpired:
            nginx.kill()
            nginx.wait()

    def fill_placeholders(self, text, where):
        text = text.replace(PUBLISHED_URL, self.url)
        def digest(match):
            line = match.group(0)
            probe = re.sub(r"\s*--expect-digest DIGEST", "", line)
            probe = re.sub(r"-o \S+", "-o .digest-probe.mosb", probe)
            self.bash(probe, where)
            report = json.loads(self.bash("mosb inspect --json .digest-probe.mosb", where))
            os.remove(os.path.join(self.dir, ".digest-probe.mosb"))
            return line.replace("DIGEST", report["digest"])
        # A command with its continuation lines, up to the one naming DIGEST.
        return re.sub(r"(?:[^\n]*\\\n)*[^\n]*--expect-digest DIGEST", digest, text)

    def test_every_sh_block_runs(self):
        if not os.path.exists(NY_QUERIES):
            raise mosbtest.missing("shared/data is absent")
        downloads = os.path.join(self.dir, "downloads")
        os.mkdir(downloads)
        shutil.copy(NY_QUERIES, downloads)
        write_synthetic_ny(downloads)
        os.makedirs(os.path.join(self.dir, "build"))
        os.symlink(BUILD, os.path.join(self.dir, "build", "release"))
        os.symlink(os.path.join(SOURCE, "examples"), os.path.join(self.dir, "examples"))
        # The published solvers a user builds (docs/SOLVERS.md): here their stand-ins, which speak
        # the same interfaces (standin_solvers.py).
        os.makedirs(os.path.join(self.dir, "solvers"))
        standin = os.path.join(SOURCE, "tests", "cli", "standin_solvers.py")
        for program, solver in (("multiobj", "apex"), ("mohs", "mohs")):
            path = os.path.join(self.dir, "solvers", program)
            with open(path, "w") as f:
                f.write("#!/bin/sh\nexec /usr/bin/python3 %s %s \"$@\"\n" % (standin, solver))
            os.chmod(path, 0o755)
        self.url = self.serve_published()
        ran = 0
        for heading, line, text in sh_blocks():
            if heading in ELSEWHERE:
                continue
            with self.subTest(block="README.md:%d (%s)" % (line, heading)):
                self.bash(self.fill_placeholders(text, line), line)
                ran += 1
        self.assertGreaterEqual(ran, 5)
        # What the blocks promise, checked once more from their files.
        self.assertEqual(self.bash("cmp NY.mosb NY2.mosb && echo same", "cmp"), "same\n")
        with open(os.path.join(self.dir, "comparison.tex")) as f:
            self.assertIn("\\toprule", f.read())

    def test_blocks_run_elsewhere_are_still_named_there(self):
        headings = {heading for heading, _, _ in sh_blocks()}
        for heading, places in ELSEWHERE.items():
            self.assertIn(heading, headings, "ELSEWHERE names a section README.md no longer has")
            for path, text in places:
                with open(os.path.join(SOURCE, path), encoding="utf-8") as f:
                    self.assertIn(text, f.read(), "%s no longer runs README's '%s'" % (path, heading))
        for heading, line, text in sh_blocks():
            if heading == "Quick start":
                commands = [shlex.split(l, comments=True) for l in text.splitlines()]
                self.assertEqual([c for c in commands if c],
                                 [["bash", "tools/quickstart.sh"], ["bash", "tests/run-all.sh"]])


if __name__ == "__main__":
    mosbtest.main(verbosity=2)
