#!/usr/bin/python3
"""End-to-end tests of solver profiles (spec/RUN.md §10): `mosb run --profile`, the export cache,
`mosb cache clear` and `mosb export dimacs --multi-column --queries-format`.

    MOSB=build/release/tools/mosb EXAMPLES=build/release/examples /usr/bin/python3 tests/cli/test_profiles.py

Each shipped profile runs a stand-in of its solver (standin_solvers.py: the interface the real
program has, as docs/SOLVERS.md records it) and is cross-checked with the example NAMOA* through
`mosb solutions compare`, as a user checks a real solver.
"""

import json
import os
import stat
import sys
import tomllib

import mosbtest
import standin_solvers
from mosbtest import CliTest, FINISHED, assert_finished, setUpModule  # noqa: F401

EXAMPLES = os.path.abspath(os.environ.get("EXAMPLES", ""))
HERE = os.path.dirname(os.path.abspath(__file__))
STANDIN = os.path.join(HERE, "standin_solvers.py")
# The shipped profiles, read from the folder they are built from: a new profile is a file there
# and its stand-in (standin_solvers.STANDINS), no list here.
PROFILE_DIR = os.path.join(HERE, "..", "..", "profiles")
PROFILES = sorted(f[:-len(".toml")] for f in os.listdir(PROFILE_DIR) if f.endswith(".toml"))
# The profile of the example solvers runs them, not a stand-in.
EXAMPLE_PROFILE = "mosb-examples"
# Cases beyond each profile's defaults on both views: (view, options); BOA* is bi-objective.
EXTRA_CASES = {"apex": [("Grid_2", ["--profile-option", "algorithm=BOA"]),
                        ("Grid_3", ["--profile-option", "algorithm=NAMOAdr"])],
               "mohs": [("Grid_2", ["--profile-option", "algorithm=BOA"])]}


def profile_toml(name):
    with open(os.path.join(PROFILE_DIR, name + ".toml"), "rb") as f:
        return tomllib.load(f)

# A 1-based DIMACS graph of 6 vertices with parallel arcs: 1->2 three times ((1, 5) and (3, 2)
# are both Pareto-optimal, (4, 6) is dominated), 4->5 twice with equal costs.
PARALLEL_C1 = "p sp 6 11\na 1 2 1\na 1 2 3\na 1 2 4\na 2 3 1\na 1 3 9\na 3 4 1\na 4 5 2\n" \
              "a 4 5 2\na 5 6 1\na 2 6 7\na 6 1 1\n"
PARALLEL_C2 = "p sp 6 11\na 1 2 5\na 1 2 2\na 1 2 6\na 2 3 1\na 1 3 1\na 3 4 1\na 4 5 3\n" \
              "a 4 5 3\na 5 6 1\na 2 6 1\na 6 1 1\n"
PARALLEL_QUERIES = "1 3\n1 6\n2 1\n1 5\n"


class ProfileTest(CliTest):

    def setUp(self):
        super().setUp()
        self.cache = self.path("cache")
        self.env = dict(os.environ, MOSB_EXPORT_CACHE=self.cache,
                        STANDIN_ARGS=self.path("args.log"))
        self.env.pop("STANDIN_SEARCH_SECONDS", None)
        for objectives in (2, 3):
            bare = self.path("bare%d.mosb" % objectives)
            self.ok("generate", "grid", "--width", "5", "--height", "5", "--objectives",
                    str(objectives), "-o", bare)
            self.ok("queries", "generate", bare, "--set", "q", "--count", "8", "--view",
                    "Grid_%d" % objectives, "-o", self.path("g%d.mosb" % objectives))
        self.standins = {}
        for solver in standin_solvers.STANDINS:
            path = self.write("bin/" + solver, "#!/bin/sh\nexec /usr/bin/python3 %s %s \"$@\"\n"
                              % (STANDIN, solver))
            os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
            self.standins[solver] = path

    # --- helpers -----------------------------------------------------------------------------

    def run_profile(self, instance, view, profile, executable, *extra, output="out.sol",
                    code=FINISHED, env=None):
        r = self.mosb("run", self.path(instance), "--view", view, "--profile", profile,
                      "--executable", executable, *extra, "-o", self.path(output),
                      env=env or self.env)
        assert_finished(self, r, code, [self.path(output)])
        return r

    def reference(self, instance, view, output="ref.sol"):
        """The example NAMOA*'s front, through the mosb-examples profile."""
        self.run_profile(instance, view, "mosb-examples", os.path.join(EXAMPLES, "namoa"),
                         output=output)
        return output

    def compare(self, a, b):
        r = self.mosb("solutions", "compare", "--json", self.path(a), self.path(b))
        return json.loads(r.stdout)

    def inspect(self, name):
        return json.loads(self.ok("solutions", "inspect", "--json", self.path(name)).stdout)

    def statuses(self, name):
        return {k: v for k, v in self.inspect(name)["statuses"].items() if v}

    def parameters(self, name):
        return self.inspect(name)["parameters"]

    def exports(self):
        return sorted(d for d in os.listdir(self.cache) if not d.startswith("."))

    def export_files(self):
        (directory,) = self.exports()
        return {f: mosbtest.read(os.path.join(self.cache, directory, f), "r")
                for f in sorted(os.listdir(os.path.join(self.cache, directory)))}

    def parallel_instance(self, extra_profile=None):
        self.write("par-c1.gr", PARALLEL_C1)
        self.write("par-c2.gr", PARALLEL_C2)
        self.write("par.queries", PARALLEL_QUERIES)
        self.ok("convert", "dimacs", "--gr", self.path("par-c1.gr"), "--gr",
                self.path("par-c2.gr"), "--name", "par", "--view", "par=c1,c2", "-o",
                self.path("bare-par.mosb"))
        self.ok("queries", "import", self.path("bare-par.mosb"), self.path("par.queries"),
                "--set", "q", "--view", "par", "-o", self.path("par.mosb"))

    # --- the shipped profiles, each against the example NAMOA* --------------------------------

    def test_list_profiles(self):
        r = self.ok("run", "--list-profiles")
        names = [line.split(":")[0] for line in r.stdout.splitlines() if not line.startswith(" ")]
        self.assertEqual(names, PROFILES)
        # Every shipped profile of a published solver has its stand-in, and no stand-in lacks
        # its profile.
        self.assertEqual(sorted(list(standin_solvers.STANDINS) + [EXAMPLE_PROFILE]), PROFILES)
        self.assertIn("--profile-option algorithm=Apex|BOA|PPA|NAMOAdr (default Apex)", r.stdout)
        listed = json.loads(self.ok("run", "--list-profiles", "--json").stdout)
        self.assertEqual({p["name"]: p for p in listed}["mohs"]["options"], {"algorithm": "LTMOA"})
        self.assert_one_line_error(self.mosb("run", "--list-profiles", "--view", "x"),
                                   "--view: not with --list-profiles", code=2)

    def test_every_shipped_profile_agrees_with_namoa(self):
        cases = [(profile, view, []) for profile in standin_solvers.STANDINS
                 for view in ("Grid_2", "Grid_3")]
        cases += [(profile, view, extra) for profile, extras in EXTRA_CASES.items()
                  for view, extra in extras]
        for view in ("Grid_2", "Grid_3"):
            self.reference("g%s.mosb" % view[-1], view, "ref-%s.sol" % view)
        for profile, view, extra in cases:
            with self.subTest(profile=profile, view=view, extra=extra):
                out = "%s-%s-%d.sol" % (profile, view, len(extra))
                self.run_profile("g%s.mosb" % view[-1], view, profile, self.standins[profile],
                                 "--time-limit", "60s", *extra, output=out)
                result = self.compare("ref-%s.sol" % view, out)
                self.assertTrue(result["ok"], result)
                self.assertEqual(result["equal"], 8, result)
                self.assertEqual(self.statuses(out), {"solved": 8})
                parameters = self.parameters(out)
                self.assertEqual(parameters["profile.name"], profile)
                # What the solver's own runtime measures (docs/SOLVERS.md's table).
                self.assertEqual(parameters["profile.runtime_clock"],
                                 profile_toml(profile)["output"]["runtime_clock"])
        # The runtime the solver reports is kept (T-MDA's eighth summary field, EMOA*'s
        # rt_search, mohs's Runtime line).
        for profile, seconds in (("tmda", 0.0021), ("emoa", 0.000103), ("mohs", 0.0364537)):
            reported = self.inspect("%s-Grid_2-0.sol" % profile)["statistics"]
            self.assertAlmostEqual(reported["reported_runtime_seconds"]["total"], 8 * seconds,
                                   places=9, msg=profile)

    def test_a_profile_run_is_named_by_its_options_and_epsilon(self):
        """Two algorithms, or two ε, of one program never share a recorded name."""
        for extra, name in (([], "A*pex"),
                            (["--profile-option", "algorithm=NAMOAdr"], "A*pex NAMOAdr"),
                            (["--profile-option", "merge=RANDOM", "--epsilon", "0.05"],
                             "A*pex RANDOM \u03b5=0.05"),
                            (["--profile-option", "algorithm=NAMOAdr", "--solver-name", "mine"],
                             "mine")):
            with self.subTest(extra=extra):
                self.run_profile("g3.mosb", "Grid_3", "apex", self.standins["apex"], *extra,
                                 output="named.sol")
                self.assertEqual(self.inspect("named.sol")["solver"], name)
                os.remove(self.path("named.sol"))

    def test_arguments_as_the_solvers_take_them(self):
        self.run_profile("g3.mosb", "Grid_3", "apex", self.standins["apex"], "--time-limit", "10s",
                         "--profile-option", "algorithm=NAMOAdr")
        self.run_profile("g2.mosb", "Grid_2", "emoa", self.standins["emoa"], "--time-limit", "2.5s",
                         output="emoa.sol")
        self.run_profile("g2.mosb", "Grid_2", "mohs", self.standins["mohs"], output="mohs.sol")
        calls = mosbtest.read(self.path("args.log"), "r").splitlines()
        apex = calls[0].split()
        # -t: integer seconds above mosb's limit (10 s × 1.1 + 1 s); -e 0; MORE_SLACK for 3+
        self.assertEqual(apex[apex.index("-t") + 1], "12")
        self.assertEqual(apex[apex.index("-e") + 1], "0")
        self.assertEqual(apex[apex.index("--merge") + 1], "MORE_SLACK")
        self.assertEqual(apex[apex.index("-a") + 1], "NAMOAdr")
        self.assertEqual(len(apex[apex.index("-m") + 1:apex.index("-s")]), 3)
        emoa = calls[8].split()
        self.assertEqual(emoa[0], "emoa")
        self.assertEqual(emoa[3:5], ["3.75", "2"])  # a real limit, 2.5 × 1.1 + 1; M
        mohs = calls[16].split()
        self.assertEqual(mohs[mohs.index("-t") + 1], "1000000000")  # mosb has no limit

    def test_partial_fronts_under_the_solvers_own_cut_off_are_never_solved(self):
        # The stand-ins' searches "need" 100 CPU seconds: under mosb's 1 s limit their own
        # cut-off (above mosb's) still stops them first, as a real solver's clock could.
        # A*pex's JSON log says "Failed": the importer's reading of any status but "Success"
        # (spec/RUN.md §3.1) makes it failed; the others state a time-out.
        env = dict(self.env, STANDIN_SEARCH_SECONDS="100")
        for profile, status in (("apex", "failed"), ("mohs", "timeout"), ("emoa", "timeout")):
            with self.subTest(profile=profile):
                out = profile + ".sol"
                r = self.run_profile("g2.mosb", "Grid_2", profile, self.standins[profile],
                                     "--time-limit", "1s", output=out, env=env)
                self.assertEqual(self.statuses(out), {status: 8})
                self.assertEqual(self.inspect(out)["vectors"], 0)
                if profile == "apex":
                    self.assertIn('finish_info.status "Failed"', r.stderr)
        # T-MDA without its summary line (as when killed): not finished, so failed, never solved.
        env = dict(self.env, STANDIN_NO_SUMMARY="1")
        r = self.run_profile("g3.mosb", "Grid_3", "tmda", self.standins["tmda"], output="tmda.sol",
                             env=env)
        self.assertEqual(self.statuses("tmda.sol"), {"failed": 8})
        self.assertIn("has no line starting with 'T-MDA;': the search did not finish", r.stderr)
        # T-MDA built unchanged prints its summary (N solutions) and no front: failed, with why,
        # never 8 queries read as disconnected.
        env = dict(self.env, STANDIN_NO_FRONT="1")
        r = self.run_profile("g3.mosb", "Grid_3", "tmda", self.standins["tmda"],
                             output="tmda-nofront.sol", env=env)
        self.assertEqual(self.statuses("tmda-nofront.sol"), {"failed": 8})
        self.assertRegex(r.stderr, r"stdout:1: the solver says it found [1-9][0-9]* solutions, its "
                         r"output holds 0 vectors")

    # --- ids, the text forms ---------------------------------------------------------------

    def test_text_forms_byte_for_byte(self):
        self.parallel_instance()
        self.run_profile("par.mosb", "par", "tmda", self.standins["tmda"], output="t.sol")
        files = self.export_files()
        header = "c written by mosb %s (export dimacs) from benchmark par\nc instance digest %s\n" % (
            self.version(), self.digest("par.mosb"))
        self.assertEqual(files["par.gr"], header +
                         "c objectives c1 c2, then 1 columns of 0\np sp 6 11\n"
                         "a 0 1 1 5 0\na 0 1 3 2 0\na 0 1 4 6 0\na 0 2 9 1 0\na 1 2 1 1 0\n"
                         "a 1 5 7 1 0\na 2 3 1 1 0\na 3 4 2 3 0\na 3 4 2 3 0\na 4 5 1 1 0\n"
                         "a 5 0 1 1 0\n")
        mosb_cache_clear = self.ok("cache", "clear", "--export-cache", self.cache)
        self.assertIn("removed 1 export from", mosb_cache_clear.stdout)
        self.assertEqual(self.exports(), [])
        # EMOA*: parallel arcs collapsed (the dominated (4, 6) and the second (2, 3) dropped,
        # (3, 2) through vertex 6), per-objective files with the same line layout.
        self.run_profile("par.mosb", "par", "emoa", self.standins["emoa"], output="e.sol")
        files = self.export_files()
        self.assertEqual(sorted(files), ["export.txt", "par-c1.gr", "par-c2.gr", "par-q.queries"])
        self.assertEqual(files["par-q.queries"], "0 2\n0 5\n1 0\n0 4\n")  # 0-based
        note = "c vertices 6 to 6 subdivide parallel arcs\n"
        self.assertEqual(files["par-c1.gr"], header + note + "c objective c1\np sp 7 10\n"
                         "a 0 1 1\na 0 6 3\na 0 2 9\na 1 2 1\na 1 5 7\na 2 3 1\na 3 4 2\n"
                         "a 4 5 1\na 5 0 1\na 6 1 0\n")
        self.assertEqual(files["par-c2.gr"], header + note + "c objective c2\np sp 7 10\n"
                         "a 0 1 5\na 0 6 2\na 0 2 1\na 1 2 1\na 1 5 1\na 2 3 1\na 3 4 3\n"
                         "a 4 5 1\na 5 0 1\na 6 1 0\n")
        self.ok("cache", "clear", "--export-cache", self.cache)
        # A*pex: the dummy arc between two new vertices ends every file.
        self.run_profile("par.mosb", "par", "apex", self.standins["apex"], output="a.sol")
        files = self.export_files()
        self.assertTrue(files["par-c2.gr"].endswith("c objective c2\np sp 8 12\na 0 1 5\n"
                                                    "a 0 1 2\na 0 1 6\na 0 2 1\na 1 2 1\n"
                                                    "a 1 5 1\na 2 3 1\na 3 4 3\na 3 4 3\n"
                                                    "a 4 5 1\na 5 0 1\na 6 7 0\n"),
                        files["par-c2.gr"])
        self.assertIn("c the last arc joins two vertices of no query", files["par-c1.gr"])

    def version(self):
        return self.ok("--version").stdout.split()[1]

    def digest(self, name):
        return self.inspect_instance(name)["digest"]

    def inspect_instance(self, name):
        return json.loads(self.ok("inspect", "--json", self.path(name)).stdout)

    def test_parallel_arcs_collapse_keeps_every_pareto_path(self):
        self.parallel_instance()
        self.reference("par.mosb", "par")
        self.run_profile("par.mosb", "par", "emoa", self.standins["emoa"], output="emoa.sol")
        result = self.compare("ref.sol", "emoa.sol")
        self.assertTrue(result["ok"], result)
        self.assertEqual(result["equal"], 4)
        # The same stand-in given the arcs as they are (a profile that keeps them) loses the
        # front through 1->2 (1, 5): the last parallel arc wins in its loader.
        profile = mosbtest.read(os.path.join(os.path.dirname(STANDIN), "..", "..", "profiles",
                                             "emoa.toml"), "r")
        self.write("emoa-keep.toml", profile.replace('parallel_arcs = "collapse"',
                                                     'parallel_arcs = "keep"'))
        self.run_profile("par.mosb", "par", self.path("emoa-keep.toml"), self.standins["emoa"],
                         output="keep.sol")
        result = self.compare("ref.sol", "keep.sol")
        self.assertFalse(result["ok"], result)

    def test_ids_land_in_the_profiles_base(self):
        self.parallel_instance()
        self.reference("par.mosb", "par")
        mohs = mosbtest.read(os.path.join(os.path.dirname(STANDIN), "..", "..", "profiles",
                                          "mohs.toml"), "r")
        # mohs reads any base: a 1-based text and 1-based ids solve the same queries.
        self.write("mohs1.toml", mohs.replace("id_base = 0", "id_base = 1"))
        self.run_profile("par.mosb", "par", self.path("mohs1.toml"), self.standins["mohs"],
                         output="mohs1.sol")
        self.assertTrue(self.compare("ref.sol", "mohs1.sol")["ok"])
        self.assertEqual(self.parameters("mohs1.sol")["run.id_base"], "1")
        calls = mosbtest.read(self.path("args.log"), "r").splitlines()
        first = calls[-4].split()
        self.assertEqual(first[first.index("-s") + 1:first.index("-s") + 4], ["1", "-g", "3"])
        # T-MDA reads ids below N only: a 1-based text (ids up to N) fails loudly on every query,
        # never solves another one.
        tmda = mosbtest.read(os.path.join(os.path.dirname(STANDIN), "..", "..", "profiles",
                                          "tmda.toml"), "r")
        self.write("tmda1.toml", tmda.replace("id_base = 0", "id_base = 1"))
        self.run_profile("par.mosb", "par", self.path("tmda1.toml"), self.standins["tmda"],
                         output="tmda1.sol")
        self.assertEqual(self.statuses("tmda1.sol"), {"failed": 4})
        # T-MDA's degrees are 16-bit counts: a profile's max_degree refuses more, naming the vertex.
        self.write("tmda-deg.toml", tmda.replace("max_degree = 65534", "max_degree = 2"))
        r = self.mosb("run", self.path("par.mosb"), "--view", "par", "--profile",
                      self.path("tmda-deg.toml"), "--executable", self.standins["tmda"], "-o",
                      self.path("deg.sol"), env=self.env)
        self.assert_one_line_error(r, "vertex 0 has more than 2 arcs out, the most the solver holds")

    def test_a_query_file_and_named_objective_files(self):
        # A solver of query files (as A*pex's and mohs's -q FILE, `s,t` lines): it reads line
        # {query} of {queries} and the objectives' files by name, in the order it wants them.
        self.parallel_instance()
        self.reference("par.mosb", "par")
        solver = self.write("bin/qsolver", """#!/usr/bin/python3
import sys
sys.path.insert(0, %r)
import standin_solvers as s
c2, c1, queries, k, d = sys.argv[1:]
assert d == "2"
line = open(queries).read().split("\\n")[int(k)]
source, target = (int(x) for x in line.split(","))
arcs = [(u, v, (int(a), int(b))) for (u, v, a), (_, _, b) in
        zip(s.read_gr_boost(c1), s.read_gr_boost(c2))]
n = max(max(u, v) for u, v, _ in arcs) + 1
for c in s.pareto(n, arcs, source, target):
    print(*c)
""" % os.path.dirname(STANDIN))
        os.chmod(solver, 0o755)
        self.write("q.toml", 'name = "q"\n'
                   'command = "{executable} {gr:c2} {gr:c1} {queries} {query} {d}"\n'
                   '[input]\nform = "dimacs"\nid_base = 1\nqueries = "comma"\n')
        self.run_profile("par.mosb", "par", self.path("q.toml"), solver, output="q.sol")
        result = self.compare("ref.sol", "q.sol")
        self.assertTrue(result["ok"], result)
        self.assertEqual(result["equal"], 4)
        self.assertEqual(self.export_files()["par-q.queries"], "1,3\n1,6\n2,1\n1,5\n")
        self.write("bad.toml", 'name = "q"\ncommand = "{executable} {gr:c9}"\n'
                   '[input]\nform = "dimacs"\n')
        r = self.mosb("run", self.path("par.mosb"), "--view", "par", "--profile",
                      self.path("bad.toml"), "--executable", solver, "-o", self.path("x.sol"),
                      env=self.env)
        self.assert_one_line_error(r, "profile q: {gr:c9}: the run has no objective 'c9'")

    # --- refusals --------------------------------------------------------------------------

    def test_float_costs_for_an_integer_solver(self):
        self.write("f-c1.gr", "p sp 3 3\na 1 2 1.5\na 2 3 2.7\na 1 3 4.5\n")
        self.write("f-c2.gr", "p sp 3 3\na 1 2 1\na 2 3 1\na 1 3 1\n")
        self.write("f.queries", "1 3\n")
        self.ok("convert", "dimacs", "--gr", self.path("f-c1.gr"), "--gr", self.path("f-c2.gr"),
                "--name", "f", "-o", self.path("f.mosb"))
        self.ok("queries", "import", self.path("f.mosb"), self.path("f.queries"), "--set", "q",
                "--in-place")
        for profile in ("apex", "mohs", "tmda"):
            r = self.mosb("run", self.path("f.mosb"), "--objectives", "c1,c2", "--queries", "q",
                          "--profile", profile, "--executable", self.standins[profile], "-o",
                          self.path("x.sol"), env=self.env)
            self.assert_one_line_error(r, "objective 'c1' holds float costs",
                                       "reads integers only: give a scale K (--scale")
            self.assertFalse(os.path.exists(self.path("x.sol")))
        # --scale 10: 15 + 27 = 42 -> 4.2, and 45 -> 4.5; the factor is recorded.
        self.mosb("run", self.path("f.mosb"), "--objectives", "c1,c2", "--queries", "q",
                  "--profile", "mohs", "--executable", self.standins["mohs"], "--scale", "10",
                  "-o", self.path("s.sol"), env=self.env)
        self.assertEqual(self.parameters("s.sol")["profile.scale"], "10.0")
        self.assertEqual(self.parameters("s.sol")["profile.scaled_objectives"], "c1")
        self.ok("solutions", "export", self.path("s.sol"), "--dir", self.path("s"))
        front = mosbtest.read(self.path("s", "0.txt"), "r")
        self.assertEqual(front, "4.2 2\n4.5 1\n")
        r = self.mosb("run", self.path("g2.mosb"), "--view", "Grid_2", "--profile", "mohs",
                      "--executable", self.standins["mohs"], "--scale", "10", "-o",
                      self.path("y.sol"), env=self.env)
        self.assert_one_line_error(r, "scale: no objective of the run holds float costs")

    def test_malformed_profile_is_one_line_with_file_line_and_key(self):
        self.write("bad.toml", 'name = "bad"\ncommand = "{executable} {source} {target}"\n'
                   '[input]\nform = "dimacs"\nid_bsae = 1\n')
        r = self.mosb("run", self.path("g2.mosb"), "--view", "Grid_2", "--profile",
                      self.path("bad.toml"), "--executable", self.standins["apex"], "-o",
                      self.path("x.sol"), env=self.env)
        self.assert_error(r, "%s:5:1: key 'input.id_bsae': unknown key" % self.path("bad.toml"))
        self.write("bad2.toml", 'name = "bad"\ncommand = "{executable}"\nsuccess_exit_codes = 1\n')
        r = self.mosb("run", self.path("g2.mosb"), "--view", "Grid_2", "--profile",
                      self.path("bad2.toml"), "--executable", self.standins["apex"], "-o",
                      self.path("x.sol"), env=self.env)
        self.assert_error(r, "%s:3:22: key 'success_exit_codes': expected an array"
                          % self.path("bad2.toml"))
        # Past the 1 MiB cap (a comment a byte too long): refused before it is parsed.
        self.write("long.toml", "#" * (1 << 20) + "\n")
        r = self.mosb("run", self.path("g2.mosb"), "--view", "Grid_2", "--profile",
                      self.path("long.toml"), "--executable", self.standins["apex"], "-o",
                      self.path("x.sol"), env=self.env)
        self.assert_error(r, "%s: more than 1048576 bytes" % self.path("long.toml"))
        self.assertFalse(os.path.exists(self.path("x.sol")))

    def test_options_and_usage(self):
        base = ["run", self.path("g3.mosb"), "--view", "Grid_3", "--executable",
                self.standins["apex"], "-o", self.path("x.sol")]
        r = self.mosb(*base, "--profile", "apex", "--profile-option", "algorithm=Dijkstra",
                      env=self.env)
        self.assert_one_line_error(r, "algorithm is one of Apex, BOA, PPA, NAMOAdr")
        r = self.mosb(*base, "--profile", "apex", "--profile-option", "algorithm=BOA", env=self.env)
        self.assert_one_line_error(r, "algorithm=BOA takes at most 2 objectives, the run has 3")
        r = self.mosb(*base, "--profile", "apex", "--profile-option", "colour=red", env=self.env)
        self.assert_one_line_error(r, "profile apex has the options algorithm, merge")
        r = self.mosb(*base, "--profile", "tmda", "--epsilon", "0.1", env=self.env)
        self.assert_one_line_error(r, "profile tmda gives its solver no epsilon")
        r = self.mosb(*base, "--profile", "nosuch", env=self.env)
        self.assert_one_line_error(r, "--profile nosuch: no shipped profile of that name")
        r = self.mosb(*base, "--profile", "apex", "--solver", "x", env=self.env)
        self.assert_one_line_error(r, "--solver: not with --profile", code=2)
        r = self.mosb("run", self.path("g3.mosb"), "--view", "Grid_3", "--profile", "apex", "-o",
                      "x.sol", env=self.env)
        self.assert_one_line_error(r, "--profile: give --executable PATH", code=2)
        r = self.mosb("run", self.path("g3.mosb"), "--view", "Grid_3", "--solver", "/bin/true",
                      "--scale", "2", "-o", "x.sol", env=self.env)
        self.assert_one_line_error(r, "--scale: only with --profile", code=2)
        self.assertFalse(os.path.exists(self.path("x.sol")))

    # --- the export cache ------------------------------------------------------------------

    def test_the_export_is_made_once_and_reused(self):
        self.run_profile("g3.mosb", "Grid_3", "mohs", self.standins["mohs"], output="a.sol")
        (directory,) = self.exports()
        files = sorted(os.listdir(os.path.join(self.cache, directory)))
        before = {f: os.stat(os.path.join(self.cache, directory, f)) for f in files}
        # Another run, another profile with the same text form: nothing written again.
        self.run_profile("g3.mosb", "Grid_3", "mohs", self.standins["mohs"], "--profile-option",
                         "algorithm=Apex", output="b.sol")
        self.assertEqual(self.exports(), [directory])
        for f in files:
            after = os.stat(os.path.join(self.cache, directory, f))
            self.assertEqual((after.st_ino, after.st_mtime_ns),
                             (before[f].st_ino, before[f].st_mtime_ns), f)
        # Another form is another export; a file cut short is exported again.
        self.run_profile("g3.mosb", "Grid_3", "tmda", self.standins["tmda"], output="c.sol")
        self.assertEqual(len(self.exports()), 2)
        gr = [f for f in files if f.endswith(".gr")][0]
        self.assertEqual(stat.S_IMODE(before[gr].st_mode), 0o444)
        os.chmod(os.path.join(self.cache, directory, gr), 0o644)  # its owner may, and root does
        with open(os.path.join(self.cache, directory, gr), "r+") as f:
            f.truncate(10)
        r = self.run_profile("g3.mosb", "Grid_3", "mohs", self.standins["mohs"], output="d.sol")
        self.assertIn("%s: 10 bytes, export.txt says" % gr, r.stderr)
        self.assertTrue(self.compare("a.sol", "d.sol")["ok"])
        r = self.ok("cache", "clear", "--export-cache", self.cache, "--json")
        self.assertEqual(json.loads(r.stdout)["removed"], 2)
        self.assertEqual(os.listdir(self.cache), [])
        # The default place: $XDG_CACHE_HOME/mosb/exports without MOSB_EXPORT_CACHE.
        env = dict(self.env, XDG_CACHE_HOME=self.path("xdg"))
        del env["MOSB_EXPORT_CACHE"]
        self.run_profile("g2.mosb", "Grid_2", "emoa", self.standins["emoa"], output="e.sol",
                         env=env)
        self.assertEqual(len(os.listdir(self.path("xdg", "mosb", "exports"))), 1)
        self.assertIn("removed 1 export", self.ok("cache", "clear", env=env).stdout)

    def test_a_solver_that_edits_its_input_spoils_no_later_run(self):
        """Issue 43 §3: a careless solver rewrites a value of its cached {gr} in place, the size
        unchanged; the next run of an honest solver on the same export finds the hash changed,
        exports it again (saying so) and gets the right front."""
        hostile = self.write("bin/hostile", """#!/bin/sh
gr=; previous=
for a in "$@"; do [ "$previous" = "-m" ] && gr=$a; previous=$a; done
/usr/bin/python3 - "$gr" <<'EDIT'
import os, sys
path = sys.argv[1]
os.chmod(path, 0o644)  # read-only stops another user's solver; its owner may change the mode
lines = open(path).read().split("\\n")
lines = [line[:-1] + "9" if line.startswith("a ") and line[-1] in "12345678" else line
         for line in lines]
open(path, "r+").write("\\n".join(lines))
EDIT
exec /usr/bin/python3 %s mohs "$@"
""" % STANDIN)
        os.chmod(hostile, 0o755)
        self.reference("g2.mosb", "Grid_2")
        # Unsealed, the edit lands; the run notices its input changed under it (spec/RUN.md §6,
        # "Programs pinned") and writes no file rather than fronts of two graphs.
        r = self.run_profile("g2.mosb", "Grid_2", "mohs", hostile, output="hostile.sol", code=1)
        (directory,) = self.exports()
        gr = os.path.join(self.cache, directory,
                          sorted(f for f in os.listdir(os.path.join(self.cache, directory))
                                 if f.endswith(".gr"))[0])  # the first objective's, {gr}'s first
        self.assertIn(gr + " changed during the run", r.stderr)
        self.assertFalse(os.path.exists(self.path("hostile.sol")))
        size = os.path.getsize(gr)
        r = self.run_profile("g2.mosb", "Grid_2", "mohs", self.standins["mohs"], output="ok.sol")
        self.assertIn("mosb: warning: export cache: %s: its content changed since it was exported"
                      % gr, r.stderr)
        self.assertEqual(len([line for line in r.stderr.splitlines() if "warning" in line]), 1)
        self.assertEqual(os.path.getsize(gr), size)
        result = self.compare("ref.sol", "ok.sol")
        self.assertTrue(result["ok"], result)
        self.assertEqual(result["equal"], 8, result)
        # The export is whole again: a third run reuses it without a word.
        r = self.run_profile("g2.mosb", "Grid_2", "mohs", self.standins["mohs"], output="ok2.sol")
        self.assertNotIn("warning", r.stderr)

    def test_cache_clear_leaves_what_is_not_its_own(self):
        self.run_profile("g2.mosb", "Grid_2", "mohs", self.standins["mohs"], output="a.sol")
        self.write("cache/notes.txt", "mine\n")
        self.write("cache/0123456789abcdef-0123456789abcdef/export.txt", "not the cache's\n")
        r = self.ok("cache", "clear", "--export-cache", self.cache, "--json")
        self.assertEqual(json.loads(r.stdout)["removed"], 1)
        self.assertEqual(sorted(os.listdir(self.cache)),
                         ["0123456789abcdef-0123456789abcdef", "notes.txt"])
        self.assertEqual(sorted(r.stderr.splitlines()),
                         ["mosb: %s: not an export of mosb, left alone" % self.path("cache", f)
                          for f in ("0123456789abcdef-0123456789abcdef", "notes.txt")])

    def test_slurm_tasks_get_the_profile(self):
        self.ok("run", self.path("g2.mosb"), "--view", "Grid_2", "--profile", "mohs",
                "--executable", self.standins["mohs"], "--profile-option", "algorithm=Apex",
                "--export-cache", self.cache, "--shards", "2", "--slurm", self.path("job"),
                env=dict(self.env, PATH=self.path("no-sbatch-here")))
        arguments = json.loads(mosbtest.read(self.path("job", "run.json"), "r"))["run_arguments"]
        for option, value in (("--profile", "mohs"), ("--executable", self.standins["mohs"]),
                              ("--profile-option", "algorithm=Apex"),
                              ("--export-cache", self.cache)):
            self.assertEqual(arguments[arguments.index(option) + 1], value)
        # What a task runs: its arguments are a run of their own.
        self.ok("run", *arguments, "--shard", "1/2", "-o",
                self.path("shard-1.sol"), env=self.env)
        self.assertEqual(self.statuses("shard-1.sol"), {"solved": 4, "not-run": 4})

    # --- export dimacs ---------------------------------------------------------------------

    def test_export_dimacs_multi_column_and_comma_queries(self):
        self.parallel_instance()
        r = self.ok("export", "dimacs", self.path("par.mosb"), "-o", self.path("txt"),
                    "--multi-column", "--queries-format", "comma", "--json")
        written = json.loads(r.stdout)["wrote"]
        self.assertEqual([os.path.basename(p) for p in written], ["par.gr", "par-q.queries"])
        self.assertEqual(mosbtest.read(self.path("txt", "par-q.queries"), "r"),
                         "1,3\n1,6\n2,1\n1,5\n")  # the instance's id base: 1
        text = mosbtest.read(self.path("txt", "par.gr"), "r")
        self.assertIn("c objectives c1 c2\np sp 6 11\na 1 2 1 5\na 1 2 3 2\n", text)
        self.ok("export", "dimacs", self.path("par.mosb"), "-o", self.path("txt0"),
                "--id-base", "0", "--force-id-base")
        self.assertEqual(mosbtest.read(self.path("txt0", "par-q.queries"), "r"),
                         "0 2\n0 5\n1 0\n0 4\n")


if __name__ == "__main__":
    mosbtest.main()
