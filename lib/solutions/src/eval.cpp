#include "mosb/eval.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "front_index.hpp"
#include "mosb/error.hpp"
#include "mosb/random.hpp"
#include "nondominance.hpp"

namespace mosb {

namespace {

// GCC/Clang; -Wpedantic needs the marker, which an alias declaration cannot carry.
__extension__ typedef unsigned __int128 u128;  // NOLINT(modernize-use-using)

Ratio reduced(std::uint64_t num, std::uint64_t den) {
  const std::uint64_t g = std::gcd(num, den);
  return g == 0 ? Ratio{0, 1} : Ratio{num / g, den / g};
}

constexpr Ratio kInfinity{1, 0};

// Per cost type: ε's representation and the one comparison everything else is built on,
// sign(p - (1+ε)·q).
template <class T>
struct Arith;

// The smallest non-negative double x with ok(x), for a predicate that is false then true over
// the non-negative doubles in increasing order and true at +infinity. Found from `guess` by
// galloping over the bit patterns (ordered as the values they encode), then bisecting: O(log k)
// calls for an answer k doubles away, at most about 130. Stepping one double at a time is what
// hung `eval`: below 1, an ulp of ε is far smaller than an ulp of 1 + ε.
template <class Ok>
double smallest_double_where(double guess, Ok ok) {
  constexpr auto kTop = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::infinity());
  const auto holds = [&](std::uint64_t b) { return ok(std::bit_cast<double>(b)); };
  const std::uint64_t start =
      guess >= 0 ? std::min(std::bit_cast<std::uint64_t>(guess), kTop) : std::uint64_t{0};
  std::uint64_t lo = 0, hi = 0;  // !holds(lo), holds(hi)
  if (holds(start)) {
    hi = start;
    for (std::uint64_t step = 1;; step *= 2) {
      if (hi == 0) return 0.0;
      const std::uint64_t probe = hi > step ? hi - step : 0;
      if (!holds(probe)) {
        lo = probe;
        break;
      }
      hi = probe;
    }
  } else {
    lo = start;
    for (std::uint64_t step = 1;; step *= 2) {
      if (lo == kTop) return std::numeric_limits<double>::infinity();  // ok broke its contract
      const std::uint64_t probe = kTop - lo > step ? lo + step : kTop;
      if (holds(probe)) {
        hi = probe;
        break;
      }
      lo = probe;
    }
  }
  while (hi - lo > 1) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    (holds(mid) ? hi : lo) = mid;
  }
  return std::bit_cast<double>(hi);
}

// Per cost type: ε's representation, the one comparison everything else is built on,
// sign(p - (1+ε)·q), and what a coordinate needs: `need` gives a key, ordered as the ε it stands
// for, and `from_need` that ε (keys are compared many times, turned into an ε once per vector).
template <class T>
struct Arith;

template <>
struct Arith<std::uint64_t> {
  using Eps = Ratio;
  using Need = Ratio;
  static Eps make(Ratio r) { return r; }
  static Eps zero() { return {0, 1}; }
  static int cmp(std::uint64_t p, std::uint64_t q, const Ratio& e) {
    if (e.is_infinite()) return q > 0 ? -1 : (p > 0 ? 1 : 0);
    if (p <= q) {
      if (p < q) return -1;
      return e.num == 0 || q == 0 ? 0 : -1;
    }
    if (q == 0) return 1;
    // p > q: compare den·(p-q) with num·q; each product is below 2^128.
    const u128 lhs = static_cast<u128>(e.den) * (p - q);
    const u128 rhs = static_cast<u128>(e.num) * q;
    return lhs < rhs ? -1 : (lhs == rhs ? 0 : 1);
  }
  // The smallest ε with p ≤ (1+ε)·q.
  static Need need(std::uint64_t p, std::uint64_t q) {
    if (p <= q) return zero();
    if (q == 0) return kInfinity;
    return {p - q, q};  // reduced once at the end: comparisons cross-multiply
  }
  static Need no_need() { return zero(); }
  static Need unreachable() { return kInfinity; }
  static Eps from_need(const Need& n) { return n; }
  static bool less(const Ratio& a, const Ratio& b) { return a < b; }
  static double value(const Eps& e) { return e.to_double(); }
  // The largest p with p ≤ (1+ε)·q, i.e. with cmp(p, q, e) <= 0: q + ⌊num·q/den⌋, at most 2^64 - 1.
  static std::uint64_t bound(std::uint64_t q, const Ratio& e) {
    constexpr auto kTop = std::numeric_limits<std::uint64_t>::max();
    if (e.is_infinite()) return q > 0 ? kTop : 0;
    const u128 b = q + static_cast<u128>(e.num) * q / e.den;
    return b > kTop ? kTop : static_cast<std::uint64_t>(b);
  }
};

// ε is a double and (1+ε)·q is rounded once after 1+ε is: the comparison depends on ε only
// through the double g = fl(1+ε). So a coordinate's need is the smallest double g ≥ 1 with
// fl(g·q) ≥ p, and the vector's ε is g − 1 (exact up to g = 2^53; beyond, the first double from
// there whose 1+ε reaches g): S covers R at ε exactly when fl(1+ε) ≥ 1 + the achieved ε. It is
// p/q − 1 as mosb 0.2.0 computed it wherever fl(p/q) is the smallest such g, i.e. unless fl(p/q)
// rounded up and the product with the double below still rounds up to p.
template <>
struct Arith<double> {
  using Eps = double;
  using Need = double;  // g
  static Eps make(Ratio r) { return r.to_double(); }
  static Eps zero() { return 0.0; }
  static int cmp(double p, double q, double e) {
    if (std::isinf(e)) return q > 0 ? -1 : (p > 0 ? 1 : 0);
    const double t = (1.0 + e) * q;
    return p < t ? -1 : (p == t ? 0 : 1);
  }
  static Need need(double p, double q) {
    if (p <= q) return 1.0;
    if (q == 0) return std::numeric_limits<double>::infinity();
    return smallest_double_where(p / q, [&](double g) { return g * q >= p; });
  }
  static Need no_need() { return 1.0; }
  static Need unreachable() { return std::numeric_limits<double>::infinity(); }
  static Eps from_need(Need g) {
    if (g <= 1.0) return 0.0;
    if (std::isinf(g)) return g;
    const double e = g - 1.0;
    if (1.0 + e >= g) return e;
    return smallest_double_where(e, [&](double x) { return x >= e && 1.0 + x >= g; });
  }
  static bool less(double a, double b) { return a < b; }
  static double value(Eps e) { return e; }
  // The largest p with cmp(p, q, e) <= 0: (1+ε)·q rounded as cmp rounds it.
  static double bound(double q, double e) {
    if (std::isinf(e)) return q > 0 ? e : 0.0;
    return (1.0 + e) * q;
  }
};

template <class T>
bool lex_less(const T* a, const T* b, std::size_t d) {
  return std::lexicographical_compare(a, a + d, b, b + d);
}

template <class T>
std::vector<std::size_t> lex_order(FrontView<T> front) {
  std::vector<std::size_t> order(front.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return lex_less(front[a], front[b], front.dimension);
  });
  return order;
}

// "Is some inserted point ≤ (1+ε)·t in coordinates 1..d-1?" for d ≤ 3; coordinate 0 is the
// caller's sweep. d = 2: the running minimum of coordinate 1. d = 3: a Fenwick tree over the rank
// of coordinate 1 holding prefix minima of coordinate 2.
template <class T>
class DominanceIndex {
  using A = Arith<T>;
  using Eps = typename A::Eps;

 public:
  explicit DominanceIndex(FrontView<T> universe) : d_(universe.dimension) {
    if (d_ == 3) {
      second_.reserve(universe.size());
      for (std::size_t k = 0; k < universe.size(); ++k) second_.push_back(universe[k][1]);
      std::sort(second_.begin(), second_.end());
      second_.erase(std::unique(second_.begin(), second_.end()), second_.end());
      tree_.assign(second_.size(), kMax);
    }
  }

  void reset() {
    any_ = false;
    min_second_ = kMax;
    std::fill(tree_.begin(), tree_.end(), kMax);
  }

  void insert(const T* p) {
    any_ = true;
    if (d_ == 2) {
      min_second_ = std::min(min_second_, p[1]);
    } else if (d_ == 3) {
      auto i = static_cast<std::size_t>(std::lower_bound(second_.begin(), second_.end(), p[1]) -
                                        second_.begin());
      for (++i; i <= tree_.size(); i += i & (~i + 1)) tree_[i - 1] = std::min(tree_[i - 1], p[2]);
    }
  }

  bool covers(const T* t, const Eps& e) const {
    if (!any_) return false;
    if (d_ == 1) return true;
    if (d_ == 2) return A::cmp(min_second_, t[1], e) <= 0;
    auto k = static_cast<std::size_t>(
        std::partition_point(second_.begin(), second_.end(),
                             [&](T v) { return A::cmp(v, t[1], e) <= 0; }) -
        second_.begin());
    T best = kMax;
    for (; k > 0; k -= k & (~k + 1)) best = std::min(best, tree_[k - 1]);
    return best != kMax && A::cmp(best, t[2], e) <= 0;
  }

 private:
  static constexpr T kMax = std::numeric_limits<T>::max();
  std::size_t d_;
  bool any_ = false;
  T min_second_ = kMax;
  std::vector<T> second_, tree_;
};

// The ε q needs, by a scan of the solution: min over p of max over i of need(p_i, q_i); a
// vector's maximum stops once it reaches the best so far. (Sweeper::need's score is the same
// loop for the front index; written out here, as before issue 44, the scan runs 10-15 % faster on
// small 2- and 3-objective fronts than through the shared lambda, BENCHMARKS.md issue 44.)
template <class T>
typename Arith<T>::Eps need_by_scan(FrontView<T> solution, const T* q) {
  using A = Arith<T>;
  typename A::Need best = A::unreachable();
  for (std::size_t k = 0; k < solution.size(); ++k) {
    const T* p = solution[k];
    typename A::Need worst = A::no_need();
    for (std::size_t i = 0; i < solution.dimension; ++i) {
      const auto e = A::need(p[i], q[i]);
      if (A::less(worst, e)) worst = e;
      if (!A::less(worst, best)) break;
    }
    if (A::less(worst, best)) best = worst;
  }
  return A::from_need(best);
}

// The offline coverage test ("which targets t have no point p ≤ (1+ε)·t?") and the need of one
// target. d ≤ 3: points and targets sorted once by coordinate 0 (scaling by 1+ε keeps that
// order), then each test is one merge sweep with a DominanceIndex. d ≥ 4: the front index of the
// points (front_index.hpp), asked once per target with the bound (1+ε)·t, rounded as cmp rounds.
template <class T>
class Sweeper {
  using A = Arith<T>;
  using Eps = typename A::Eps;

 public:
  Sweeper(FrontView<T> points, FrontView<T> targets)
      : points_(points), targets_(targets), index_(points) {
    if (points.dimension >= 4) {
      tree_.emplace(points.values, points.dimension);
    } else {
      point_order_ = by_first(points);
      target_order_ = by_first(targets);
    }
  }

  // Targets t with no point p ≤ (1+ε)·t, increasing.
  std::vector<std::size_t> uncovered(const Eps& e) {
    return tree_ ? uncovered_by_tree(e) : uncovered_by_sweep(e);
  }

  // The ε target t needs: min over the points p of max over i of need(p_i, t_i). A vector's
  // maximum stops once it reaches the best so far; the need only grows with each p_i, so the
  // front index may skip whole subtrees by it.
  Eps need(const T* t) const {
    using Need = typename A::Need;
    const std::size_t d = points_.dimension;
    const auto score = [t, d](const T* p, const Need& best) {
      Need worst = A::no_need();
      for (std::size_t i = 0; i < d; ++i) {
        const Need e = A::need(p[i], t[i]);
        if (A::less(worst, e)) worst = e;
        if (!A::less(worst, best)) break;
      }
      return worst;
    };
    const auto less = [](const Need& a, const Need& b) { return A::less(a, b); };
    if (tree_) return A::from_need(tree_->minimum(score, A::unreachable(), less));
    return need_by_scan(points_, t);
  }

 private:
  std::vector<std::size_t> uncovered_by_sweep(const Eps& e) {
    index_.reset();
    std::vector<std::size_t> out;
    std::size_t j = 0;
    for (std::size_t q : target_order_) {
      const T* t = targets_[q];
      while (j < point_order_.size() && A::cmp(points_[point_order_[j]][0], t[0], e) <= 0)
        index_.insert(points_[point_order_[j++]]);
      if (!index_.covers(t, e)) out.push_back(q);
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  std::vector<std::size_t> uncovered_by_tree(const Eps& e) const {
    std::vector<std::size_t> out;
    std::vector<T> bound(targets_.dimension);
    for (std::size_t q = 0; q < targets_.size(); ++q) {
      const T* t = targets_[q];
      for (std::size_t i = 0; i < bound.size(); ++i) bound[i] = A::bound(t[i], e);
      if (!tree_->any_at_most(bound.data())) out.push_back(q);
    }
    return out;
  }

  static std::vector<std::size_t> by_first(FrontView<T> front) {
    std::vector<std::size_t> order(front.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return front[a][0] < front[b][0]; });
    return order;
  }

  FrontView<T> points_, targets_;
  DominanceIndex<T> index_;
  std::optional<solutions_internal::FrontIndex<T>> tree_;
  std::vector<std::size_t> point_order_, target_order_;
};

// The minimal subset of a front: duplicates and vectors another one dominates removed
// (nondominance.hpp), in lexicographic order.
template <class T>
std::vector<T> minimal_subset(FrontView<T> front) {
  const std::size_t d = front.dimension;
  std::vector<bool> dropped(front.size(), false);
  for (std::size_t k : solutions_internal::weakly_dominated_rows<T>(front.values, d))
    dropped[k] = true;
  std::vector<T> kept;
  for (std::size_t k : lex_order(front))
    if (!dropped[k]) kept.insert(kept.end(), front[k], front[k] + d);
  return kept;
}

// Coverage under either reading. The strict one: weakly covered, and (1+ε)·q itself is not a
// vector of the minimal solution subset (if it is, the only vectors ≤ (1+ε)·q equal it).
template <class T>
class CoverageTest {
  using A = Arith<T>;
  using Eps = typename A::Eps;

 public:
  CoverageTest(FrontView<T> solution, FrontView<T> reference, bool strict)
      : reference_(reference),
        strict_(strict),
        minimal_(strict ? minimal_subset(solution) : std::vector<T>{}),
        sweeper_(strict ? FrontView<T>{minimal_, solution.dimension} : solution, reference) {}

  // The ε reference vector q needs: the same over the minimal subset as over the whole solution,
  // since a vector's need is at least that of any vector dominating it.
  Eps need(std::size_t q) const { return sweeper_.need(reference_[q]); }

  std::vector<std::size_t> uncovered(const Eps& e) {
    auto out = sweeper_.uncovered(e);
    if (!strict_) return out;
    const std::size_t d = reference_.dimension;
    const FrontView<T> minimal{minimal_, d};
    std::vector<std::size_t> strict_out;
    std::size_t next = 0;
    for (std::size_t q = 0; q < reference_.size(); ++q) {
      if (next < out.size() && out[next] == q) {
        strict_out.push_back(q);
        ++next;
        continue;
      }
      // Binary search for (1+ε)·q among the lexicographically sorted minimal vectors.
      const T* t = reference_[q];
      std::size_t lo = 0, hi = minimal.size();
      bool found = false;
      while (lo < hi) {
        const std::size_t mid = lo + (hi - lo) / 2;
        int sign = 0;
        for (std::size_t i = 0; i < d && sign == 0; ++i) sign = A::cmp(minimal[mid][i], t[i], e);
        if (sign == 0) {
          found = true;
          break;
        }
        if (sign < 0)
          lo = mid + 1;
        else
          hi = mid;
      }
      if (found) strict_out.push_back(q);
    }
    return strict_out;
  }

 private:
  FrontView<T> reference_;
  bool strict_;
  std::vector<T> minimal_;
  Sweeper<T> sweeper_;
};

template <class T>
void check_fronts(FrontView<T> solution, FrontView<T> reference) {
  if (solution.dimension != reference.dimension || reference.dimension == 0)
    throw Error(ErrorCode::invalid_argument,
                "evaluate_front: the solution has " + std::to_string(solution.dimension) +
                    " objectives, the reference " + std::to_string(reference.dimension));
  if (solution.values.size() % solution.dimension != 0 ||
      reference.values.size() % reference.dimension != 0)
    throw Error(ErrorCode::invalid_argument,
                "evaluate_front: a front's value count is not a multiple of its dimension");
}

template <class T>
std::vector<std::size_t> uncovered_impl(FrontView<T> solution, FrontView<T> reference,
                                        Ratio epsilon, const EvalOptions& options) {
  check_fronts(solution, reference);
  CoverageTest<T> test(solution, reference, options.strict_dominance);
  return test.uncovered(Arith<T>::make(epsilon));
}

// Exact matches (ε = 0 is the same multiset): merge the two lexicographic orders.
template <class T>
std::uint64_t count_matches(FrontView<T> solution, FrontView<T> reference,
                            const std::vector<std::size_t>& solution_lex,
                            const std::vector<std::size_t>& reference_lex) {
  const std::size_t d = reference.dimension;
  std::uint64_t matched = 0;
  for (std::size_t a = 0, b = 0; a < solution_lex.size() && b < reference_lex.size();) {
    const T* p = solution[solution_lex[a]];
    const T* q = reference[reference_lex[b]];
    if (lex_less(p, q, d)) {
      ++a;
    } else if (lex_less(q, p, d)) {
      ++b;
    } else {
      ++matched, ++a, ++b;
    }
  }
  return matched;
}

// Solution vectors the reference strictly dominates: weakly dominated, and not equal to a
// reference vector (if equal to q, nothing else in a non-dominated reference is ≤ it).
template <class T>
std::vector<std::size_t> dominated_by_reference(FrontView<T> solution, FrontView<T> reference,
                                                const std::vector<std::size_t>& reference_lex) {
  const std::size_t d = reference.dimension;
  std::vector<std::size_t> dominated;
  Sweeper<T> reverse(reference, solution);
  const auto not_dominated = reverse.uncovered(Arith<T>::zero());
  std::size_t next = 0;
  for (std::size_t k = 0; k < solution.size(); ++k) {
    if (next < not_dominated.size() && not_dominated[next] == k) {
      ++next;
      continue;
    }
    const T* p = solution[k];
    const auto it = std::lower_bound(
        reference_lex.begin(), reference_lex.end(), p,
        [&](std::size_t r, const T* probe) { return lex_less(reference[r], probe, d); });
    if (it != reference_lex.end() && std::equal(p, p + d, reference[*it])) continue;
    dominated.push_back(k);
  }
  return dominated;
}

// What the componentwise coverage tests learn about the achieved ε: it is above `floor`, and
// `open` holds the reference vectors the test at `floor` left uncovered (unset: none tested).
template <class T>
struct Bracket {
  typename Arith<T>::Eps floor = Arith<T>::zero();
  std::optional<std::vector<std::size_t>> open;
};

// The coverage tests at the requested ε, one entry of result.coverage each. The componentwise
// ones also bracket the achieved ε: the largest requested ε that leaves something uncovered, and
// what it leaves.
template <class T>
Bracket<T> test_requested(FrontView<T> solution, FrontView<T> reference,
                          std::span<const Ratio> epsilons, const EvalOptions& options,
                          std::uint64_t matched, CoverageTest<T>& weak, FrontEvaluation& result) {
  using A = Arith<T>;
  std::optional<CoverageTest<T>> strict;
  if (options.strict_dominance) strict.emplace(solution, reference, true);
  Bracket<T> bracket;
  for (const Ratio& epsilon : epsilons) {
    EpsilonCoverage c;
    c.epsilon = epsilon;
    if (epsilon.num == 0) {
      c.covered = result.same_multiset;
      c.uncovered = reference.size() - matched;
      c.extra = solution.size() - matched;
    } else {
      const typename A::Eps e = A::make(epsilon);
      auto u = weak.uncovered(e);
      c.uncovered = strict ? strict->uncovered(e).size() : u.size();
      c.covered = c.uncovered == 0;
      if (!u.empty() && (!bracket.open || A::less(bracket.floor, e))) {
        bracket.floor = e;
        bracket.open = std::move(u);
      }
    }
    result.coverage.push_back(c);
  }
  return bracket;
}

// The achieved ε always uses the componentwise reading (under the strict one the smallest ε
// need not exist: it is an infimum). It is the largest ε a reference vector needs, and the
// coverage test at ε returns exactly the vectors that need more than ε. One vector's need costs
// at most a scan of the solution, O(|S|·d) (for d ≥ 4 a branch and bound over its front index),
// far less than a coverage test. So: while many vectors are open, take the largest need of a
// sample of them and test it (what stays open needs more: about 1/(sample+1) of them); once few
// are open, the largest of their needs is the answer.
// Sets result.worst_reference.
template <class T>
typename Arith<T>::Eps search_achieved(CoverageTest<T>& weak, Bracket<T> bracket,
                                       FrontEvaluation& result) {
  using A = Arith<T>;
  using Eps = typename A::Eps;
  constexpr std::size_t kSample = 64, kScanAll = 256;
  auto& open = bracket.open;
  Eps& floor = bracket.floor;
  if (!open) open = weak.uncovered(A::zero());
  Eps achieved = A::zero();
  SplitMix64 pick(0x5eed);  // a fixed seed: the same result and time on every run
  while (!open->empty()) {
    std::vector<std::size_t> candidates;
    if (open->size() <= kScanAll) {
      candidates = *open;
    } else {
      for (std::size_t k = 0; k < kSample; ++k)
        candidates.push_back((*open)[pick.uniform(0, open->size() - 1)]);
    }
    Eps largest = A::zero();
    std::size_t worst = candidates.front();
    for (std::size_t q : candidates) {
      const Eps need = weak.need(q);
      if (A::less(largest, need) || q == candidates.front()) largest = need, worst = q;
    }
    result.worst_reference = worst;
    achieved = largest;
    // The last test cannot trigger while the coverage test and the need agree; it keeps the loop
    // finite if they ever did not.
    if (open->size() <= kScanAll || !A::less(largest, A::make(kInfinity)) ||
        !A::less(floor, largest))
      break;
    open = weak.uncovered(largest);
    floor = largest;
  }
  return achieved;
}

template <class T>
FrontEvaluation evaluate_impl(FrontView<T> solution, FrontView<T> reference,
                              std::span<const Ratio> epsilons, const EvalOptions& options) {
  check_fronts(solution, reference);
  FrontEvaluation result;
  result.solution_size = solution.size();
  result.reference_size = reference.size();

  const auto solution_lex = lex_order(solution);
  const auto reference_lex = lex_order(reference);
  const std::uint64_t matched = count_matches(solution, reference, solution_lex, reference_lex);
  result.same_multiset = matched == reference.size() && matched == solution.size();
  result.dominated_by_reference = dominated_by_reference(solution, reference, reference_lex);

  CoverageTest<T> weak(solution, reference, false);
  auto bracket = test_requested(solution, reference, epsilons, options, matched, weak, result);
  const auto achieved = search_achieved(weak, std::move(bracket), result);
  if constexpr (std::is_same_v<T, std::uint64_t>) {
    result.achieved = achieved.is_infinite() ? kInfinity : reduced(achieved.num, achieved.den);
    result.achieved_value = achieved.to_double();
  } else {
    result.achieved_value = achieved;
    result.achieved = std::isinf(achieved) ? kInfinity : Ratio{0, 1};
  }
  return result;
}

}  // namespace

double Ratio::to_double() const {
  if (is_infinite()) return std::numeric_limits<double>::infinity();
  return static_cast<double>(static_cast<long double>(num) / static_cast<long double>(den));
}

std::string Ratio::to_decimal(int digits) const {
  if (is_infinite()) return "inf";
  std::string out = std::to_string(num / den);
  std::uint64_t rest = num % den;
  if (rest == 0) return out;
  std::string fraction;
  for (int k = 0; k < digits && rest != 0; ++k) {
    const u128 scaled = static_cast<u128>(rest) * 10;
    fraction.push_back(static_cast<char>('0' + static_cast<int>(scaled / den)));
    rest = static_cast<std::uint64_t>(scaled % den);
  }
  if (rest != 0) {
    // Round up at the last digit, carrying into the integer part if needed.
    int k = static_cast<int>(fraction.size()) - 1;
    while (k >= 0 && fraction[static_cast<std::size_t>(k)] == '9') {
      fraction[static_cast<std::size_t>(k)] = '0';
      --k;
    }
    if (k >= 0) {
      ++fraction[static_cast<std::size_t>(k)];
    } else {
      out = std::to_string(num / den + 1);
    }
    while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
  }
  return fraction.empty() ? out : out + "." + fraction;
}

bool operator==(const Ratio& a, const Ratio& b) {
  if (a.is_infinite() || b.is_infinite()) return a.is_infinite() == b.is_infinite();
  return static_cast<u128>(a.num) * b.den == static_cast<u128>(b.num) * a.den;
}

bool operator<(const Ratio& a, const Ratio& b) {
  if (a.is_infinite()) return false;
  if (b.is_infinite()) return true;
  return static_cast<u128>(a.num) * b.den < static_cast<u128>(b.num) * a.den;
}

namespace {

// Why `text`, which is not the plain decimal parse_epsilon takes, is refused: a number written
// otherwise (an exponent, a sign, inf) is named for what it is, out of range first.
std::string refusal(std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::invalid_argument || end != text.data() + text.size())
    return "not a number: expected a non-negative decimal number such as 0.05";
  if (std::isnan(value)) return "not a number: expected a non-negative decimal number such as 0.05";
  if (text.front() == '-') return "negative: expected a non-negative decimal number such as 0.05";
  if (error == std::errc::result_out_of_range || std::isinf(value) || value >= 1e18 ||
      (value > 0 && value < 1e-18))
    return "out of range: an epsilon is below 10^18 and a multiple of 10^-18";
  return "write it without an exponent, as a decimal number such as 0.05";
}

}  // namespace

Ratio parse_epsilon(std::string_view text) {
  const auto bad = [&](const std::string& why) {
    return Error(ErrorCode::invalid_argument,
                 "invalid epsilon '" + std::string(text) + "': " + why);
  };
  const std::size_t point = text.find('.');
  std::string_view whole = text.substr(0, point);
  std::string_view fraction =
      point == std::string_view::npos ? std::string_view{} : text.substr(point + 1);
  if (whole.empty() && fraction.empty()) throw bad(refusal(text));
  for (std::string_view part : {whole, fraction})
    for (char c : part)
      if (c < '0' || c > '9') throw bad(refusal(text));
  // Leading zeros of the whole part and trailing zeros of the fraction carry no digit of the value.
  while (!whole.empty() && whole.front() == '0') whole.remove_prefix(1);
  while (!fraction.empty() && fraction.back() == '0') fraction.remove_suffix(1);
  if (whole.size() > 18)
    throw bad("out of range: more than 18 digits before the point (at most 10^18 - 1)");
  if (fraction.size() > 18)
    throw bad(whole.empty() &&
                      fraction.substr(0, 18).find_first_not_of('0') == std::string_view::npos
                  ? "out of range: below 10^-18, the finest epsilon (18 digits after the point)"
                  : "more than 18 digits after the point");
  // Up to 36 digits: exact in 128 bits, then reduced; the fraction must fit in 64 bits.
  u128 num = 0, den = 1;
  for (char c : whole) num = num * 10 + static_cast<u128>(c - '0');
  for (char c : fraction) {
    num = num * 10 + static_cast<u128>(c - '0');
    den *= 10;
  }
  for (const u128 prime : {u128{2}, u128{5}})
    while (den % prime == 0 && num % prime == 0) {
      num /= prime;
      den /= prime;
    }
  if (num > std::numeric_limits<std::uint64_t>::max())
    throw bad("out of range: not a fraction of two 64-bit integers (too many digits)");
  return reduced(static_cast<std::uint64_t>(num), static_cast<std::uint64_t>(den));
}

FrontEvaluation evaluate_front(FrontView<std::uint64_t> solution,
                               FrontView<std::uint64_t> reference, std::span<const Ratio> epsilons,
                               const EvalOptions& options) {
  return evaluate_impl(solution, reference, epsilons, options);
}

FrontEvaluation evaluate_front(FrontView<double> solution, FrontView<double> reference,
                               std::span<const Ratio> epsilons, const EvalOptions& options) {
  return evaluate_impl(solution, reference, epsilons, options);
}

std::vector<std::size_t> uncovered_reference(FrontView<std::uint64_t> solution,
                                             FrontView<std::uint64_t> reference, Ratio epsilon,
                                             const EvalOptions& options) {
  return uncovered_impl(solution, reference, epsilon, options);
}

std::vector<std::size_t> uncovered_reference(FrontView<double> solution,
                                             FrontView<double> reference, Ratio epsilon,
                                             const EvalOptions& options) {
  return uncovered_impl(solution, reference, epsilon, options);
}

// Rounded up at the 9th digit (less a millionth of a unit there, so that a ratio whose double
// rounding lands just above a 9-digit decimal is not pushed one unit up); a positive ε is at least
// 0.000000001, never "0", which would claim the fronts equal.
std::string achieved_epsilon_text(const FrontEvaluation& front, bool exact) {
  if (exact) return front.achieved.den == 0 ? "inf" : front.achieved.to_decimal();
  if (!std::isfinite(front.achieved_value)) return "inf";
  const double units = std::ceil(front.achieved_value * 1e9 - 1e-6);
  const double up = (front.achieved_value > 0 ? std::max(1.0, units) : 0.0) / 1e9;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9f", up);
  std::string text = buffer;
  while (text.back() == '0') text.pop_back();
  if (text.back() == '.') text.pop_back();
  return text;
}

}  // namespace mosb
