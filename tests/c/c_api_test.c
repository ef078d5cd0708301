/* The C ABI (mosb.h) from C99, over the golden files of spec/golden/1.0 (see
 * tests/support/golden_input.hpp for the values). Usage: mosb_c_api_test GOLDEN_DIR VERSION [STORE]
 * where STORE, when given, is a store holding valid/small.mosb packed (tests/c/CMakeLists.txt). */
#include <pthread.h>
#define _POSIX_C_SOURCE 200809L /* pthreads under -std=c99 */
#include <stdio.h>
#include <string.h>

#include "mosb.h"

static int failures = 0;

#define CHECK(cond)                                                            \
  do {                                                                         \
    if (!(cond)) {                                                             \
      fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                              \
    }                                                                          \
  } while (0)

static char path_buffer[4096];
static const char* golden(const char* dir, const char* name) {
  snprintf(path_buffer, sizeof path_buffer, "%s/%s", dir, name);
  return path_buffer;
}

static int contains(const char* text, const char* fragment) {
  return strstr(text, fragment) != NULL;
}

/* Cost value of CSR arc a in any stored type, read through the typed pointer. */
static double cost_at(mosb_element_type type, const void* values, size_t a) {
  switch (type) {
    case MOSB_U8:
      return ((const uint8_t*)values)[a];
    case MOSB_U16:
      return ((const uint16_t*)values)[a];
    case MOSB_U32:
      return ((const uint32_t*)values)[a];
    case MOSB_U64:
      return (double)((const uint64_t*)values)[a];
    case MOSB_F32:
      return ((const float*)values)[a];
    case MOSB_F64:
      return ((const double*)values)[a];
    default:
      return -1;
  }
}

static void check_graph(const mosb_graph* g) {
  /* Forward CSR of golden_input sorted stably by tail. */
  static const uint64_t offsets[] = {0, 2, 4, 6, 7};
  static const uint32_t targets[] = {1, 2, 2, 0, 3, 2, 0};
  static const double distance[] = {10, 20, 30, 300, 40, 5, 50};
  static const double time[] = {0.25, 3.75, 2, 8, 1.5, 0.5, 4};
  uint64_t n = 0, m = 0, v, i;
  const uint64_t *fo = NULL, *ro = NULL;
  const uint32_t *ft = NULL, *rs = NULL, *ra = NULL;
  size_t k = 0, j, count = 0, index = 99;
  const char *name = NULL, *unit = NULL, *query_set = NULL, *value = NULL, *digest = NULL;
  const size_t* objectives = NULL;
  const uint32_t* pairs = NULL;
  mosb_element_type type;
  const void* column = NULL;
  uint64_t widened[7];
  double real[7];

  CHECK(mosb_vertex_count(g, &n) == MOSB_OK && n == 4);
  CHECK(mosb_arc_count(g, &m) == MOSB_OK && m == 7);
  CHECK(mosb_forward_csr(g, &fo, &ft) == MOSB_OK);
  for (v = 0; v <= n; ++v) CHECK(fo[v] == offsets[v]);
  for (i = 0; i < m; ++i) CHECK(ft[i] == targets[i]);
  CHECK(mosb_reverse_csr(g, &ro, &rs, &ra) == MOSB_OK);
  CHECK(ro[0] == 0 && ro[n] == m);
  for (v = 0; v < n; ++v)
    for (i = ro[v]; i < ro[v + 1]; ++i) {
      CHECK(ft[ra[i]] == v);
      CHECK(fo[rs[i]] <= ra[i] && ra[i] < fo[rs[i] + 1]);
    }

  CHECK(mosb_objective_count(g, &k) == MOSB_OK && k == 5);
  CHECK(mosb_objective_name(g, 1, &name) == MOSB_OK && strcmp(name, "time") == 0);
  CHECK(mosb_objective_unit(g, 0, &unit) == MOSB_OK && strcmp(unit, "m") == 0);
  CHECK(mosb_objective_unit(g, 2, &unit) == MOSB_OK && strcmp(unit, "") == 0);
  CHECK(mosb_find_objective(g, "big", &index) == MOSB_OK && index == 4);
  CHECK(mosb_find_objective(g, "nope", &index) == MOSB_ERROR_NOT_FOUND && index == 4);
  CHECK(contains(mosb_last_error(), "no objective named 'nope'"));
  CHECK(mosb_objective_type(g, 3, &type) == MOSB_OK && type == MOSB_U32);
  CHECK(mosb_objective_type(g, 4, &type) == MOSB_OK && type == MOSB_U64);
  CHECK(mosb_objective_name(g, 5, &name) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(contains(mosb_last_error(), "objective index 5 out of range"));

  CHECK(mosb_cost(g, 0, &type, &column) == MOSB_OK);
  CHECK(type != MOSB_U64); /* the writer chose a narrower type: the typed pointer must follow it */
  for (i = 0; i < m; ++i) CHECK(cost_at(type, column, i) == distance[i]);
  CHECK(mosb_cost(g, 1, &type, &column) == MOSB_OK);
  for (i = 0; i < m; ++i) CHECK(cost_at(type, column, i) == time[i]);
  CHECK(mosb_cost_copy_u64(g, 0, widened, 7) == MOSB_OK);
  for (i = 0; i < m; ++i) CHECK((double)widened[i] == distance[i]);
  CHECK(mosb_cost_copy_u64(g, 4, widened, 7) == MOSB_OK && widened[3] == (uint64_t)1 << 33);
  CHECK(mosb_cost_copy_f64(g, 1, real, 7) == MOSB_OK);
  for (i = 0; i < m; ++i) CHECK(real[i] == time[i]);
  CHECK(mosb_cost_copy_u64(g, 1, widened, 7) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(contains(mosb_last_error(), "do not convert to integers"));
  CHECK(mosb_cost_copy_f64(g, 1, real, 6) == MOSB_ERROR_INVALID_ARGUMENT);

  CHECK(mosb_view_count(g, &count) == MOSB_OK && count == 2);
  CHECK(mosb_view_name(g, 1, &name) == MOSB_OK && strcmp(name, "Small_5") == 0);
  CHECK(mosb_view_name(g, 2, &name) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(mosb_view(g, "Small_2", &objectives, &count, &query_set) == MOSB_OK);
  CHECK(count == 2 && objectives[0] == 0 && objectives[1] == 1);
  CHECK(strcmp(query_set, "default") == 0);
  CHECK(mosb_view(g, "Small_5", &objectives, &count, NULL) == MOSB_OK);
  CHECK(count == 5 && objectives[4] == 4);
  CHECK(mosb_view(g, "nope", &objectives, &count, &query_set) == MOSB_ERROR_NOT_FOUND);
  CHECK(contains(mosb_last_error(), "no view 'nope' (views: Small_2, Small_5)"));

  CHECK(mosb_query_set_count(g, &count) == MOSB_OK && count == 2);
  CHECK(mosb_query_set_name(g, 1, &name) == MOSB_OK && strcmp(name, "reverse") == 0);
  CHECK(mosb_queries(g, "default", &pairs, &count) == MOSB_OK && count == 3);
  CHECK(pairs[0] == 0 && pairs[1] == 3 && pairs[2] == 1 && pairs[3] == 0 && pairs[5] == 3);
  CHECK(mosb_queries(g, "nope", &pairs, &count) == MOSB_ERROR_NOT_FOUND);

  CHECK(mosb_metadata(g, "benchmark", &value, &count) == MOSB_OK);
  CHECK(strcmp(value, "golden-small") == 0 && count == 12);
  CHECK(mosb_metadata(g, "note", &value, NULL) == MOSB_OK &&
        contains(value, "backslash,\nnewline"));
  CHECK(mosb_metadata(g, "absent", &value, &count) == MOSB_ERROR_NOT_FOUND);

  CHECK(mosb_digest(g, &digest) == MOSB_OK && strlen(digest) == 32);
  for (j = 0; j < 32; ++j) CHECK(strchr("0123456789abcdef", digest[j]) != NULL);
  CHECK(mosb_verify(g, MOSB_VERIFY_FULL) == MOSB_OK);
}

/* Many threads on one fresh handle: the lazily described parts (units, views, metadata) are
 * built once; each thread's mosb_last_error is its own. */
static const mosb_graph* shared_graph;
static void* worker(void* arg) {
  const char* unit = NULL;
  size_t count = 0, index = 0;
  int* ok = (int*)arg;
  const char* value = NULL;
  *ok = mosb_objective_unit(shared_graph, 1, &unit) == MOSB_OK && strcmp(unit, "s") == 0;
  *ok &= mosb_view_count(shared_graph, &count) == MOSB_OK && count == 2;
  *ok &=
      mosb_metadata(shared_graph, "family", &value, NULL) == MOSB_OK && strcmp(value, "road") == 0;
  *ok &= mosb_find_objective(shared_graph, "thread-only", &index) == MOSB_ERROR_NOT_FOUND;
  *ok &= contains(mosb_last_error(), "thread-only");
  return NULL;
}

static void check_threads(const char* dir) {
  mosb_graph* g = NULL;
  pthread_t threads[8];
  int ok[8];
  size_t t, index;
  CHECK(mosb_find_objective(NULL, "x", &index) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(contains(mosb_last_error(), "the graph handle is NULL"));
  CHECK(mosb_open(golden(dir, "valid/small.mosb"), &g) == MOSB_OK);
  shared_graph = g;
  for (t = 0; t < 8; ++t) CHECK(pthread_create(&threads[t], NULL, worker, &ok[t]) == 0);
  for (t = 0; t < 8; ++t) {
    CHECK(pthread_join(threads[t], NULL) == 0);
    CHECK(ok[t]);
  }
  /* The workers' failures did not replace this thread's message. */
  CHECK(contains(mosb_last_error(), "the graph handle is NULL"));
  mosb_close(g);
}

static void check_failures(const char* dir) {
  mosb_graph* g = NULL;
  CHECK(mosb_open(golden(dir, "absent.mosb"), &g) == MOSB_ERROR_IO && g == NULL);
  CHECK(contains(mosb_last_error(), "absent.mosb: cannot open"));
  CHECK(mosb_open(golden(dir, "invalid/bad-magic.mosb"), &g) == MOSB_ERROR_NOT_MOSB && g == NULL);
  CHECK(contains(mosb_last_error(), "not a mosb file (wrong magic)"));
  CHECK(mosb_open(golden(dir, "invalid/newer-major.mosb"), &g) == MOSB_ERROR_VERSION);
  CHECK(mosb_open(golden(dir, "invalid/unknown-feature.mosb"), &g) == MOSB_ERROR_VERSION);
  CHECK(mosb_open(golden(dir, "invalid/header-checksum.mosb"), &g) == MOSB_ERROR_DAMAGED);
  CHECK(contains(mosb_last_error(), "header-checksum.mosb: header checksum mismatch"));
  CHECK(g == NULL);

  /* Damage behind the header: open succeeds, verify finds it; open_verified refuses it. */
  CHECK(mosb_open(golden(dir, "invalid/section-checksum.mosb"), &g) == MOSB_OK && g != NULL);
  CHECK(mosb_verify(g, MOSB_VERIFY_HEADER) == MOSB_OK);
  CHECK(mosb_verify(g, MOSB_VERIFY_CHECKSUMS) == MOSB_ERROR_DAMAGED);
  CHECK(contains(mosb_last_error(), "section 'time': [checksum] mismatch"));
  CHECK(mosb_verify(g, (mosb_verify_level)42) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(contains(mosb_last_error(), "mosb_verify: unknown verify level 42"));
  /* A call error is reported as one, before anything is read from the file. */
  CHECK(mosb_view_count(g, NULL) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(contains(mosb_last_error(), "mosb_view_count: the output count is NULL"));
  mosb_close(g);
  g = NULL;
  CHECK(mosb_open_verified(golden(dir, "invalid/section-checksum.mosb"), MOSB_VERIFY_HEADER, &g) ==
        MOSB_OK);
  mosb_close(g);
  g = NULL;
  CHECK(mosb_open_verified(golden(dir, "invalid/target-range.mosb"), MOSB_VERIFY_FULL, &g) ==
        MOSB_ERROR_DAMAGED);
  CHECK(g == NULL && contains(mosb_last_error(), "[target-range]"));
  CHECK(mosb_open(NULL, &g) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(strcmp(mosb_last_error(), "mosb_open: the path is NULL") == 0);
  mosb_close(NULL);
}

/* A call error: INVALID_ARGUMENT, and the message starts with the function's name. */
static int starts_with(const char* text, const char* prefix) {
  return strncmp(text, prefix, strlen(prefix)) == 0;
}
#define CALL_ERROR(call, function)                                                                \
  CHECK((call) == MOSB_ERROR_INVALID_ARGUMENT && starts_with(mosb_last_error(), function ": ") && \
        strchr(mosb_last_error(), '\n') == NULL)

/* Misuse: NULL for every pointer argument, unknown verify levels, indices and counts far out of
 * range. Each is a documented status, outputs untouched, and a message naming the function (call
 * errors) or the file (ranges). */
static void check_misuse(const char* dir) {
  mosb_graph* g = NULL;
  mosb_graph* const untouched = (mosb_graph*)&failures;
  mosb_graph* out = untouched;
  const char* path = golden(dir, "valid/small.mosb");
  uint64_t n = 12345, buffer64[8];
  double buffer[8];
  const uint64_t* offsets = NULL;
  const uint32_t *targets = NULL, *arcs = NULL, *pairs = NULL;
  const size_t* objectives = NULL;
  size_t count = 777, index = 777;
  const char *text = NULL, *view = NULL;
  mosb_element_type type = MOSB_U8;
  const void* values = NULL;

  CALL_ERROR(mosb_open(path, NULL), "mosb_open");
  CALL_ERROR(mosb_open_verified(NULL, MOSB_VERIFY_FULL, &out), "mosb_open_verified");
  CALL_ERROR(mosb_open_verified(path, MOSB_VERIFY_FULL, NULL), "mosb_open_verified");
  CALL_ERROR(mosb_open_verified(path, (mosb_verify_level)7, &out), "mosb_open_verified");
  CHECK(contains(mosb_last_error(), "unknown verify level 7"));
  CALL_ERROR(mosb_open_verified(path, (mosb_verify_level)-1, &out), "mosb_open_verified");
  CALL_ERROR(mosb_load(NULL, &out), "mosb_load");
  CALL_ERROR(mosb_load(path, NULL), "mosb_load");
  CALL_ERROR(mosb_load_within(path, 1u << 20, NULL), "mosb_load_within");
  CALL_ERROR(mosb_store_instance(NULL, "x", &out, &view), "mosb_store_instance");
  CALL_ERROR(mosb_store_instance(dir, "x", NULL, &view), "mosb_store_instance");
  CHECK(out == untouched && view == NULL);

  CHECK(mosb_open(path, &g) == MOSB_OK);
  CALL_ERROR(mosb_verify(NULL, MOSB_VERIFY_HEADER), "mosb_verify");
  CALL_ERROR(mosb_verify(g, (mosb_verify_level)-1), "mosb_verify");
  CALL_ERROR(mosb_vertex_count(NULL, &n), "mosb_vertex_count");
  CALL_ERROR(mosb_vertex_count(g, NULL), "mosb_vertex_count");
  CALL_ERROR(mosb_arc_count(NULL, &n), "mosb_arc_count");
  CALL_ERROR(mosb_arc_count(g, NULL), "mosb_arc_count");
  CHECK(n == 12345);
  CALL_ERROR(mosb_forward_csr(NULL, &offsets, &targets), "mosb_forward_csr");
  CALL_ERROR(mosb_forward_csr(g, NULL, &targets), "mosb_forward_csr");
  CALL_ERROR(mosb_forward_csr(g, &offsets, NULL), "mosb_forward_csr");
  CALL_ERROR(mosb_reverse_csr(NULL, &offsets, &targets, &arcs), "mosb_reverse_csr");
  CALL_ERROR(mosb_reverse_csr(g, NULL, &targets, &arcs), "mosb_reverse_csr");
  CALL_ERROR(mosb_reverse_csr(g, &offsets, NULL, &arcs), "mosb_reverse_csr");
  CALL_ERROR(mosb_reverse_csr(g, &offsets, &targets, NULL), "mosb_reverse_csr");
  CHECK(offsets == NULL && targets == NULL && arcs == NULL);
  CALL_ERROR(mosb_objective_count(NULL, &count), "mosb_objective_count");
  CALL_ERROR(mosb_objective_count(g, NULL), "mosb_objective_count");
  CALL_ERROR(mosb_objective_name(NULL, 0, &text), "mosb_objective_name");
  CALL_ERROR(mosb_objective_name(g, 0, NULL), "mosb_objective_name");
  CALL_ERROR(mosb_objective_unit(NULL, 0, &text), "mosb_objective_unit");
  CALL_ERROR(mosb_objective_unit(g, 0, NULL), "mosb_objective_unit");
  CALL_ERROR(mosb_objective_type(NULL, 0, &type), "mosb_objective_type");
  CALL_ERROR(mosb_objective_type(g, 0, NULL), "mosb_objective_type");
  CALL_ERROR(mosb_find_objective(g, NULL, &index), "mosb_find_objective");
  CALL_ERROR(mosb_find_objective(g, "time", NULL), "mosb_find_objective");
  CALL_ERROR(mosb_cost(NULL, 0, &type, &values), "mosb_cost");
  CALL_ERROR(mosb_cost(g, 0, NULL, &values), "mosb_cost");
  CALL_ERROR(mosb_cost(g, 0, &type, NULL), "mosb_cost");
  CALL_ERROR(mosb_cost_copy_u64(NULL, 0, buffer64, 7), "mosb_cost_copy_u64");
  CALL_ERROR(mosb_cost_copy_u64(g, 0, NULL, 7), "mosb_cost_copy_u64");
  CALL_ERROR(mosb_cost_copy_f64(NULL, 0, buffer, 7), "mosb_cost_copy_f64");
  CALL_ERROR(mosb_cost_copy_f64(g, 0, NULL, 7), "mosb_cost_copy_f64");
  CALL_ERROR(mosb_view_count(NULL, &count), "mosb_view_count");
  CALL_ERROR(mosb_view_name(NULL, 0, &text), "mosb_view_name");
  CALL_ERROR(mosb_view_name(g, 0, NULL), "mosb_view_name");
  CALL_ERROR(mosb_view(NULL, "Small_2", &objectives, &count, &text), "mosb_view");
  CALL_ERROR(mosb_view(g, NULL, &objectives, &count, &text), "mosb_view");
  CALL_ERROR(mosb_query_set_count(NULL, &count), "mosb_query_set_count");
  CALL_ERROR(mosb_query_set_count(g, NULL), "mosb_query_set_count");
  CALL_ERROR(mosb_query_set_name(NULL, 0, &text), "mosb_query_set_name");
  CALL_ERROR(mosb_query_set_name(g, 0, NULL), "mosb_query_set_name");
  CALL_ERROR(mosb_queries(NULL, "default", &pairs, &count), "mosb_queries");
  CALL_ERROR(mosb_queries(g, NULL, &pairs, &count), "mosb_queries");
  CALL_ERROR(mosb_queries(g, "default", NULL, &count), "mosb_queries");
  CALL_ERROR(mosb_queries(g, "default", &pairs, NULL), "mosb_queries");
  CALL_ERROR(mosb_metadata(NULL, "benchmark", &text, NULL), "mosb_metadata");
  CALL_ERROR(mosb_metadata(g, NULL, &text, NULL), "mosb_metadata");
  CALL_ERROR(mosb_metadata(g, "benchmark", NULL, NULL), "mosb_metadata");
  CALL_ERROR(mosb_digest(NULL, &text), "mosb_digest");
  CALL_ERROR(mosb_digest(g, NULL), "mosb_digest");
  CHECK(count == 777 && index == 777 && text == NULL && objectives == NULL && pairs == NULL &&
        values == NULL && type == MOSB_U8);

  /* Indices and counts far out of range (what a negative int becomes as a size_t): refused with
   * the file's name, nothing written. */
  CHECK(mosb_objective_name(g, (size_t)-1, &text) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(contains(mosb_last_error(), "small.mosb") && text == NULL);
  CHECK(mosb_objective_unit(g, (size_t)-1, &text) == MOSB_ERROR_INVALID_ARGUMENT && text == NULL);
  CHECK(mosb_objective_type(g, (size_t)-1, &type) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(mosb_cost(g, (size_t)-1, &type, &values) == MOSB_ERROR_INVALID_ARGUMENT && !values);
  CHECK(mosb_view_name(g, (size_t)-1, &text) == MOSB_ERROR_INVALID_ARGUMENT && text == NULL);
  CHECK(contains(mosb_last_error(), "small.mosb: view index"));
  CHECK(mosb_query_set_name(g, (size_t)-1, &text) == MOSB_ERROR_INVALID_ARGUMENT && !text);
  CHECK(contains(mosb_last_error(), "small.mosb: query set index"));
  /* A count larger than the buffer could ever be: refused before anything is written. */
  buffer[0] = -1;
  CHECK(mosb_cost_copy_f64(g, 0, buffer, (size_t)-1) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(contains(mosb_last_error(), "small.mosb") && buffer[0] == -1);
  CHECK(mosb_cost_copy_u64(g, 0, buffer64, 0) == MOSB_ERROR_INVALID_ARGUMENT);
  CHECK(mosb_find_objective(g, "", &index) == MOSB_ERROR_NOT_FOUND && index == 777);
  CHECK(mosb_view(g, "", &objectives, &count, &text) == MOSB_ERROR_NOT_FOUND);
  CHECK(mosb_queries(g, "", &pairs, &count) == MOSB_ERROR_NOT_FOUND && count == 777);
  CHECK(mosb_metadata(g, "", &text, &count) == MOSB_ERROR_NOT_FOUND && text == NULL);
  /* Every output of mosb_view may be NULL. */
  CHECK(mosb_view(g, "Small_2", NULL, NULL, NULL) == MOSB_OK);
  CHECK(mosb_view(g, "Small_2", NULL, &count, NULL) == MOSB_OK && count == 2);
  mosb_close(g);
}

/* Overwrites one byte of a file that no handle maps (a damaged download or copy). */
static void flip_byte(const char* path, long offset) {
  FILE* f = fopen(path, "r+b");
  int c;
  CHECK(f != NULL);
  if (!f) return;
  CHECK(fseek(f, offset, SEEK_SET) == 0 && (c = fgetc(f)) != EOF);
  CHECK(fseek(f, offset, SEEK_SET) == 0 && fputc((c ^ 0x5a) & 0xff, f) != EOF);
  fclose(f);
}

/* A packed store entry resolved by view name: the same graph as the golden file. */
static void check_store(const char* store) {
  mosb_graph* g = NULL;
  const char* view = NULL;
  if (mosb_store_instance(store, "Small_2", &g, &view) != MOSB_OK) {
    fprintf(stderr, "mosb_store_instance: %s\n", mosb_last_error());
    ++failures;
    return;
  }
  CHECK(view != NULL && strcmp(view, "Small_2") == 0);
  check_graph(g);
  mosb_close(g);
  view = NULL;
  CHECK(mosb_store_instance(store, "golden-small/Small_5", &g, NULL) == MOSB_OK);
  mosb_close(g);
  g = NULL;
  CHECK(mosb_store_instance(store, "no-such-benchmark", &g, &view) == MOSB_ERROR_NOT_FOUND);
  CHECK(g == NULL && view == NULL);
  CHECK(contains(mosb_last_error(), "no-such-benchmark"));
  CHECK(mosb_store_instance(store, NULL, &g, &view) == MOSB_ERROR_INVALID_ARGUMENT);

  /* The packed file itself: refused by the zero-copy opens at once, decoded by mosb_load. */
  g = NULL;
  CHECK(mosb_open(golden(store, "small.mosb"), &g) == MOSB_ERROR_PACKED);
  CHECK(g == NULL && contains(mosb_last_error(), "small.mosb") &&
        contains(mosb_last_error(), "mosb_load"));
  CHECK(mosb_open_verified(golden(store, "small.mosb"), MOSB_VERIFY_CHECKSUMS, &g) ==
        MOSB_ERROR_PACKED);
  CHECK(g == NULL);
  CHECK(mosb_load(golden(store, "small.mosb"), &g) == MOSB_OK);
  check_graph(g);
  mosb_close(g);
  /* Within a cap: the declared sizes are checked against it before anything is allocated. */
  g = NULL;
  CHECK(mosb_load_within(golden(store, "small.mosb"), 64, &g) == MOSB_ERROR_NO_MEMORY);
  CHECK(g == NULL && contains(mosb_last_error(), "small.mosb") &&
        contains(mosb_last_error(), "cap of 64 bytes"));
  CHECK(mosb_load_within(golden(store, "small.mosb"), 1u << 20, &g) == MOSB_OK);
  check_graph(g);
  mosb_close(g);
  CHECK(mosb_load_within(NULL, 0, &g) == MOSB_ERROR_INVALID_ARGUMENT);
  /* A cap of 0: the memory available, as mosb_load. */
  CHECK(mosb_load_within(golden(store, "small.mosb"), 0, &g) == MOSB_OK);
  check_graph(g);
  mosb_close(g);
  /* "Verified in full": a damaged unpacked copy in the cache is made again from the packed entry;
   * a damaged packed entry is refused with DAMAGED, naming it, and no handle. */
  flip_byte(golden(store, ".cache/small.mosb"), 1000);
  g = NULL;
  CHECK(mosb_store_instance(store, "Small_2", &g, NULL) == MOSB_OK);
  CHECK(g != NULL && mosb_verify(g, MOSB_VERIFY_FULL) == MOSB_OK);
  mosb_close(g);
  flip_byte(golden(store, "small.mosb"), 1000);
  CHECK(remove(golden(store, ".cache/small.mosb")) == 0);
  g = NULL;
  CHECK(mosb_store_instance(store, "Small_2", &g, &view) == MOSB_ERROR_DAMAGED && g == NULL);
  CHECK(contains(mosb_last_error(), "small.mosb") && strchr(mosb_last_error(), '\n') == NULL);
}

int main(int argc, char** argv) {
  mosb_graph* g = NULL;
  if (argc != 3 && argc != 4) {
    fprintf(stderr, "usage: %s GOLDEN_DIR VERSION [STORE]\n", argv[0]);
    return 2;
  }
  CHECK(strcmp(mosb_version(), argv[2]) == 0);
  CHECK(strcmp(mosb_last_error(), "") == 0);
  if (mosb_open_verified(golden(argv[1], "valid/small.mosb"), MOSB_VERIFY_FULL, &g) != MOSB_OK) {
    fprintf(stderr, "cannot open the golden file: %s\n", mosb_last_error());
    return 1;
  }
  check_graph(g);
  mosb_close(g);
  check_threads(argv[1]);
  check_failures(argv[1]);
  check_misuse(argv[1]);
  if (argc == 4) check_store(argv[3]);
  if (failures)
    fprintf(stderr, "%d checks failed\n", failures);
  else
    printf("all C ABI checks passed\n");
  return failures ? 1 : 0;
}
