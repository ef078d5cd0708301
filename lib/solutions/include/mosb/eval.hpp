// Evaluation of a solver's front against a reference Pareto front (spec/EVALUATION.md): the paper's
// ε-dominance coverage at given ε, the achieved ε, the worst reference vector, and solver vectors
// the reference strictly dominates. Integer costs are compared exactly (128-bit cross products);
// floating-point costs in double arithmetic.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mosb {

// A non-negative rational num/den; den == 0 stands for +infinity (num is then 1).
struct Ratio {
  std::uint64_t num = 0, den = 1;

  bool is_infinite() const { return den == 0; }
  double to_double() const;
  // Decimal with at most `digits` fractional digits, rounded up (so the printed value, given back
  // as an ε, still covers); "inf" for infinity. Exact when the expansion ends earlier.
  std::string to_decimal(int digits = 9) const;
  friend bool operator==(const Ratio& a, const Ratio& b);
  friend bool operator<(const Ratio& a, const Ratio& b);
};

// "0.05", "1", ".5", "0" → exact reduced ratio. Throws mosb::Error for anything else (a sign, an
// exponent, more than 18 significant digits on either side of the point, not counting leading zeros
// of the whole part and trailing zeros of the fraction, or a reduced numerator above 2^64 - 1).
Ratio parse_epsilon(std::string_view text);

// n vectors of `dimension` values, row-major: vector k is values[k*dimension, (k+1)*dimension).
template <class T>
struct FrontView {
  std::span<const T> values;
  std::size_t dimension = 0;

  std::size_t size() const { return dimension == 0 ? 0 : values.size() / dimension; }
  const T* operator[](std::size_t k) const { return values.data() + k * dimension; }
};

struct EvalOptions {
  // The paper's definition read literally: p ε-dominates q only if, besides p ≤ (1+ε)q for all i,
  // p_j < (1+ε)q_j for some j. Off by default (see spec/EVALUATION.md for why).
  bool strict_dominance = false;
};

struct EpsilonCoverage {
  Ratio epsilon;
  bool covered = false;
  // Reference vectors no solution vector ε-dominates. At ε = 0, `covered` means the same
  // multiset; uncovered then counts reference vectors without an equal solution vector.
  std::uint64_t uncovered = 0;
  // At ε = 0 only: solution vectors without an equal reference vector (duplicates, vectors the
  // reference dominates, vectors it lacks), the other way a multiset can differ; 0 at ε > 0.
  std::uint64_t extra = 0;
};

struct FrontEvaluation {
  std::size_t solution_size = 0, reference_size = 0;
  std::vector<EpsilonCoverage> coverage;  // one per requested ε, in the order given
  // The smallest uniform ε at which the solution covers the reference (componentwise reading);
  // infinite when none does (an empty solution, or q_i = 0 that no vector meets with p_i = 0).
  // For integer costs `achieved` is exact; for double costs its num/den is unset and only
  // `achieved_value` is meaningful: g − 1 for g the smallest double 1+ε must round to for the
  // coverage test (1+ε rounded, then (1+ε)·q_i) to cover, so covered at a double ε ⟺
  // fl(1+ε) ≥ 1 + achieved_value (spec/EVALUATION.md §2).
  Ratio achieved;
  double achieved_value = 0;
  // A reference vector that needs exactly the achieved ε (the worst one); nullopt when the
  // achieved ε is 0.
  std::optional<std::size_t> worst_reference;
  // Indices of solution vectors that some reference vector strictly dominates (a solver bug, when
  // the reference is exact), increasing. Assumes the reference is mutually non-dominated.
  std::vector<std::size_t> dominated_by_reference;
  bool same_multiset = false;
};

// The achieved ε as printed by `mosb eval` (spec/EVALUATION.md): exact (`achieved`, a terminating
// or rounded-up decimal) with `exact` arithmetic, else `achieved_value` rounded up at the 9th
// digit, so that the printed ε passed back as --eps still covers; "inf" when nothing covers.
std::string achieved_epsilon_text(const FrontEvaluation& front, bool exact);

// Both fronts must have the same dimension ≥ 1 (throws mosb::Error otherwise); values must be
// non-negative (double: finite and ≥ 0), which the caller checks. Values are compared as given
// (a tolerance is applied before, by evaluate_solutions and compare_fronts).
// Time: O((|S| + |R|) log(|S| + |R|)) per coverage test for d ≤ 3; for d ≥ 4 one query of a
// k-d tree per vector (tens of nodes on fronts near a plane, every node, O(|S|·|R|·d) per
// test, at worst); the achieved ε takes expected O(log |R|) coverage tests plus at most 256 + 64
// per test scans of S (for d ≥ 4 branch and bound searches of the tree), each coordinate's need
// found in O(1) expected and O(64) worst-case steps (spec/EVALUATION.md §3), whatever the values,
// integer or double.
FrontEvaluation evaluate_front(FrontView<std::uint64_t> solution,
                               FrontView<std::uint64_t> reference, std::span<const Ratio> epsilons,
                               const EvalOptions& options = {});
FrontEvaluation evaluate_front(FrontView<double> solution, FrontView<double> reference,
                               std::span<const Ratio> epsilons, const EvalOptions& options = {});

// The coverage test alone: indices (increasing) of reference vectors that no solution vector
// ε-dominates. ε = 0 here is plain weak dominance, p ≤ q.
std::vector<std::size_t> uncovered_reference(FrontView<std::uint64_t> solution,
                                             FrontView<std::uint64_t> reference, Ratio epsilon,
                                             const EvalOptions& options = {});
std::vector<std::size_t> uncovered_reference(FrontView<double> solution,
                                             FrontView<double> reference, Ratio epsilon,
                                             const EvalOptions& options = {});

}  // namespace mosb
