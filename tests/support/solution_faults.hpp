// The invalid golden solution files: each is spec/golden/1.3/solutions/valid/small.sol.mosb with
// one deliberate fault, and the stage ("open" or "payload") whose check must name it.
#pragma once

#include <limits>

#include "file_patch.hpp"

namespace mosb::testing {

struct SolutionFault {
  const char* file;
  const char* stage;
  const char* expected;
  void (*apply)(Bytes&);
};

inline const SolutionFault kSolutionFaults[] = {
    {"minor-0.sol.mosb", "open", "solution files exist since 1.1",
     [](Bytes& b) {
       auto h = header_of(b);
       h.version_minor = 0;
       set_header(b, h);
       reseal_header(b);
     }},
    {"offsets-end.sol.mosb", "open", "rows, but the last front offset is",
     [](Bytes& b) {
       const auto s = find_entry(b, "front_offsets");
       poke<std::uint64_t>(b, s, 3, 2);
       reseal_section(b, s);
     }},
    {"cost-checksum.sol.mosb", "payload", "section 'time': [checksum] mismatch",
     [](Bytes& b) { poke<double>(b, find_entry(b, "time"), 0, 9.5); }},
    {"status-range.sol.mosb", "payload", "query 2: [status] value 9 is not a status",
     [](Bytes& b) {
       const auto s = find_entry(b, "solution_status");
       poke<std::uint8_t>(b, s, 2, 9);
       reseal_section(b, s);
     }},
    {"solved-empty.sol.mosb", "payload", "query 2: [status] solved with an empty front",
     [](Bytes& b) {
       const auto s = find_entry(b, "solution_status");
       poke<std::uint8_t>(b, s, 2, 0);
       reseal_section(b, s);
     }},
    {"timeout-statistics.sol.mosb", "payload", "query 2: [statistics] timeout carries statistics",
     [](Bytes& b) {
       const auto s = find_entry(b, "runtime_seconds");
       poke<double>(b, s, 2, 60.0);
       reseal_section(b, s);
     }},
    {"path-vertex.sol.mosb", "payload", "[path-vertex] vertex 7 is not below the vertex count 4",
     [](Bytes& b) {
       const auto s = find_entry(b, "path_vertices");
       poke<std::uint32_t>(b, s, 1, 7);
       reseal_section(b, s);
     }},
    {"negative-time.sol.mosb", "payload", "section 'time': [cost-value] front vector 1",
     [](Bytes& b) {
       const auto s = find_entry(b, "time");
       poke<double>(b, s, 1, -1.0);
       reseal_section(b, s);
     }},
    // 1.3: integer path sums stop at 2^53 (they are read as exact doubles).
    {"sum-above-2-53.sol.mosb", "payload",
     "section 'distance': [cost-value] front vector 2 is above 2^53",
     [](Bytes& b) {
       const auto s = find_entry(b, "distance");
       poke<std::uint64_t>(b, s, 2, (std::uint64_t{1} << 53) + 1);
       reseal_section(b, s);
     }},
    // 1.3: a failed query carries no front.
    {"failed-front.sol.mosb", "payload", "query 1: [status] failed with a front of 1 vectors",
     [](Bytes& b) {
       const auto s = find_entry(b, "solution_status");
       poke<std::uint8_t>(b, s, 1, 5);
       reseal_section(b, s);
     }},
    // A non-zero byte in an alignment gap (after the first payload that does not end on a
    // multiple of 64): every checksum still holds, but FORMAT.md §1 says such bytes are zero.
    {"padding.sol.mosb", "payload", "[padding] byte",
     [](Bytes& b) {
       for (std::size_t i = 0; i < header_of(b).section_count; ++i) {
         const auto e = entry_of(b, i);
         if ((e.offset + e.stored_length) % 64 != 0) {
           b[e.offset + e.stored_length] = std::byte{0x2A};
           return;
         }
       }
     }},
};

}  // namespace mosb::testing
