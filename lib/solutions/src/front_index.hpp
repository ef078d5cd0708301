// Orthant queries on a front of any dimension: "is some vector ≤ b in every objective?", and the
// smallest value of a score that only grows with each coordinate. The one structure behind the
// dominance sweeps of nondominance.cpp and the ε-coverage tests of eval.cpp for d >= 4
// (spec/EVALUATION.md §3). Internal to lib/solutions; generic over the stored value type.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mosb::solutions_internal {

// A static k-d tree over the vectors of a front. Every node keeps its bounding box, the smallest
// rank of its vectors and the smallest key of its vectors, the key being a weighted sum of the
// coordinates with power-of-two weights (computed in double arithmetic, it only grows with each
// coordinate, so a vector ≤ b has a key ≤ b's key: on a front whose vectors lie near a plane, the
// key alone rules out most of the tree). Queries compare stored values with `<=` only, so their
// answers are exactly those of a scan, whatever T.
template <class T>
class FrontIndex {
 public:
  // `rows`: n vectors of d values, row-major (copied). `rank`: empty, or one per vector; a query
  // then sees only the vectors of rank below its limit.
  FrontIndex(std::span<const T> rows, std::size_t d, std::span<const std::size_t> rank = {});

  // Whether some vector x of rank below `limit` has x[i] <= bound[i] for every i.
  bool any_at_most(const T* bound, std::size_t limit = SIZE_MAX) const;

  // The smallest score over every vector, `none` when there are none; `less` orders scores.
  // score(x, best) must only grow with each coordinate of x, and may return any value not below
  // `best` as soon as it knows score(x) is not below it. A subtree is skipped when the score of
  // its box's low corner is not below the best so far, so the result is that of a scan.
  template <class Score, class Value, class Less>
  Value minimum(Score score, Value none, Less less) const;

 private:
  static constexpr std::size_t kLeaf = 8;
  struct Node {
    std::size_t begin, end, right;  // the left child, if any, is the next node
    std::size_t axis;               // split at the right child's lowest value on it
    std::size_t first_rank;
    double min_key;
  };

  std::size_t build(std::span<const T> rows, std::vector<std::size_t>& order, std::size_t begin,
                    std::size_t end);
  std::size_t widest_axis(std::size_t node) const;
  bool any_below(std::size_t node, const T* bound, double key, std::size_t limit) const;
  template <class Score, class Value, class Less>
  void minimum_below(std::size_t node, Score& score, Value& best, Less& less) const;
  double key_of(const T* x) const;
  const T* point(std::size_t p) const { return points_.data() + p * d_; }
  const T* low(std::size_t node) const { return boxes_.data() + node * 2 * d_; }
  const T* high(std::size_t node) const { return low(node) + d_; }
  bool leaf(std::size_t node) const { return nodes_[node].right == 0; }
  std::size_t rank_of(std::size_t p) const { return rank_.empty() ? 0 : rank_[p]; }

  std::size_t d_;
  std::vector<T> points_;  // the vectors in tree order, each leaf's contiguous
  std::vector<std::size_t> rank_;
  std::vector<double> weight_, key_;
  std::vector<Node> nodes_;
  std::vector<T> boxes_;  // per node: d lows, then d highs
};

template <class T>
template <class Score, class Value, class Less>
Value FrontIndex<T>::minimum(Score score, Value none, Less less) const {
  Value best = none;
  if (!nodes_.empty()) minimum_below(0, score, best, less);
  return best;
}

// Depth first, the child with the smaller lower bound first: a good score found early prunes the
// rest.
template <class T>
template <class Score, class Value, class Less>
void FrontIndex<T>::minimum_below(std::size_t node, Score& score, Value& best, Less& less) const {
  if (leaf(node)) {
    for (std::size_t p = nodes_[node].begin; p < nodes_[node].end; ++p) {
      const Value s = score(point(p), best);
      if (less(s, best)) best = s;
    }
    return;
  }
  const std::size_t left = node + 1, right = nodes_[node].right;
  const Value left_bound = score(low(left), best), right_bound = score(low(right), best);
  const bool right_first = less(right_bound, left_bound);
  if (less(right_first ? right_bound : left_bound, best))
    minimum_below(right_first ? right : left, score, best, less);
  if (less(right_first ? left_bound : right_bound, best))
    minimum_below(right_first ? left : right, score, best, less);
}

extern template class FrontIndex<std::uint64_t>;
extern template class FrontIndex<std::int64_t>;
extern template class FrontIndex<double>;

}  // namespace mosb::solutions_internal
