#!/usr/bin/python3
"""Benchmark of the example solvers (BENCHMARKS.md, "Example solvers").

    build/release/tests/bench/mosb_bench_dimacs --dir DIR      # writes DIR/dimacs-{NY,FLA}-{d,t}.gr
    /usr/bin/python3 tests/bench/bench_examples.py --dir DIR --build build/release

1. Time to first query (process start -> first front printed and the process gone): `namoa` on the
   .mosb (converted here with `mosb convert dimacs`) against `namoa_text` loading the two .gr files;
   one query, vertex 0 -> 20000, the same search in both. Best of 3 wall-clock runs, with the
   child's CPU time (user + system) of that run.
2. Per-query time of `namoa` (NetMaker-10k_3, 3 objectives) and `boa_star` (c1, c2) on the real NetMaker
   graph with its 40 published `.inst` queries, as the solvers print them.
Fails (exit 1) only when the two programs disagree on a front size.
"""

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "..", "shared", "data", "netmaker")


def timed(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        sys.exit("%s failed: %s" % (cmd[0], r.stderr))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, r.stdout.split()


def best_of(n, cmd):
    return min((timed(cmd) for _ in range(n)), key=lambda t: t[0])


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--dir", required=True)
    p.add_argument("--build", default="build/release")
    a = p.parse_args()
    mosb = os.path.join(a.build, "tools", "mosb")
    examples = os.path.join(a.build, "examples")
    print("time to first query, namoa, 1 query (0 -> 20000), best of 3 (wall s / child CPU s)")
    for size in ("NY", "FLA"):
        d, t = (os.path.join(a.dir, "dimacs-%s-%s.gr" % (size, k)) for k in "dt")
        inst = os.path.join(a.dir, "examples-%s.mosb" % size)
        subprocess.run([mosb, "convert", "dimacs", "--gr", d, "--gr", t, "--objective", "distance",
                        "--objective", "time", "-o", inst], check=True, capture_output=True)
        wm, cm, om = best_of(3, [os.path.join(examples, "namoa"), inst, "--query", "0", "20000"])
        wt, ct, ot = best_of(3, [os.path.join(examples, "namoa_text"), d + "," + t, "--query", "1", "20001"])
        if om[2] != ot[2]:
            sys.exit("front sizes differ: %s vs %s" % (om, ot))
        print("  %-4s .mosb %7.3f / %6.3f   text %7.3f / %6.3f   ratio %5.1fx wall %5.1fx CPU"
              "   (front %s, query %s s / %s s)" % (size, wm, cm, wt, ct, wt / wm, ct / cm, om[2], om[3], ot[3]))
    gr = os.path.join(DATA, "netMaker_3o_10000n_1amin_10amax_20i_1s_scorr_79134.gr")
    if not os.path.isfile(gr):
        print("NetMaker: %s is absent, skipped" % gr)
        return
    with tempfile.TemporaryDirectory() as tmp:
        inst = os.path.join(tmp, "nm.mosb")
        subprocess.run([mosb, "convert", "netmaker", gr, "-o", inst], check=True, capture_output=True)
        subprocess.run([mosb, "queries", "import", os.path.join(DATA, "netMaker_4d.inst"), "--into", inst,
                        "--name", "nm", "--match", "_79134.gr"], check=True, capture_output=True)
        print("NetMaker 10000 vertices, 59750 arcs, 40 published queries (per-query s as printed)")
        for name, args in (("boa_star", ["--objectives", "c1,c2"]), ("namoa", [])):
            wall, cpu, out = timed([os.path.join(examples, name), inst, "--queries", "nm", *args])
            rows = [out[i:i + 5] for i in range(0, len(out), 5)]
            secs = sorted(float(r[3]) for r in rows)
            fronts = [int(r[2]) for r in rows]
            print("  %-8s %s: median %.4f  mean %.4f  max %.4f s; fronts median %d max %d;"
                  " whole run %.2f s wall, %.2f s CPU" % (name, "c1,c2" if args else "c1,c2,c3",
                                                         statistics.median(secs), statistics.mean(secs),
                                                         secs[-1], statistics.median(fronts), max(fronts), wall, cpu))


if __name__ == "__main__":
    main()
