#include "front_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace mosb::solutions_internal {

namespace {

// Per objective, 2^k for the largest k ≤ 60 with 2^k · range ≤ the largest range (a constant
// objective weighs 1): objectives of similar spread weigh the same, so on a front near the plane
// "sum of costs = c" the key is that sum, and an objective with a tiny range is not drowned by one
// with a huge range. Any non-negative weights would be correct; these make the key discriminate.
template <class T>
std::vector<double> key_weights(std::span<const T> rows, std::size_t d) {
  const std::size_t n = rows.size() / d;
  std::vector<double> range(d, 0.0);
  for (std::size_t i = 0; i < d; ++i) {
    auto low = static_cast<double>(rows[i]), high = low;
    for (std::size_t k = 1; k < n; ++k) {
      low = std::min(low, static_cast<double>(rows[k * d + i]));
      high = std::max(high, static_cast<double>(rows[k * d + i]));
    }
    range[i] = high - low;
  }
  const double widest = *std::max_element(range.begin(), range.end());
  std::vector<double> weight(d, 1.0);
  if (!std::isfinite(widest)) return weight;
  for (std::size_t i = 0; i < d; ++i) {
    if (!(range[i] > 0)) continue;
    int k = 0;
    while (k < 60 && std::ldexp(range[i], k + 1) <= widest) ++k;
    weight[i] = std::ldexp(1.0, k);
  }
  return weight;
}

}  // namespace

template <class T>
FrontIndex<T>::FrontIndex(std::span<const T> rows, std::size_t d, std::span<const std::size_t> rank)
    : d_(d) {
  const std::size_t n = d == 0 ? 0 : rows.size() / d;
  if (n == 0) return;
  weight_ = key_weights(rows, d);
  points_.assign(rows.begin(), rows.end());
  rank_.assign(rank.begin(), rank.end());  // empty: every vector has rank 0
  key_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    key_[k] = key_of(point(k));
    if (std::isnan(key_[k])) key_[k] = -std::numeric_limits<double>::infinity();
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  nodes_.reserve(2 * (n / kLeaf) + 1);
  build(order, 0, n);
  // Lay the vectors, ranks and keys out in tree order, so that a leaf's are contiguous.
  std::vector<T> points(n * d);
  std::vector<std::size_t> ranks(rank_.empty() ? 0 : n);
  std::vector<double> keys(n);
  for (std::size_t p = 0; p < n; ++p) {
    std::copy(point(order[p]), point(order[p]) + d,
              points.begin() + static_cast<std::ptrdiff_t>(p * d));
    if (!rank_.empty()) ranks[p] = rank_[order[p]];
    keys[p] = key_[order[p]];
  }
  points_ = std::move(points);
  rank_ = std::move(ranks);
  key_ = std::move(keys);
}

// Nodes in depth-first order; a node's box, smallest rank and smallest key are those of its
// vectors. Split at the median of the axis of widest weighted spread.
template <class T>
std::size_t FrontIndex<T>::build(std::vector<std::size_t>& order, std::size_t begin,
                                 std::size_t end) {
  const std::size_t index = nodes_.size();
  nodes_.push_back({begin, end, 0, 0, SIZE_MAX, key_[order[begin]]});
  boxes_.resize(boxes_.size() + 2 * d_);
  T* low = boxes_.data() + index * 2 * d_;
  T* high = low + d_;
  std::copy(point(order[begin]), point(order[begin]) + d_, low);
  std::copy(point(order[begin]), point(order[begin]) + d_, high);
  for (std::size_t p = begin; p < end; ++p) {
    const T* x = point(order[p]);
    for (std::size_t i = 0; i < d_; ++i) {
      low[i] = std::min(low[i], x[i]);
      high[i] = std::max(high[i], x[i]);
    }
    nodes_[index].first_rank = std::min(nodes_[index].first_rank, rank_of(order[p]));
    nodes_[index].min_key = std::min(nodes_[index].min_key, key_[order[p]]);
  }
  if (end - begin <= kLeaf) return index;
  const std::size_t axis = widest_axis(index), middle = begin + (end - begin) / 2;
  std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin),
                   order.begin() + static_cast<std::ptrdiff_t>(middle),
                   order.begin() + static_cast<std::ptrdiff_t>(end),
                   [&](std::size_t a, std::size_t b) { return point(a)[axis] < point(b)[axis]; });
  build(order, begin, middle);
  const std::size_t right = build(order, middle, end);
  nodes_[index].right = right;
  nodes_[index].axis = axis;
  return index;
}

template <class T>
std::size_t FrontIndex<T>::widest_axis(std::size_t node) const {
  std::size_t axis = 0;
  double widest = -1;
  for (std::size_t i = 0; i < d_; ++i) {
    const double spread =
        weight_[i] * (static_cast<double>(high(node)[i]) - static_cast<double>(low(node)[i]));
    if (spread > widest) widest = spread, axis = i;
  }
  return axis;
}

// Rounding is monotone, so each product and each partial sum only grows with x[i], infinities
// included. Only +inf + -inf breaks it (values near ±DBL_MAX times a weight): such a key is NaN,
// which rules nothing out as a bound and becomes -inf, the smallest key, for a stored vector.
template <class T>
double FrontIndex<T>::key_of(const T* x) const {
  double key = 0;
  for (std::size_t i = 0; i < d_; ++i) key += weight_[i] * static_cast<double>(x[i]);
  return key;
}

template <class T>
bool FrontIndex<T>::any_at_most(const T* bound, std::size_t limit) const {
  return !nodes_.empty() && any_below(0, bound, key_of(bound), limit);
}

// The node's vectors hold one ≤ bound if its box lies inside the orthant and one of them is
// seen; none if the box, the keys or the ranks rule them all out.
template <class T>
bool FrontIndex<T>::any_below(std::size_t node, const T* bound, double key,
                              std::size_t limit) const {
  const Node& n = nodes_[node];
  if (n.first_rank >= limit || n.min_key > key) return false;
  bool inside = true;
  for (std::size_t i = 0; i < d_; ++i) {
    if (low(node)[i] > bound[i]) return false;
    inside = inside && high(node)[i] <= bound[i];
  }
  if (inside) return true;
  if (leaf(node)) {
    for (std::size_t p = n.begin; p < n.end; ++p) {
      if (rank_of(p) >= limit || key_[p] > key) continue;
      const T* x = point(p);
      if (std::equal(x, x + d_, bound, [](T a, T b) { return a <= b; })) return true;
    }
    return false;
  }
  // First the child on the bound's side of the split: the vectors nearest the bound are there,
  // and a vector just below the bound, if any, is most likely among them.
  const bool right_first = low(n.right)[n.axis] <= bound[n.axis];
  const std::size_t first = right_first ? n.right : node + 1,
                    second = right_first ? node + 1 : n.right;
  return any_below(first, bound, key, limit) || any_below(second, bound, key, limit);
}

template class FrontIndex<std::uint64_t>;
template class FrontIndex<std::int64_t>;
template class FrontIndex<double>;

}  // namespace mosb::solutions_internal
