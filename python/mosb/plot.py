"""matplotlib figures of `mosb plot` and `mosb report`, for finishing figures in a notebook.

    import mosb, mosb.plot
    ref, boa = mosb.open_solutions("ref.sol"), mosb.open_solutions("boa.sol")
    fig = mosb.plot.front(boa, 0, reference=ref)      # a matplotlib.figure.Figure
    fig = mosb.plot.cactus([ref, boa]); fig.savefig("cactus.pdf")

Each function takes mosb.Solutions (or paths, opened with mosb.open_solutions) and returns a new
matplotlib.figure.Figure, built without pyplot (no global state, any backend). The conventions are
the SVG figures' (spec/EVALUATION.md §5): Okabe–Ito colours, reference vectors as hollow blue
rings under the solver's smaller vermillion dots, value axes from 0, a subtitle saying when a
front of more than two objectives is drawn as a projection. The runtime figures read the data as
the report's do (spec/EVALUATION.md §7): the solvers' own runtime where every file has one on one
clock, else mosb's wall clock (`runtime="wall"` or `"reported"` chooses); the cactus plot and the
performance profile count solved queries, the scatter plot the queries both completed (solved or
shown unreachable). Their data is the report's own, computed by the library
(mosb/runtime_figures.hpp); this module draws it. matplotlib is imported on first call (Debian:
python3-matplotlib).
"""
import math

import numpy as np

from . import Solutions, _mosb, _require, open_solutions

__all__ = ["OKABE_ITO", "front", "cactus", "performance_profile", "runtime_scatter"]

# Okabe & Ito's colour-blind-safe palette: orange, sky blue, bluish green, yellow, blue,
# vermillion, reddish purple, black.
OKABE_ITO = ("#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2", "#D55E00", "#CC79A7",
             "#000000")
# Series colours without yellow, in the SVG figures' order.
_SERIES = ("#0072B2", "#D55E00", "#009E73", "#E69F00", "#CC79A7", "#56B4E9", "#000000")


def _figure(figsize):
    figure = _require("matplotlib.figure", "matplotlib", "mosb.plot")
    return figure.Figure(figsize=figsize, layout="constrained")


def _solutions(s):
    return s if isinstance(s, Solutions) else open_solutions(s)


def _name(s):
    return s.solver_name


def _objective(s, objective):
    if isinstance(objective, str):
        return s.objectives.index(objective)
    return int(objective)


def front(solutions, query, reference=None, objectives=(0, 1), figsize=(6.4, 4.0)):
    """Query `query`'s front on two objectives (names or positions): the solver's vectors as
    dots over the reference's as rings, the legend counting each set."""
    s = _solutions(solutions)
    x, y = (_objective(s, o) for o in objectives)
    fig = _figure(figsize)
    ax = fig.add_subplot()
    if reference is not None:
        r = _solutions(reference)
        values = r.front(query)
        ax.scatter(values[x], values[y], s=49, facecolors="none", edgecolors=OKABE_ITO[4],
                   linewidths=1.5, label="reference %s (%d vectors)" % (_name(r), len(values[x])),
                   zorder=2)
    values = s.front(query)
    ax.scatter(values[x], values[y], s=16, color=OKABE_ITO[5], alpha=0.75, edgecolors="white",
               linewidths=0.5, label="%s (%d vectors)" % (_name(s), len(values[x])), zorder=3)
    ax.set_xlabel(s.objectives[x])
    ax.set_ylabel(s.objectives[y])
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    title = "query %d of %s" % (query, s.query_set)
    if len(s.objectives) > 2:
        title += "\nprojection on %s, %s of %d objectives" % (
            s.objectives[x], s.objectives[y], len(s.objectives))
    ax.set_title(title)
    ax.legend(loc="upper right")
    return fig


def _runtime_statistic(files, runtime=None):
    """The statistic every runtime figure of `files` shows, as lib/solutions' choose_runtime picks
    it: `runtime` ("wall" or "reported") when given; else the solvers' own
    (reported_runtime_seconds) when every file has it on one clock
    (solution.solver.param.profile.runtime_clock, wall when not said), else mosb's wall clock."""
    if runtime is not None:
        if runtime not in ("wall", "reported"):
            raise ValueError("runtime: 'wall' or 'reported', not %r" % (runtime,))
        return "runtime_seconds" if runtime == "wall" else "reported_runtime_seconds"
    clocks = set()
    for s in files:
        if s.statistic("reported_runtime_seconds") is None:
            return "runtime_seconds"
        clocks.add(s.metadata.get("solution.solver.param.profile.runtime_clock", "wall"))
    return "reported_runtime_seconds" if len(clocks) == 1 else "runtime_seconds"


def _runs(s, statistic):
    """A file's queries as the runtime figures read them: status codes and runtimes (NaN where
    absent)."""
    values = s.statistic(statistic)
    if values is None:
        values = np.full(s.query_count, np.nan)
    return s.statuses(), values


def _not_drawn(count, what):
    return ", %d %s not drawn" % (count, what) if count else ""


def cactus(solutions, runtime=None, figsize=(6.4, 4.0)):
    """Queries solved within a time, per solver: its solved queries' runtimes sorted, against
    their count (log runtime axis; those of 0 s counted in the legend, not drawn)."""
    files = [_solutions(s) for s in solutions]
    statistic = _runtime_statistic(files, runtime)
    fig = _figure(figsize)
    ax = fig.add_subplot()
    for k, s in enumerate(files):
        data = _mosb.cactus_series(*_runs(s, statistic))
        x, y = zip(*data["points"]) if data["points"] else ((), ())
        ax.plot(x, y, marker="o", markersize=3, color=_SERIES[k % len(_SERIES)],
                label="%s (%d solved%s)" % (_name(s), data["solved"],
                                            _not_drawn(data["zero"], "in 0 s")))
    ax.set_yscale("log")
    ax.set_xlabel("queries solved")
    ax.set_ylabel("runtime [s]")
    ax.set_title("Cactus plot")
    ax.legend()
    return fig


def performance_profile(solutions, runtime=None, figsize=(6.4, 4.0)):
    """The Dolan–Moré profile over the queries some solver solved: per solver, the fraction solved
    within τ times the best runtime. The files must share their instance, view and query set."""
    files = [_solutions(s) for s in solutions]
    statistic = _runtime_statistic(files, runtime)
    runs = [_runs(s, statistic) for s in files]
    data = _mosb.performance_profile([r[0] for r in runs], [r[1] for r in runs])
    fig = _figure(figsize)
    ax = fig.add_subplot()
    top = 1.0
    for k, (s, points) in enumerate(zip(files, data["series"])):
        x, y = zip(*points) if points else ((), ())
        top = max([top, *x])
        ax.step(x, y, where="post", color=_SERIES[k % len(_SERIES)], label=_name(s))
    ax.set_xscale("log")
    ax.set_xlim(1, 10 ** math.ceil(math.log10(top)) if top > 1 else 10)
    ax.set_ylim(0, 1)
    ax.set_xlabel("τ: runtime / best runtime")
    ax.set_ylabel("fraction of queries within τ")
    ax.set_title("Performance profile (Dolan–Moré, %d queries)" % data["queries"])
    ax.legend(loc="lower right")
    return fig


def runtime_scatter(a, b, runtime=None, figsize=(5.0, 5.0)):
    """Per-query runtimes of solver A (x) against B (y) over the queries both completed (solved
    or shown unreachable), log–log with the diagonal; those of 0 s counted in the title."""
    a, b = _solutions(a), _solutions(b)
    statistic = _runtime_statistic([a, b], runtime)
    data = _mosb.runtime_scatter(*_runs(a, statistic), *_runs(b, statistic))
    x, y = (np.array(v, dtype=float) for v in zip(*data["points"])) if data["points"] else (
        np.array([]), np.array([]))
    fig = _figure(figsize)
    ax = fig.add_subplot()
    ax.scatter(x, y, s=16, color=OKABE_ITO[4], alpha=0.75)
    values = np.r_[x, y]
    lo = 10 ** math.floor(math.log10(values.min())) if len(values) else 0.1
    hi = 10 ** math.ceil(math.log10(values.max())) if len(values) else 1
    ax.plot([lo, hi], [lo, hi], color="#555555", linewidth=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(lo, hi)
    ax.set_ylim(lo, hi)
    ax.set_aspect("equal")
    ax.set_xlabel("%s runtime [s]" % _name(a))
    ax.set_ylabel("%s runtime [s]" % _name(b))
    ax.set_title("Runtime per query (%d both completed%s)"
                 % (len(x) + data["zero"], _not_drawn(data["zero"], "in 0 s")))
    return fig
