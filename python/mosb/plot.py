"""matplotlib figures of `mosb plot` and `mosb report`, for finishing figures in a notebook.

    import mosb, mosb.plot
    ref, boa = mosb.open_solutions("ref.sol"), mosb.open_solutions("boa.sol")
    fig = mosb.plot.front(boa, 0, reference=ref)      # a matplotlib.figure.Figure
    fig = mosb.plot.cactus([ref, boa]); fig.savefig("cactus.pdf")

Each function takes mosb.Solutions (or paths, opened with mosb.open_solutions) and returns a new
matplotlib.figure.Figure, built without pyplot (no global state, any backend). The conventions are
the SVG figures' (spec/EVALUATION.md §5): Okabe–Ito colours, reference vectors as hollow blue
rings under the solver's smaller vermillion dots, value axes from 0, a subtitle saying when a
front of more than two objectives is drawn as a projection. matplotlib is imported on first call
(Debian: python3-matplotlib).
"""
import math

import numpy as np

from . import Solutions, _require, open_solutions

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


def _runtimes(s):
    """Runtimes of the solved queries (NaN where not solved or absent)."""
    runtime = s.statistic("runtime_seconds")
    if runtime is None:
        return np.full(s.query_count, np.nan)
    solved = s.statuses() == 0
    return np.where(solved, runtime, np.nan)


def cactus(solutions, figsize=(6.4, 4.0)):
    """Queries solved within a time, per solver: its solved queries' runtimes sorted, against
    their count (log runtime axis)."""
    fig = _figure(figsize)
    ax = fig.add_subplot()
    for k, s in enumerate(map(_solutions, solutions)):
        times = np.sort(_runtimes(s)[~np.isnan(_runtimes(s))])
        ax.plot(np.arange(1, len(times) + 1), times, marker="o", markersize=3,
                color=_SERIES[k % len(_SERIES)], label="%s (%d solved)" % (_name(s), len(times)))
    ax.set_yscale("log")
    ax.set_xlabel("queries solved")
    ax.set_ylabel("runtime [s]")
    ax.set_title("Cactus plot")
    ax.legend()
    return fig


def performance_profile(solutions, figsize=(6.4, 4.0)):
    """The Dolan–Moré profile over the queries some solver solved: per solver, the fraction solved
    within τ times the best runtime. The files must share their instance, view and query set."""
    files = [_solutions(s) for s in solutions]
    times = np.array([_runtimes(s) for s in files])  # solver x query
    solved_by_some = ~np.all(np.isnan(times), axis=0)
    times = np.maximum(times[:, solved_by_some], 1e-6)
    best = np.nanmin(times, axis=0)
    fig = _figure(figsize)
    ax = fig.add_subplot()
    n = times.shape[1]
    top = 1.0
    for k, s in enumerate(files):
        ratios = np.sort((times[k] / best)[~np.isnan(times[k])])
        top = max(top, ratios[-1] if len(ratios) else 1.0)
        fractions = np.arange(1, len(ratios) + 1) / max(n, 1)
        ax.step(np.r_[1.0, ratios], np.r_[0.0, fractions], where="post",
                color=_SERIES[k % len(_SERIES)], label=_name(s))
    ax.set_xscale("log")
    ax.set_xlim(1, 10 ** math.ceil(math.log10(top)) if top > 1 else 10)
    ax.set_ylim(0, 1)
    ax.set_xlabel("τ: runtime / best runtime")
    ax.set_ylabel("fraction of queries within τ")
    ax.set_title("Performance profile (Dolan–Moré)")
    ax.legend(loc="lower right")
    return fig


def runtime_scatter(a, b, figsize=(5.0, 5.0)):
    """Per-query runtimes of solver A (x) against B (y) over the queries both solved, log–log
    with the diagonal."""
    a, b = _solutions(a), _solutions(b)
    x, y = _runtimes(a), _runtimes(b)
    both = ~np.isnan(x) & ~np.isnan(y)
    fig = _figure(figsize)
    ax = fig.add_subplot()
    ax.scatter(x[both], y[both], s=16, color=OKABE_ITO[4], alpha=0.75)
    positive = np.r_[x[both], y[both]]
    positive = positive[positive > 0]
    lo = 10 ** math.floor(math.log10(positive.min())) if len(positive) else 0.1
    hi = 10 ** math.ceil(math.log10(positive.max())) if len(positive) else 1
    ax.plot([lo, hi], [lo, hi], color="#555555", linewidth=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(lo, hi)
    ax.set_ylim(lo, hi)
    ax.set_aspect("equal")
    ax.set_xlabel("%s runtime [s]" % _name(a))
    ax.set_ylabel("%s runtime [s]" % _name(b))
    ax.set_title("Runtime per query (%d both solved)" % int(both.sum()))
    return fig
