"""Read mosb multi-objective shortest-path instances (.mosb) from Python, zero-copy.

    import mosb
    g = mosb.open("grid.mosb")
    g.forward_offsets, g.forward_targets      # read-only numpy views into the mapping
    g.cost("c1"), g.queries("default"), g.metadata

The reading, the checks and the error messages are those of the C++ library (the same sources the
`mosb` program is built from); every failure is a `mosb.Error` whose message names the file and
whose `code` is the C++ ErrorCode's name ("io", "not_mosb", "version", "damaged", "not_found",
"invalid_argument", "packed", "no_memory", "other"); the message is one line, control characters
quoted from the file escaped as `mosb inspect` escapes them. Text in a file that is not UTF-8 is
such an error ('damaged'), never a UnicodeDecodeError. Running out of memory while decoding a file
is 'no_memory'; elsewhere (numpy, an adapter's library) it stays Python's MemoryError. An argument
of the wrong type (a view that is neither a name nor a View) raises TypeError, and a negative index
IndexError, as Python does.
Paths may be str, bytes or os.PathLike; one with a NUL byte is refused.
Arrays are views into the memory-mapped file: they are read-only and each keeps the mapping alive,
so they stay valid after the object that handed them out is gone. A mapped file truncated or
rewritten in place meanwhile ends the process with SIGBUS (what mmap does, not an exception):
replace a file by writing a new one and renaming it over the old, as mosb's own writers do.
Opening checks the header and section table only; verify at "structure" before indexing arrays by
ids read from the file (the adapters do so themselves).
"""
import collections
import importlib
import io
import json
import operator
import os

import numpy as np

from . import _mosb
from ._mosb import Error

__version__ = _mosb.__version__
__all__ = ["Error", "Instance", "STATUSES", "Solutions", "Store", "StoreInstance", "View",
           "VERIFY_LEVELS", "load", "open", "open_solutions", "suite"]

VERIFY_LEVELS = _mosb.VERIFY_LEVELS
# The query statuses of solution files (spec/SOLUTIONS.md §4), indexed by their stored code.
STATUSES = _mosb.STATUSES

# A view (spec/FORMAT.md §7 `view.NAME.*`): objective indices in view order, and the name of the
# view's query set (None when the view names none).
View = collections.namedtuple("View", "name objectives query_set")


def _error(code, message):
    """A mosb.Error raised from Python, with the same `code` attribute as the library's."""
    error = Error(message)
    error.code = code
    return error


def _os_path(path, function):
    """`path` (str, bytes or os.PathLike) as the bytes the operating system gets, as open() takes
    it; an embedded NUL would silently cut the name short, so it is refused."""
    encoded = os.fsencode(os.fspath(path))
    if b"\0" in encoded:
        raise _error("invalid_argument",
                     "mosb.%s: the path %r contains a NUL byte" % (function, path))
    return encoded


def open(path, verify=None):  # noqa: A001 (the package's entry point, like io.open)
    """Maps and checks the instance at `path` (FORMAT.md §9); `verify` is an optional level of
    VERIFY_LEVELS run right after opening. Raises mosb.Error naming the file; a packed file
    (`mosb pack`) is refused at once with code 'packed' (mosb.load decodes it).

    The file stays mapped while the instance or an array from it lives: truncating or rewriting
    it in place meanwhile ends the process with SIGBUS (what mmap does). Replace a file by
    writing a new one and renaming it over the old, as mosb's own writers do."""
    instance = Instance(_mosb.Reader.open(_os_path(path, "open")))
    if verify is not None:
        instance.verify(verify)
    return instance


def suite():
    """The benchmark suite as data: spec/suite.json, the description `mosb suite build` builds from
    (the generated benchmarks' parameters and views, one recipe per raw-source benchmark with its
    input files). A new dict on every call."""
    with io.open(os.path.join(os.path.dirname(__file__), "suite.json"), encoding="utf-8") as f:
        return json.load(f)


def load(path, verify=None, max_memory=None):
    """Like open(), but a packed file (`mosb pack`) is decoded into memory the instance owns (every
    section's checksum checked) instead of being refused; an unpacked file is mapped as by open().
    Decoding must fit in `max_memory` bytes (default: the memory available), checked against the
    sizes the file declares before anything is allocated: past it, mosb.Error with code
    'no_memory'. An unpacked file stays mapped, with open()'s SIGBUS caveat."""
    if max_memory is not None and (not isinstance(max_memory, int) or isinstance(max_memory, bool)
                                   or not 0 < max_memory < 2**64):
        raise TypeError("mosb.load: max_memory must be an int in [1, 2^64), not %r" % (max_memory,))
    instance = Instance(_mosb.Reader.load(_os_path(path, "load"), max_memory or 0))
    if verify is not None:
        instance.verify(verify)
    return instance


# What a store resolves a name to: the instance (verified in full), its view (None: every
# objective), the query set to run (None when the view names none), the path mapped (for a packed
# entry its unpacked copy in the store's cache) and the entry's file name in the MANIFEST.
StoreInstance = collections.namedtuple("StoreInstance", "instance view query_set path file")


class Store:
    """A store (`mosb store init|add`): a directory of instances and the MANIFEST listing them."""

    def __init__(self, directory):
        self._directory = _os_path(directory, "Store")  # NUL refused, as for mosb.open
        self.directory = os.fsdecode(self._directory)
        self.files = tuple(_mosb.store_files(self._directory))  # mosb.Error when not a store

    def __repr__(self):
        return "<mosb.Store %r: %d files>" % (self.directory, len(self.files))

    def instance(self, name):
        """Resolves "BENCHMARK/VIEW", a view name or a benchmark name as mosb::Store::instance
        does; a packed entry is unpacked into the store's cache on first use."""
        reader, view, query_set, path, file = _mosb.store_instance(self._directory, name)
        instance = Instance(reader)
        return StoreInstance(instance, instance.view(view) if view else None, query_set or None,
                             path, file)


def _require(module, package, purpose):
    """Imports an optional dependency, or says which package is missing and what needs it."""
    try:
        return importlib.import_module(module)
    except ImportError as e:
        raise ImportError("mosb: %s needs the Python package '%s', which is not installed "
                          "(Debian: apt-get install python3-%s)" % (purpose, package, package)) from e


class Instance:
    """An open .mosb file. Obtain one with mosb.open()."""

    def __init__(self, reader):
        self._reader = reader
        self._structure_checked = False
        self._views = None  # name -> View, all resolved at the first view() (None: not yet)

    def _checked(self):
        """The reader, once its structure is verified (offsets, id ranges, the reverse CSR, the
        metadata; O(m), once per instance; checksums are not recomputed): the adapters walk the
        arcs, and an unchecked file could send them out of bounds or into huge allocations."""
        if not self._structure_checked:
            self._reader.verify("structure")
            self._structure_checked = True
        return self._reader

    def __repr__(self):
        return "<mosb.Instance %r: %d vertices, %d arcs, objectives %s>" % (
            self.path, self.vertex_count, self.arc_count, ",".join(self.objectives))

    # --- graph ------------------------------------------------------------------------------
    @property
    def path(self):
        return self._reader.display_name

    @property
    def format_version(self):
        return self._reader.format_version

    @property
    def vertex_count(self):
        return self._reader.vertex_count

    @property
    def arc_count(self):
        return self._reader.arc_count

    @property
    def forward_offsets(self):
        """u64, n+1: the out-arcs of v are arcs forward_offsets[v] .. forward_offsets[v+1]-1."""
        return self._reader.forward_offsets()

    @property
    def forward_targets(self):
        """u32, m: the head of each arc (arc ids are positions in the forward CSR)."""
        return self._reader.forward_targets()

    @property
    def reverse_offsets(self):
        return self._reader.reverse_offsets()

    @property
    def reverse_sources(self):
        return self._reader.reverse_sources()

    @property
    def reverse_arcs(self):
        """u32, m: the forward arc id of each in-arc entry (its cost is cost[reverse_arcs[j]])."""
        return self._reader.reverse_arcs()

    def arc_sources(self):
        """u32, m: the tail of each forward arc (computed, not stored: a new array). Verifies the
        structure first (once per instance)."""
        self._checked()
        out_degrees = np.diff(self.forward_offsets.view(np.int64))  # offsets <= m < 2^32
        return np.repeat(np.arange(self.vertex_count, dtype=np.uint32), out_degrees)

    # --- objectives, views, queries --------------------------------------------------------
    @property
    def objectives(self):
        """Objective names in objective order."""
        return tuple(self._reader.objective_names())

    def objective_index(self, name_or_index):
        if isinstance(name_or_index, str):
            return self._reader.objective_index(name_or_index)
        index = operator.index(name_or_index)
        if index < 0:
            raise IndexError("mosb: objective index %d is negative" % index)
        if index >= len(self.objectives):  # the library's error for cost(index)
            raise _error("invalid_argument", "%s: objective index %d out of range (the file has "
                         "%d objectives)" % (self.path, index, len(self.objectives)))
        return index

    def cost(self, name_or_index):
        """One objective's cost per arc, in its stored type (u8/u16/u32/u64/f32/f64)."""
        return self._reader.cost(self.objective_index(name_or_index))

    @property
    def views(self):
        """View names (metadata `view.NAME.objectives`), sorted."""
        return tuple(self._reader.view_names())

    def view(self, name):
        """The view `name` as a View(name, objectives, query_set); mosb.Error when absent.
        The first call resolves every view at once (one pass over the metadata), so resolving
        all of a file's views costs O(V log V), not O(V^2)."""
        if not isinstance(name, str):
            raise TypeError("mosb: a view name is a str, not %s" % type(name).__name__)
        if self._views is None:
            try:
                self._views = {v[0]: View(v[0], tuple(v[1]), v[2] or None)
                               for v in self._reader.views()}
            except Error:
                self._views = False  # a bad view: resolve one at a time, each with its error
        if self._views and name in self._views:
            return self._views[name]
        name, objectives, query_set = self._reader.view(name)  # absent: the error, with the list
        return View(name, tuple(objectives), query_set or None)

    @property
    def query_sets(self):
        return tuple(self._reader.query_set_names())

    def queries(self, name):
        """The query set `name` as a read-only (q, 2) u32 array of (start, goal) rows."""
        return self._reader.queries(name)

    @property
    def metadata(self):
        """The metadata section as a new dict (key -> unescaped value)."""
        return self._reader.metadata()

    @property
    def digest(self):
        """The content digest (FORMAT.md §8), 32 hex digits."""
        return self._reader.digest()

    def verify(self, level="full"):
        """Runs `mosb verify --level LEVEL`'s checks; raises mosb.Error with the same message
        the CLI prints after FAIL."""
        self._reader.verify(level)

    # --- adapters ---------------------------------------------------------------------------
    def _objective_list(self, view):
        """Objective indices of `view` (a name or a View), or all objectives when None."""
        if view is None:
            return list(range(len(self.objectives)))
        if isinstance(view, str):
            view = self.view(view)
        if not isinstance(view, View):
            raise TypeError("mosb: view must be a view name, a mosb.View or None, not %s"
                            % type(view).__name__)
        return list(view.objectives)

    def to_scipy_csr(self, objective, parallel="keep"):
        """The graph as an n x n scipy.sparse.csr_matrix whose values are one objective's costs.

        `parallel` says what becomes of parallel arcs (several arcs u -> v):
        - "keep" (the default): one entry per arc, and nothing is copied: the matrix's `data` is
          the mapped column (every cost type, u8..u64, f32 and f64, is a scipy data type). The
          structure is the forward CSR; scipy keeps one index type for indices and indptr, so
          forward_targets is reinterpreted as int32 without a copy when n < 2^31 and indptr (u64
          on disk) becomes a new int32 array of n+1 entries. Beware: scipy treats duplicate
          entries as a sum (toarray(), arithmetic, sum_duplicates()), so arcs of cost 5 and 1
          read as one entry of 6, which no path costs.
        - "min" or "max": one entry per (u, v), the cheapest or dearest arc's cost, in the
          column's type: what a shortest-path computation over the matrix needs ("min").
        - "sum": one entry per (u, v), the costs added in uint64 (integer costs) or float64.
        Reduced matrices are new arrays, with sorted indices.
        """
        sparse = _require("scipy.sparse", "scipy", "to_scipy_csr")
        if parallel not in ("keep", "min", "max", "sum"):
            raise ValueError("mosb: to_scipy_csr: parallel must be 'keep', 'min', 'max' or 'sum', "
                             "not %r" % (parallel,))
        self._checked()
        data = self.cost(objective)
        n = self.vertex_count
        # Ids are < n and offsets <= m < 2^32, so the signed reinterpretations hold the same values.
        if n <= np.iinfo(np.int32).max:
            indices = self.forward_targets.view(np.int32)
        else:
            indices = self.forward_targets.astype(np.int64)
        indptr = self.forward_offsets.view(np.int64)
        if parallel == "keep":
            return sparse.csr_matrix((data, indices, indptr), shape=(n, n), copy=False)
        rows = self.arc_sources()
        # Arcs grouped by (source, target), each group's costs increasing.
        order = np.lexsort((data, indices, rows))
        rows, cols, values = rows[order], indices[order], data[order]
        starts = np.flatnonzero(np.r_[len(rows) > 0, (rows[1:] != rows[:-1]) | (cols[1:] != cols[:-1])])
        if parallel == "min":
            reduced = values[starts]
        elif parallel == "max":
            reduced = values[np.r_[starts[1:], len(values)] - 1]
        else:
            wide = np.float64 if values.dtype.kind == "f" else np.uint64
            reduced = np.add.reduceat(values.astype(wide), starts) if len(starts) else values.astype(wide)
        return sparse.csr_matrix((reduced, (rows[starts], cols[starts])), shape=(n, n))

    def to_networkx(self, view=None):
        """A networkx.MultiDiGraph: vertices 0..n-1, one edge per arc keyed by its arc id, with
        one attribute per objective of `view` (all objectives when None)."""
        nx = _require("networkx", "networkx", "to_networkx")
        self._checked()
        graph = nx.MultiDiGraph()
        graph.add_nodes_from(range(self.vertex_count))
        names = self.objectives
        columns = [(names[i], self.cost(i).tolist()) for i in self._objective_list(view)]
        sources = self.arc_sources().tolist()
        targets = self.forward_targets.tolist()
        graph.add_edges_from(
            (sources[a], targets[a], a, {name: values[a] for name, values in columns})
            for a in range(self.arc_count))
        return graph

    def to_igraph(self, view=None):
        """A directed igraph.Graph: vertices 0..n-1, edge i = arc i, one edge attribute per
        objective of `view` (all objectives when None)."""
        ig = _require("igraph", "igraph", "to_igraph")
        self._checked()
        edges = np.column_stack((self.arc_sources(), self.forward_targets)).tolist()
        graph = ig.Graph(n=self.vertex_count, edges=edges, directed=True)
        names = self.objectives
        for i in self._objective_list(view):
            graph.es[names[i]] = self.cost(i).tolist()
        return graph

    def arcs_frame(self, view=None):
        """A pandas.DataFrame with one row per arc (index: arc id): source, target, then one
        column per objective of `view` (all objectives when None). pandas copies the columns."""
        pd = _require("pandas", "pandas", "arcs_frame")
        self._checked()
        columns = {"source": self.arc_sources(), "target": self.forward_targets}
        names = self.objectives
        for i in self._objective_list(view):
            columns[names[i]] = self.cost(i)
        frame = pd.DataFrame(columns)
        frame.index.name = "arc"
        return frame


def open_solutions(path):
    """Maps the solution file at `path` (spec/SOLUTIONS.md; a packed one, format 1.6, is decoded
    into memory the result owns) and checks its payload (checksums, statuses, offsets, values), as
    every `mosb` command that reads fronts does: a damaged file is a mosb.Error naming it, never
    numbers from corrupt data. Fronts are not checked against their instance here (`mosb
    solutions verify --instance` does that)."""
    return Solutions(_mosb.SolutionsReader.open(_os_path(path, "open_solutions")))


class Solutions:
    """An open solution file: a solver's fronts for one view and query set of one instance.
    Obtain one with mosb.open_solutions(). Arrays are read-only views of the mapping, as for
    Instance (the same SIGBUS caveat applies to a file rewritten in place)."""

    def __init__(self, reader):
        self._reader = reader
        self.objectives = tuple(reader.objective_names())
        self.metadata = reader.metadata()
        self.front_offsets = reader.front_offsets()  # Q+1 entries: query q's rows of the columns

    def __repr__(self):
        return "<mosb.Solutions %r: view %s, %d queries, %d vectors>" % (
            self.path, self.view, self.query_count, self.vector_count)

    path = property(lambda self: self._reader.display_name)
    instance_digest = property(lambda self: self._reader.instance_digest)
    # The name the solver is shown under (as by mosb eval and report): solution.solver.name, else
    # the file's name without directory and extension.
    solver_name = property(lambda self: self._reader.solver_name)
    view = property(lambda self: self._reader.view)
    query_set = property(lambda self: self._reader.query_set)
    query_count = property(lambda self: self._reader.query_count)
    vector_count = property(lambda self: self._reader.vector_count)

    @property
    def solver(self):
        """solution.solver.name/version, solution.epsilon and solution.machine (None when absent)."""
        get = self.metadata.get
        return {"name": get("solution.solver.name"), "version": get("solution.solver.version"),
                "epsilon": get("solution.epsilon", "0"), "machine": get("solution.machine")}

    def statuses(self):
        """Each query's status, as a numpy array of codes indexing STATUSES."""
        return self._reader.statuses()

    def status(self, query):
        """Query `query`'s status by name ("solved", "timeout", ...)."""
        return STATUSES[self.statuses()[self._query(query)]]

    def column(self, objective):
        """All fronts' values of one objective (name or index), zero-copy: uint64 (integer
        objectives) or float64 path sums; files written before format 1.3 hold the arc type."""
        if isinstance(objective, str):
            if objective not in self.objectives:
                raise _error("not_found", "%s: no objective %r in the view (objectives: %s)" % (
                    self.path, objective, ", ".join(self.objectives)))
            objective = self.objectives.index(objective)
        objective = operator.index(objective)
        if not 0 <= objective < len(self.objectives):
            raise IndexError("objective index %d out of range (%d objectives)" % (
                objective, len(self.objectives)))
        return self._reader.column(objective)

    def front(self, query):
        """Query `query`'s front: one zero-copy array per objective (a slice of column()), in the
        view's objective order. Empty arrays for a query with no front."""
        q = self._query(query)
        begin, end = int(self.front_offsets[q]), int(self.front_offsets[q + 1])
        return tuple(self.column(i)[begin:end] for i in range(len(self.objectives)))

    def statistic(self, name):
        """One statistic per query as float64 (NaN where absent), or None when the file has no
        such column: runtime_seconds, expanded, generated, peak_memory_bytes, exit_status."""
        return self._reader.statistic(name)

    def fronts_frame(self):
        """A pandas.DataFrame with one row per front vector: query, status, then one column per
        objective (pandas copies the columns)."""
        pd = _require("pandas", "pandas", "fronts_frame")
        sizes = np.diff(self.front_offsets).astype(np.int64)
        queries = np.repeat(np.arange(self.query_count, dtype=np.uint64), sizes)
        columns = {"query": queries,
                   "status": pd.Categorical.from_codes(np.repeat(self.statuses(), sizes),
                                                       categories=list(STATUSES))}
        for i, name in enumerate(self.objectives):
            columns[name] = self.column(i)
        return pd.DataFrame(columns)

    def queries_frame(self):
        """A pandas.DataFrame with one row per query (index: query): status, front_size and every
        statistic the file has (float64, NaN where absent)."""
        pd = _require("pandas", "pandas", "queries_frame")
        columns = {"status": pd.Categorical.from_codes(self.statuses(), categories=list(STATUSES)),
                   "front_size": np.diff(self.front_offsets)}
        for name in ("runtime_seconds", "expanded", "generated", "peak_memory_bytes",
                     "exit_status"):
            values = self.statistic(name)
            if values is not None:
                columns[name] = values
        frame = pd.DataFrame(columns)
        frame.index.name = "query"
        return frame

    def _query(self, query):
        q = operator.index(query)
        if not 0 <= q < self.query_count:
            raise IndexError("query %d out of range (%d queries)" % (q, self.query_count))
        return q
