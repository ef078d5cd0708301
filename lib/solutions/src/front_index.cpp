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
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  nodes_.reserve(n / 2 + 1);  // a leaf holds at least kLeaf / 2 vectors
  boxes_.reserve(nodes_.capacity() * 2 * d);
  build(rows, order, 0, n);
  // The vectors, keys and ranks in tree order, so that a leaf's are contiguous.
  points_.resize(n * d);
  key_.resize(n);
  if (!rank.empty()) rank_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(order[p] * d), d,
                points_.begin() + static_cast<std::ptrdiff_t>(p * d));
    key_[p] = key_of(point(p));
    if (std::isnan(key_[p])) key_[p] = -std::numeric_limits<double>::infinity();
    if (!rank.empty()) rank_[p] = rank[order[p]];
  }
  // Children follow their parent: in reverse, each node's smallest key and rank from theirs.
  for (std::size_t node = nodes_.size(); node-- > 0;) {
    Node& here = nodes_[node];
    if (leaf(node)) {
      for (std::size_t p = here.begin; p < here.end; ++p) {
        here.min_key = std::min(here.min_key, key_[p]);
        here.first_rank = std::min(here.first_rank, rank_of(p));
      }
    } else {
      here.min_key = std::min(nodes_[node + 1].min_key, nodes_[here.right].min_key);
      here.first_rank = std::min(nodes_[node + 1].first_rank, nodes_[here.right].first_rank);
    }
  }
}

// Nodes in depth-first order, each with the bounding box of its vectors; split at the median of
// the axis of widest weighted spread.
template <class T>
std::size_t FrontIndex<T>::build(std::span<const T> rows, std::vector<std::size_t>& order,
                                 std::size_t begin, std::size_t end) {
  const auto row = [&](std::size_t k) { return rows.data() + k * d_; };
  const std::size_t index = nodes_.size();
  nodes_.push_back({begin, end, 0, 0, SIZE_MAX, std::numeric_limits<double>::infinity()});
  boxes_.resize(boxes_.size() + 2 * d_);
  T* low = boxes_.data() + index * 2 * d_;
  T* high = low + d_;
  std::copy_n(row(order[begin]), d_, low);
  std::copy_n(row(order[begin]), d_, high);
  for (std::size_t p = begin + 1; p < end; ++p) {
    const T* x = row(order[p]);
    for (std::size_t i = 0; i < d_; ++i) {
      low[i] = std::min(low[i], x[i]);
      high[i] = std::max(high[i], x[i]);
    }
  }
  if (end - begin <= kLeaf) return index;
  const std::size_t axis = widest_axis(index), middle = begin + (end - begin) / 2;
  std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin),
                   order.begin() + static_cast<std::ptrdiff_t>(middle),
                   order.begin() + static_cast<std::ptrdiff_t>(end),
                   [&](std::size_t a, std::size_t b) { return row(a)[axis] < row(b)[axis]; });
  build(rows, order, begin, middle);
  const std::size_t right = build(rows, order, middle, end);
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
