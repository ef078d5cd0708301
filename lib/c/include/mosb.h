/* mosb.h: the C ABI of libmosb (link with mosb::mosb_c, or `pkg-config --libs mosb_c`).
 *
 * Plain C99, usable from C++11 and through foreign-function interfaces (Rust bindgen, Julia
 * ccall, Python ctypes). A mosb_graph is an opened, memory-mapped .mosb instance.
 *
 * Errors: every call that can fail returns a mosb_status; on anything but MOSB_OK it leaves its
 * outputs untouched and mosb_last_error() returns a one-line message naming the file (a call
 * error, such as a NULL pointer, names the function instead, as does running out of memory outside
 * the decoding of a file; control bytes quoted from a file are escaped as `mosb inspect` escapes
 * them: \n, \t, \xNN). No C++ exception crosses this interface.
 *
 * Lifetime: every pointer a call hands out (arrays, names, metadata values, the digest) points into
 * the mapping or into the handle and stays valid until mosb_close() on that handle.
 *
 * Trust: opening reads the header and section table only. Before indexing arrays by ids read from
 * the file, verify its structure (mosb_open_verified with MOSB_VERIFY_STRUCTURE, or mosb_verify).
 * A mapped file truncated or rewritten in place ends the process with SIGBUS in any call that
 * reads it (what mmap does): replace files by writing a new one and renaming it over the old.
 *
 * Threads: every call except mosb_close may be made on one handle from many threads at once.
 * mosb_close must not run while another thread uses the handle. mosb_last_error() is per thread:
 * it reports the last failure of the calling thread.
 *
 * Arrays are in the file's little-endian layout (the library refuses big-endian hosts). Vertex and
 * arc ids are 0-based. The forward CSR: the arcs out of v are offsets[v] .. offsets[v+1]-1, arc a
 * goes to targets[a]; cost column j gives the cost of arc a at index a. The reverse CSR lists the
 * arcs into v: sources[r] is the tail and arcs[r] the forward arc id of entry r. */
#ifndef MOSB_H
#define MOSB_H

/* A C header: C++ modernizations do not apply. NOLINTBEGIN(modernize-*) */
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Mirrors mosb::ErrorCode (error.hpp), plus MOSB_OK and MOSB_ERROR_NO_MEMORY. */
typedef enum mosb_status {
  MOSB_OK = 0,
  MOSB_ERROR_OTHER = 1,            /* not classified */
  MOSB_ERROR_IO = 2,               /* cannot open or map the file */
  MOSB_ERROR_NOT_MOSB = 3,         /* not a mosb file */
  MOSB_ERROR_VERSION = 4,          /* a format version or feature this library does not read */
  MOSB_ERROR_DAMAGED = 5,          /* breaks a rule of the format (checksums, structure) */
  MOSB_ERROR_NOT_FOUND = 6,        /* no objective, query set, view or metadata key of that name */
  MOSB_ERROR_INVALID_ARGUMENT = 7, /* NULL pointer, index out of range, buffer of the wrong size,
                                      a .mosb file of another kind (a solution file) */
  MOSB_ERROR_PACKED = 8,           /* a zstd-packed section cannot be mapped zero-copy */
  MOSB_ERROR_NO_MEMORY = 9         /* out of memory, or decoding needs more than the cap allows */
} mosb_status;

/* The element type of a column; the values are those of the file format (spec/FORMAT.md §5). Cost
 * columns are unsigned or float; the signed types (MOSB_I8 ... MOSB_I64) are valid in vertex_data
 * and arc_data sections (§4). */
typedef enum mosb_element_type {
  MOSB_U8 = 1,
  MOSB_U16 = 2,
  MOSB_U32 = 3,
  MOSB_U64 = 4,
  MOSB_I8 = 5,
  MOSB_I16 = 6,
  MOSB_I32 = 7,
  MOSB_I64 = 8,
  MOSB_F32 = 9,
  MOSB_F64 = 10
} mosb_element_type;

/* How much of the file mosb_verify (and mosb_open_verified) checks (spec/FORMAT.md §9): the header
 * only; every checksum; every structural rule (id ranges, offsets, the reverse CSR, metadata,
 * padding; no checksum is recomputed); both, checksums and structure. */
typedef enum mosb_verify_level {
  MOSB_VERIFY_HEADER = 0,
  MOSB_VERIFY_CHECKSUMS = 1,
  MOSB_VERIFY_STRUCTURE = 2,
  MOSB_VERIFY_FULL = 3
} mosb_verify_level;

typedef struct mosb_graph mosb_graph;

/* The library release, e.g. "0.2.0" (not the file format version). Never fails. */
const char* mosb_version(void);
/* The message of the calling thread's last failure; "" when there was none. Valid until the
 * thread's next failing mosb call. Never fails. */
const char* mosb_last_error(void);

/* Opens and maps `path`; checks the header, the table and the counts (time independent of the
 * file size). *graph receives the handle. A packed file (`mosb pack`) is refused at once with
 * MOSB_ERROR_PACKED: its sections cannot be mapped in place (mosb_load decodes it). */
mosb_status mosb_open(const char* path, mosb_graph** graph);
/* mosb_open, then mosb_verify at `level`: a file that fails is closed again and not returned. */
mosb_status mosb_open_verified(const char* path, mosb_verify_level level, mosb_graph** graph);
/* Like mosb_open, but a packed file (`mosb pack`) is decoded into memory the handle owns, every
 * section's checksum checked, instead of being refused with MOSB_ERROR_PACKED; an unpacked file
 * is mapped as by mosb_open. */
mosb_status mosb_load(const char* path, mosb_graph** graph);
/* mosb_load with a memory cap: all that decoding a packed file takes must fit in `max_memory`
 * bytes (0: the memory available), checked against the sizes the file declares before anything is
 * allocated; past it, MOSB_ERROR_NO_MEMORY and nothing allocated. mosb_load's cap is the memory
 * available. */
mosb_status mosb_load_within(const char* path, uint64_t max_memory, mosb_graph** graph);
/* Opens the instance that the store in `directory` (its MANIFEST, spec/MANIFEST.md) resolves `name`
 * to: "BENCHMARK/VIEW", a view name, or a benchmark name, as mosb::Store::instance does. The file
 * is verified in full and must have the content digest the manifest lists. A packed entry is
 * unpacked into the store's cache (DIRECTORY/.cache) on first use, or into memory the handle owns
 * when the store cannot be written. *graph receives the handle; *view, unless `view` is NULL, the
 * resolved view's name ("" when the whole file serves), valid until mosb_close. */
mosb_status mosb_store_instance(const char* directory, const char* name, mosb_graph** graph,
                                const char** view);
/* Unmaps and frees; NULL is allowed. Every pointer obtained from the handle dies with it. */
void mosb_close(mosb_graph* graph);
/* Checks the file at `level`; MOSB_ERROR_DAMAGED names the first problem. */
mosb_status mosb_verify(const mosb_graph* graph, mosb_verify_level level);

mosb_status mosb_vertex_count(const mosb_graph* graph, uint64_t* count);
mosb_status mosb_arc_count(const mosb_graph* graph, uint64_t* count);
/* offsets: vertex_count + 1 values; targets: arc_count values. */
mosb_status mosb_forward_csr(const mosb_graph* graph, const uint64_t** offsets,
                             const uint32_t** targets);
/* offsets: vertex_count + 1 values; sources and arcs: arc_count values each. */
mosb_status mosb_reverse_csr(const mosb_graph* graph, const uint64_t** offsets,
                             const uint32_t** sources, const uint32_t** arcs);

mosb_status mosb_objective_count(const mosb_graph* graph, size_t* count);
/* NUL-terminated names; the unit is "" when the file gives none. */
mosb_status mosb_objective_name(const mosb_graph* graph, size_t objective, const char** name);
mosb_status mosb_objective_unit(const mosb_graph* graph, size_t objective, const char** unit);
mosb_status mosb_objective_type(const mosb_graph* graph, size_t objective, mosb_element_type* type);
/* The index of the objective named `name`; MOSB_ERROR_NOT_FOUND when there is none. */
mosb_status mosb_find_objective(const mosb_graph* graph, const char* name, size_t* objective);
/* Cost column `objective` in its stored type (*type), arc_count values, zero-copy: cast *values
 * to the pointer type *type names (MOSB_U8: const uint8_t*, ..., MOSB_F64: const double*). */
mosb_status mosb_cost(const mosb_graph* graph, size_t objective, mosb_element_type* type,
                      const void** values);
/* Copies cost column `objective` into out[0 .. count), widening; count must be arc_count.
 * The uint64_t form refuses float columns (MOSB_ERROR_INVALID_ARGUMENT). */
mosb_status mosb_cost_copy_u64(const mosb_graph* graph, size_t objective, uint64_t* out,
                               size_t count);
mosb_status mosb_cost_copy_f64(const mosb_graph* graph, size_t objective, double* out,
                               size_t count);

/* Views (metadata `view.<name>.*`), in sorted name order. */
mosb_status mosb_view_count(const mosb_graph* graph, size_t* count);
mosb_status mosb_view_name(const mosb_graph* graph, size_t view, const char** name);
/* The objective indices of view `name` (*count of them, in the view's order) and its query set
 * ("" when it names none). Any output pointer may be NULL when not wanted. */
mosb_status mosb_view(const mosb_graph* graph, const char* name, const size_t** objectives,
                      size_t* count, const char** query_set);

/* Query sets: *pairs holds *count (start, goal) pairs, start at pairs[2i], goal at pairs[2i+1]. */
mosb_status mosb_query_set_count(const mosb_graph* graph, size_t* count);
mosb_status mosb_query_set_name(const mosb_graph* graph, size_t set, const char** name);
mosb_status mosb_queries(const mosb_graph* graph, const char* name, const uint32_t** pairs,
                         size_t* count);

/* The value of metadata key `key` (NUL-terminated; *length excludes the NUL and may be NULL).
 * MOSB_ERROR_NOT_FOUND when the key is absent. */
mosb_status mosb_metadata(const mosb_graph* graph, const char* key, const char** value,
                          size_t* length);
/* The §8 content digest: 32 lower-case hex digits, NUL-terminated. */
mosb_status mosb_digest(const mosb_graph* graph, const char** digest);

#ifdef __cplusplus
}
#endif

/* NOLINTEND(modernize-*) */
#endif /* MOSB_H */
