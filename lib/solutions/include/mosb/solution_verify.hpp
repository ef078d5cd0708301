// Checks of a solution file against its instance (spec/SOLUTIONS.md §5): the binding, then the
// payload, then every front mutually non-dominated and duplicate-free, then every stored path.
#pragma once

#include <optional>
#include <string>

#include "mosb/graph_reader.hpp"
#include "mosb/solution_file.hpp"

namespace mosb {

// spec/SOLUTIONS.md §6: Moving AI's optimum L* (octile, diagonal sqrt 2) brackets the smallest
// games `length` c* (10 straight, 14 diagonal) of an exact front: c*/10 <= L* + tau and
// L* <= (sqrt 2 / 1.4) c*/10 + tau, tau = 1e-6 max(1, L*). nullopt when it holds, else the
// "[reference] ..." message showing both values.
std::optional<std::string> movingai_bracket_problem(double c_star, double l_star);

// The first problem, as one line naming the query (and both vectors, or the path step), or
// nullopt. `instance` must be opened with VerifyLevel::full (paths walk its CSR). Cost: the
// payload, plus O(k log k + k·w) per front of k vectors where w is the number of vectors not
// lexicographically after a vector (O(k log k) for d = 2, O(k^2) worst case for d > 2), plus the
// path lengths times the out-degrees along them. A query set carrying Moving AI optima (section
// kind 17, source `movingai-optimal`) also has each solved front's smallest reference objective
// checked against its optimum by spec/SOLUTIONS.md §6's bracket ("[reference]").
std::optional<std::string> verify_solutions(const SolutionReader& solutions,
                                            const GraphReader& instance);

}  // namespace mosb
