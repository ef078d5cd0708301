// mosb.h from C++11 (compiled with -std=c++11 -pedantic -Werror): the C ABI is the way into mosb
// for solver code bases that are not C++20.
#include <cstdio>
#include <cstring>

#include "mosb.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  mosb_graph* graph = nullptr;
  if (mosb_open(argv[1], &graph) != MOSB_OK) {
    std::fprintf(stderr, "%s\n", mosb_last_error());
    return 1;
  }
  uint64_t arcs = 0;
  const char* name = nullptr;
  const bool ok = mosb_arc_count(graph, &arcs) == MOSB_OK && arcs == 7 &&
                  mosb_objective_name(graph, 0, &name) == MOSB_OK &&
                  std::strcmp(name, "distance") == 0;
  mosb_close(graph);
  std::puts(ok ? "C++11 use of mosb.h works" : "C++11 use of mosb.h failed");
  return ok ? 0 : 1;
}
