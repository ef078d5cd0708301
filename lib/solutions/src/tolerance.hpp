// The relative tolerance of float objectives (spec/EVALUATION.md §2.1), applied once for every
// comparison of solution files (evaluate_solutions, compare_fronts): values that agree within it
// are made equal, then the comparison is exact. Internal to lib/solutions.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "mosb/solution_file.hpp"

namespace mosb::solutions_internal {

// Per objective of two files of one binding: whether either stores it as floating point (the
// objectives the tolerance applies to).
std::vector<bool> float_objectives(const SolutionReader& a, const SolutionReader& b);

// Throws mosb::Error (ErrorCode::invalid_argument) unless 0 <= tolerance < 1.
void check_tolerance(double tolerance);

// `a` and `b` hold two fronts row-major, d values per vector (finite, >= 0). For each objective i
// with snap[i], the i-th values of both fronts are sorted together and grouped from the smallest:
// a group holds every value v with v <= first + first·tolerance, first its smallest value, and the
// next value above starts a new group. Every value is replaced by its group's first. So two
// values made equal agree within the tolerance (relative to the smaller), order is kept (a value
// is never moved past another), and tolerance 0 changes nothing. Two values within the tolerance
// can still fall into two groups where distinct values lie closer than the tolerance over a span
// wider than it: they then stay different (reported), never the other way round.
// O(N log N) for N values in all.
void snap_within_tolerance(std::span<double> a, std::span<double> b, std::size_t d,
                           const std::vector<bool>& snap, double tolerance);

}  // namespace mosb::solutions_internal
