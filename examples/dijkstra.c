/* dijkstra INSTANCE [VIEW]: single-objective Dijkstra on the first objective of VIEW (default: the
 * file's first view) for each query of the view's query set, on mosb's C ABI. The CSR arrays are
 * read in place from the mapping; the costs are widened into one double array. Output per query,
 * in query order: `start goal cost` (cost `inf` when the goal is unreachable). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "mosb.h"

typedef struct {
  double key;
  uint32_t v;
} Entry;
static Entry* heap;
static size_t heap_size;

static void push(double key, uint32_t v) {
  size_t i = heap_size++, parent;
  for (; i > 0 && heap[parent = (i - 1) / 2].key > key; i = parent) heap[i] = heap[parent];
  heap[i].key = key, heap[i].v = v;
}

static Entry pop(void) {
  Entry top = heap[0], last = heap[--heap_size];
  size_t i = 0, child;
  while ((child = 2 * i + 1) < heap_size) {
    if (child + 1 < heap_size && heap[child + 1].key < heap[child].key) ++child;
    if (heap[child].key >= last.key) break;
    heap[i] = heap[child], i = child;
  }
  heap[i] = last;
  return top;
}

static int fail(const char* what) {
  fprintf(stderr, "dijkstra: %s: %s\n", what, mosb_last_error());
  return 1;
}

int main(int argc, char** argv) {
  mosb_graph* g;
  const char *view = argc > 2 ? argv[2] : NULL, *query_set;
  const size_t* objectives;
  const uint64_t* offsets;
  const uint32_t *targets, *queries;
  uint64_t n, m, a;
  size_t k, q;
  double *cost, *dist;
  if (argc < 2 || argc > 3) return fprintf(stderr, "usage: dijkstra INSTANCE [VIEW]\n"), 2;
  /* The walk indexes arrays by ids read from the file: a file whose structure is not checked
   * (targets < n, offsets monotone, query ids < n) could send it out of bounds. The check is one
   * pass over the file, milliseconds at FLA size (BENCHMARKS.md). */
  if (mosb_open_verified(argv[1], MOSB_VERIFY_STRUCTURE, &g) != MOSB_OK) return fail("open");
  if (!view && mosb_view_name(g, 0, &view) != MOSB_OK) return fail("first view");
  if (mosb_view(g, view, &objectives, &k, &query_set) != MOSB_OK) return fail("view");
  if (k == 0) return fprintf(stderr, "dijkstra: view %s names no objective\n", view), 1;
  if (mosb_queries(g, query_set, &queries, &q) != MOSB_OK) return fail("query set");
  mosb_vertex_count(g, &n), mosb_arc_count(g, &m), mosb_forward_csr(g, &offsets, &targets);
  cost = malloc((m + 1) * sizeof *cost), dist = malloc((n + 1) * sizeof *dist);
  heap = malloc((m + 1) * sizeof *heap);
  if (!cost || !dist || !heap) return fprintf(stderr, "dijkstra: out of memory\n"), 1;
  if (mosb_cost_copy_f64(g, objectives[0], cost, (size_t)m) != MOSB_OK) return fail("costs");
  for (; q > 0; --q, queries += 2) {
    Entry e;
    for (a = 0; a < n; ++a) dist[a] = INFINITY;
    dist[queries[0]] = 0, heap_size = 0, push(0, queries[0]);
    while (heap_size > 0 && (e = pop()).v != queries[1]) {
      if (e.key > dist[e.v]) continue; /* a stale entry */
      for (a = offsets[e.v]; a < offsets[e.v + 1]; ++a)
        if (e.key + cost[a] < dist[targets[a]])
          push(dist[targets[a]] = e.key + cost[a], targets[a]);
    }
    printf("%u %u %.17g\n", (unsigned)queries[0], (unsigned)queries[1], dist[queries[1]]);
  }
  free(cost), free(dist), free(heap), mosb_close(g);
  return 0;
}
