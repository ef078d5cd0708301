"""Stand-ins for the published solvers that mosb's shipped profiles run (tests/cli/test_profiles.py):
each reproduces its solver's interface as docs/SOLVERS.md records it from the real program
(arguments, files read and how, output files and their format, exit codes, status lines, runtime
line), with a plain Pareto search inside. Written from those records, not from the solvers' code.

A stand-in is this file run as `standin_solvers.py apex|mohs|emoa|tmda ARGS...` (the tests write
a two-line executable per solver that does so). Environment:
  STANDIN_ARGS=FILE             append the arguments of each call to FILE
  STANDIN_SEARCH_SECONDS=X      the search needs X CPU seconds: under a smaller own limit the
                                stand-in stops as its solver does (a partial front)
  STANDIN_NO_SUMMARY=1          (tmda) end without the summary line, as a killed T-MDA does
  STANDIN_NO_FRONT=1            (tmda) no Solution lines, as T-MDA built unchanged (its printf
                                commented out) prints only the summary
"""

import heapq
import os
import sys


def finish(code, message=None, stream=None):
    if message is not None:
        print(message, file=stream or sys.stderr)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


def record(solver, argv):
    log = os.environ.get("STANDIN_ARGS")
    if log:
        with open(log, "a") as f:
            f.write(solver + " " + " ".join(argv) + "\n")


def search_seconds():
    return float(os.environ.get("STANDIN_SEARCH_SECONDS", "0"))


def stoul(text):
    """std::stoul / std::stoi: the leading digits ("2.5" is 2), an exception without any."""
    digits = ""
    for c in text.lstrip(" "):
        if not c.isdigit():
            break
        digits += c
    if not digits:
        finish(134, "terminate called after throwing an instance of 'std::invalid_argument'")
    return int(digits)


def pareto(n, arcs, s, t):
    """The sorted distinct Pareto front of s -> t over arcs (u, v, costs); every id below n."""
    out = [[] for _ in range(n)]
    for u, v, c in arcs:
        out[u].append((v, c))
    d = len(arcs[0][2]) if arcs else 1
    closed = [[] for _ in range(n)]
    heap = [(tuple([0] * d), s)]
    while heap:
        c, v = heapq.heappop(heap)
        if any(all(x <= y for x, y in zip(o, c)) for o in closed[v]):
            continue
        closed[v].append(c)
        for w, a in out[v]:
            heapq.heappush(heap, (tuple(x + y for x, y in zip(c, a)), w))
    return sorted(closed[t])


def partial(front):
    return front[:max(1, len(front) // 2)] if front else []


def read_gr_boost(path):
    """A*pex's and mohs's loader: split on single spaces, c and p lines skipped, the first empty
    line ends the file; (u, v, cost text) per arc."""
    arcs = []
    try:
        f = open(path)
    except OSError:
        return None
    with f:
        for line in f:
            line = line.rstrip("\n")
            if line == "":
                break
            words = line.split(" ")
            if words[0] == "a":
                arcs.append((int(words[1]), int(words[2]), words[3]))
    return arcs


def options(argv, names):
    """Boost-style options: NAME VALUE..., -m taking every word up to the next option."""
    got = {}
    i = 0
    while i < len(argv):
        name = argv[i]
        if name not in names:
            finish(134, "terminate called after throwing an instance of "
                   "'boost::wrapexcept<boost::program_options::unknown_option>'")
        if name == "-m":
            files = []
            i += 1
            while i < len(argv) and not argv[i].startswith("-"):
                files.append(argv[i])
                i += 1
            got[name] = files
            continue
        got[name] = argv[i + 1]
        i += 2
    return got


def integer_option(got, name, default):
    text = got.get(name, str(default))
    if not text.lstrip("-").isdigit():
        finish(134, "terminate called after throwing an instance of "
               "'boost::wrapexcept<boost::program_options::invalid_option_value>'")
    return int(text)


def load_boost(files, stdout_lines, apex_bug):
    """The arcs of one .gr per objective, checked for the same arcs in the same order; with
    apex_bug the last arc of the second file becomes an arc of its own (A*pex's loader)."""
    per_file = []
    for path in files:
        stdout_lines.append(path)
        arcs = read_gr_boost(path)
        if arcs is None:
            print("Failed to load gr files")
            finish(255, "cannot open the gr file " + path)
        per_file.append(arcs)
    m = len(per_file[0])
    for arcs in per_file[1:]:
        if len(arcs) != m or any(a[:2] != b[:2] for a, b in zip(arcs, per_file[0])):
            finish(255, "file inconsistency")
    result = [(u, v, [stoul(c)]) for u, v, c in per_file[0]]
    extra = None
    for k, arcs in enumerate(per_file[1:], start=1):
        for i, (u, v, c) in enumerate(arcs):
            if apex_bug and k == 1 and i == m - 1:
                extra = (u, v, [stoul(c)])  # a new arc with one cost
            elif apex_bug and k > 1 and i == m - 1 and extra is not None:
                result[i][2].append(stoul(c))
            else:
                result[i][2].append(stoul(c))
    d = len(files)
    arcs = [(u, v, tuple((c + [0] * d)[:d])) for u, v, c in result]  # '?': here 0
    if extra is not None:
        arcs.append((extra[0], extra[1], tuple((extra[2] + [0] * d)[:d])))
    return arcs


def apex(argv):
    got = options(argv, {"-m", "-s", "-g", "-a", "-t", "-e", "-o", "--merge", "--logging_file"})
    if "-o" not in got:
        finish(134, "terminate called after throwing an instance of "
               "'boost::wrapexcept<boost::program_options::required_option>'")
    algorithm = got.get("-a", "Apex")
    merge = got.get("--merge", "")
    if merge == "":
        sys.stderr.write("unknown merge strategy\n")
    if algorithm not in ("Apex", "BOA", "PPA", "NAMOAdr"):
        finish(255, "unknown solver name")
    files = got["-m"]
    if algorithm == "Apex" and merge in ("", "SMALLER_G2", "SMALLER_G2_FIRST") and len(files) >= 3:
        sys.stderr.write("SMALLER_G2 can only used for bi-objectives")
        finish(255)
    if merge and algorithm != "Apex":
        print("WARNING: merge strategy with non-apex search")
    limit = integer_option(got, "-t", 300)
    lines = []
    arcs = load_boost(files, lines, apex_bug=True)
    size = max(max(u, v) for u, v, _ in arcs)
    s, t = integer_option(got, "-s", -1), integer_option(got, "-g", -1)
    if not (0 <= s <= size and 0 <= t <= size):
        finish(139)
    if algorithm in ("BOA", "PPA"):
        arcs = [(u, v, c[:2]) for u, v, c in arcs]
    front = pareto(size + 1, arcs, s, t)
    failed = search_seconds() > limit + 1  # its CPU clock stops the search at t + 1 s
    if failed:
        front = [] if algorithm == "PPA" else partial(front)
    lines += ["Graph Size: %d" % size, "Start Computing Heuristic", "Finish Computing Heuristic",
              "", "Node expansion: 15", "Runtime: %g" % (limit + 1.08972 if failed else 0.000173)]
    solutions = ['{"id": %d, "parent": -1, "cost_until_now": [%s], "heuristic_cost": [%s], '
                 '"full_cost": [%s]}' % (t, ", ".join(map(str, c)), ", ".join("0" for _ in c),
                                        ", ".join(map(str, c))) for c in front]
    print("\n".join(lines + solutions + ["-----End Single Example-----"]))
    if os.path.isdir("output"):
        with open(os.path.join("output", got["-o"]), "a") as f:
            f.write("%s-%s (0)\t%d\t%d\t28\t15\t%d\t0.000173\n" % (algorithm, merge, s, t,
                                                                  len(front)))
    if "--logging_file" in got:
        with open(got["--logging_file"], "a") as f:
            f.write('[\n{\n\t"start_time": "Fri Nov 27 11:07:47 2026",\n\t"source": %d,\n'
                    '\t"target": %d,\n\t"search_info": {\n\t\t\t"name": "%s-s2",\n'
                    '\t\t\t"eps": [0, 0]\n\t\t},\n\t"finish_info": {\n\t\t\t"solutions": [\n'
                    % (s, t, algorithm))
            f.write(",\n".join("\t\t\t\t" + x for x in solutions) + "\n")
            f.write('\t\t\t],\n\t\t\t"amount_of_solutions": %d,\n\t\t\t"status": "%s"\n'
                    '\t\t}\n\t\t,\n\t"total_runtime(ms)": 0\n}\n]\n'
                    % (len(front), "Failed" if failed else "Success"))
    finish(0)


MOHS_ALGORITHMS = ("BOA", "ABOA", "Apex", "AnytimeApex", "AnytimeApexRestart", "AnytimeApexEnh",
                   "AnytimeApexHybrid", "WCApex", "LTMOA", "LTMOAeps", "LTMOAR", "LTMOAR1",
                   "LTMOAR2", "LTMOARBucket", "LTMOABucket", "LazyLTMOA")


def mohs(argv):
    got = options(argv, {"-m", "-s", "-g", "-a", "-t", "-e", "-o", "--logsolutions", "--merge"})
    if "-o" not in got:
        finish(134, "terminate called after throwing an instance of "
               "'boost::wrapexcept<boost::program_options::required_option>'")
    open(got["-o"], "a").close()  # created, empty, even if the run later crashes
    algorithm = got.get("-a", "Apex")
    if algorithm not in MOHS_ALGORITHMS:
        finish(255)
    files = got["-m"]
    if not 2 <= len(files) <= 6:
        finish(255, "no supported solver")
    limit = integer_option(got, "-t", 300)
    lines = []
    arcs = load_boost(files, lines, apex_bug=False)
    size = max(max(u, v) for u, v, _ in arcs) + 1
    s, t = integer_option(got, "-s", -1), integer_option(got, "-g", -1)
    if not (0 <= s < size and 0 <= t < size):
        finish(134, "terminate called after throwing an instance of 'std::out_of_range'")
    if algorithm in ("BOA", "ABOA"):
        arcs = [(u, v, c[:2]) for u, v, c in arcs]
    front = pareto(size, arcs, s, t)
    timed_out = algorithm != "BOA" and search_seconds() > limit + 1
    if timed_out:
        front = partial(front)
    ltmoa = algorithm.startswith("LTMOA") or algorithm == "LazyLTMOA"
    lines.append("Graph Size: %d" % size)
    if ltmoa and not timed_out:
        lines += ["queue time: 0", "dominance check time: 0"]
    lines += ["Work took 0.000000 seconds", "Node expansion: 15",
              "Runtime: %g" % (limit + 1.5 if timed_out else 0.0364537),
              "-----End Single Example-----"]
    if ltmoa:
        lines.append("vector comparison cnt: 65")
    print("\n".join(lines))
    if "--logsolutions" in got:
        directory = got["--logsolutions"]
        if not os.path.isdir(os.path.dirname(os.path.abspath(directory))):
            finish(134, "terminate called after throwing an instance of "
                   "'boost::filesystem::filesystem_error'")
        os.makedirs(directory, exist_ok=True)
        with open(os.path.join(directory, "%d_%d.txt" % (s, t)), "w") as f:
            for c in front:
                v = ",".join(map(str, c))
                f.write("[%s],[%s],%s\n" % (v, v, "-1e-06" if algorithm == "BOA" else "5.7e-05"))
    with open(got["-o"], "a") as f:
        f.write("LTMOA(%d)-array\t%d\t%d\t28\t15\t%d\t0.0364537\n" % (len(files), s, t, len(front)))
    finish(0)


def emoa(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print("[INFO] This program should be called as follows using a command line terminal.")
        finish(0)
    m = stoul(argv[3]) if len(argv) > 3 else 0
    if len(argv) != m + 5:
        print("M=%d, expected M+6 (%d) arguments, received %d" % (m, m + 6, len(argv) + 1))
        finish(255)
    s, t, limit = int(argv[0]), int(argv[1]), float(argv[2])
    files, result = argv[4:4 + m], argv[4 + m]
    texts = []
    for path in files:
        try:
            with open(path) as f:
                texts.append(f.read().split("\n"))
        except OSError:
            print("Error: ReadRoadmapFromFile()")
            finish(255, "[Error] file '%s' could not be opened" % path)
    arcs = {}  # one arc per (u, v): the last one read wins
    for i, line in enumerate(texts[0]):
        if line == "" or line[0] in "cp":
            continue
        words = line.split(" ")
        costs = []
        for text in texts:
            value = text[i][text[i].rfind(" ") + 1:]
            try:
                costs.append(float(value))
            except ValueError:
                finish(134, "terminate called after throwing an instance of "
                       "'std::invalid_argument'")
            if costs[-1] < 0:
                finish(134, "[ERROR] LoadSparseGraphDIMAC, input graph has negative cost !?")
        arcs[(int(words[1]), int(words[2]))] = tuple(costs)
    n = max(max(u, v) for u, v in arcs) + 1
    if not (0 <= s < n and 0 <= t < n):
        finish(134)
    front = pareto(n, [(u, v, c) for (u, v), c in arcs.items()], s, t)
    timed_out = search_seconds() > limit
    print("[INFO] RunEMOA, M=%d time_limit = %g" % (m, limit))
    if timed_out:
        print("[INFO] EMOA::Search timeout !")
        front = partial(front)
    print("[INFO] EMOA::Search exit.")
    with open(result, "w") as f:
        f.write("EMOAResults: \nn_generated: 28\nn_expanded: 13\nn_domCheck: 0\n"
                "rt_initHeu: 0.000138\nrt_search: %f\ntimeout: %d\nnum_nondom_labels_max: -1\n"
                "num_nondom_labels_avg: -1\nN: %d\n"
                % (limit + 0.001603 if timed_out else 0.000103, timed_out, len(front)))
        for k, c in enumerate(reversed(front)):  # hash-map order: not sorted
            f.write("Label: %d\n[%s]\n%d %d \n" % (51 - k, "".join("%f," % x for x in c), s, t))
    finish(1)


def tmda(argv):
    if len(argv) != 4:
        print("The program is meant to receive three arguments: file-directory, id of the source "
              "node, id of the target node, and the algorithm to be ran.")
        finish(1)
    path, s, t, algorithm = argv[0], stoul(argv[1]), stoul(argv[2]), argv[3]
    try:
        with open(path) as f:
            lines = f.read().split("\n")
    except OSError:
        lines = []
    header = next((i for i, line in enumerate(lines) if line.startswith("p")), None)
    if header is None:
        print("Could not determine the size of the graph %s. Abort." % path)
        finish(1)
    _, _, n, m = lines[header].split()
    n, m = stoul(n), stoul(m)
    body = lines[header + 1:]
    if body and body[-1] == "":
        body.pop()  # the file's last newline
    arcs = []
    for line in body:
        words = line.split()
        if not words:
            finish(139)  # an empty line after the header
        if words[0] != "a":
            continue
        if len(words) != 6:
            print("Your instance file does not match the compile dimension DIM. I will generate the "
                  "file ../instances/3d_%s and abort this run. Use the new file as input."
                  % os.path.basename(path))
            finish(1)
        u, v = stoul(words[1]), stoul(words[2])
        if u >= n or v >= n:
            finish(139)
        arcs.append((u, v, tuple(stoul(c) for c in words[3:])))
    if len(arcs) != m:
        finish(139)
    if s >= n or t >= n:
        finish(134, "malloc(): invalid size (unsorted)")
    if algorithm not in ("MDA", "NAMOA"):
        finish(0)
    front = pareto(n, arcs, s, t)
    if algorithm == "MDA" and not os.environ.get("STANDIN_NO_FRONT"):
        for c in front:
            print("Solution %d %d %d" % c)
    if os.environ.get("STANDIN_NO_SUMMARY"):
        finish(0)
    print("%s;%s;%d;%d;28;28;%d;0.0021;0.02;15" % ("T-MDA" if algorithm == "MDA" else "NAMOA_LAZY",
                                                os.path.basename(path), s, t, len(front)))
    finish(0)


# One stand-in per shipped profile of a published solver (profiles/NAME.toml), by that name.
STANDINS = {"apex": apex, "mohs": mohs, "emoa": emoa, "tmda": tmda}

if __name__ == "__main__":
    solver = sys.argv[1]
    record(solver, sys.argv[2:])
    STANDINS[solver](sys.argv[2:])
