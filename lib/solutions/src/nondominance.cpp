#include "nondominance.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <vector>

namespace mosb::solutions_internal {

namespace {

template <class T>
struct Rows {
  std::span<const T> values;
  std::size_t d;
  std::size_t size() const { return values.size() / d; }
  const T* at(std::size_t k) const { return values.data() + k * d; }
  bool weakly_dominates(std::size_t a, std::size_t b) const {
    const T *x = at(a), *y = at(b);
    for (std::size_t i = 0; i < d; ++i)
      if (x[i] > y[i]) return false;
    return true;
  }
};

// Row indices in lexicographic order of their vectors, equal vectors by index (deterministic).
// Only a vector at or before v in this order can weakly dominate v.
template <class T>
std::vector<std::size_t> lexicographic_order(const Rows<T>& rows) {
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const T *x = rows.at(a), *y = rows.at(b);
    for (std::size_t i = 0; i < rows.d; ++i)
      if (x[i] != y[i]) return x[i] < y[i];
    return a < b;
  });
  return order;
}

// The sweeps below call found(j), in increasing j, for every position j of `order` whose vector is
// weakly dominated by one at a position before j, and stop when it returns false. Every earlier
// vector is no worse in the first objective, so only the other objectives are asked. A dominated
// vector is not kept for later ones: whatever it dominates, the vector dominating it does too.

// d = 2: some earlier vector dominates v iff the smallest earlier second value is <= v's.
template <class T, class Found>
void sweep_two(const Rows<T>& rows, const std::vector<std::size_t>& order, Found found) {
  T best = rows.at(order[0])[1];
  for (std::size_t j = 1; j < order.size(); ++j) {
    const T second = rows.at(order[j])[1];
    if (best <= second) {
      if (!found(j)) return;
      continue;
    }
    best = second;
  }
}

// d = 3: the staircase of earlier (second, third) pairs that no other earlier pair weakly
// dominates: keyed by the second value, the third strictly decreasing. The entry with the largest
// second value <= v's holds the smallest third value among all such entries.
template <class T, class Found>
void sweep_three(const Rows<T>& rows, const std::vector<std::size_t>& order, Found found) {
  std::map<T, T> staircase;
  for (std::size_t j = 0; j < order.size(); ++j) {
    const T y = rows.at(order[j])[1], z = rows.at(order[j])[2];
    auto it = staircase.upper_bound(y);
    if (it != staircase.begin() && std::prev(it)->second <= z) {
      if (!found(j)) return;
      continue;
    }
    // (y, z) is not dominated: it replaces the entries it dominates, which follow it.
    it = staircase.lower_bound(y);
    while (it != staircase.end() && it->second >= z) it = staircase.erase(it);
    staircase.emplace_hint(it, y, z);
  }
}

// d >= 4: a static k-d tree over the last d - 1 values of every vector; each node keeps its
// bounding box and the smallest sweep position below it, so a query for position j skips subtrees
// holding only later vectors or lying outside the orthant below v.
template <class T>
class DominanceTree {
 public:
  DominanceTree(const Rows<T>& rows, const std::vector<std::size_t>& order)
      : rows_(rows), k_(rows.d - 1) {
    position_.resize(order.size());
    for (std::size_t j = 0; j < order.size(); ++j) position_[order[j]] = j;
    items_ = order;
    build(0, items_.size(), 0);
  }

  // Whether a vector at a sweep position before j is no worse than `row` in objectives 1..d-1.
  bool any_before(std::size_t j, std::size_t row) const { return query(0, j, rows_.at(row) + 1); }

 private:
  static constexpr std::size_t kLeaf = 16;
  struct Node {
    std::size_t begin, end, left = 0, right = 0, first_position;
  };

  std::size_t build(std::size_t begin, std::size_t end, std::size_t depth) {
    const std::size_t index = nodes_.size();
    nodes_.push_back({begin, end, 0, 0, SIZE_MAX});
    low_.resize(low_.size() + k_);
    high_.resize(high_.size() + k_);
    for (std::size_t i = 0; i < k_; ++i) {
      low_[index * k_ + i] = high_[index * k_ + i] = value(items_[begin], i);
      for (std::size_t p = begin; p < end; ++p) {
        low_[index * k_ + i] = std::min(low_[index * k_ + i], value(items_[p], i));
        high_[index * k_ + i] = std::max(high_[index * k_ + i], value(items_[p], i));
      }
    }
    for (std::size_t p = begin; p < end; ++p)
      nodes_[index].first_position = std::min(nodes_[index].first_position, position_[items_[p]]);
    if (end - begin <= kLeaf) return index;
    const std::size_t axis = depth % k_, middle = begin + (end - begin) / 2;
    std::nth_element(items_.begin() + static_cast<std::ptrdiff_t>(begin),
                     items_.begin() + static_cast<std::ptrdiff_t>(middle),
                     items_.begin() + static_cast<std::ptrdiff_t>(end),
                     [&](std::size_t a, std::size_t b) { return value(a, axis) < value(b, axis); });
    const std::size_t left = build(begin, middle, depth + 1);
    const std::size_t right = build(middle, end, depth + 1);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
  }

  bool query(std::size_t index, std::size_t j, const T* v) const {
    const Node& node = nodes_[index];
    if (node.first_position >= j) return false;
    bool inside = true;
    for (std::size_t i = 0; i < k_; ++i) {
      if (low_[index * k_ + i] > v[i]) return false;
      inside = inside && high_[index * k_ + i] <= v[i];
    }
    if (inside) return true;  // the node's first vector is before j and no worse than v
    if (node.left == 0) {
      for (std::size_t p = node.begin; p < node.end; ++p) {
        const std::size_t row = items_[p];
        if (position_[row] >= j) continue;
        const T* x = rows_.at(row) + 1;
        if (std::equal(x, x + k_, v, [](T a, T b) { return a <= b; })) return true;
      }
      return false;
    }
    return query(node.left, j, v) || query(node.right, j, v);
  }

  T value(std::size_t row, std::size_t i) const { return rows_.at(row)[i + 1]; }

  const Rows<T>& rows_;
  std::size_t k_;
  std::vector<std::size_t> position_, items_;
  std::vector<Node> nodes_;
  std::vector<T> low_, high_;
};

template <class T, class Found>
void sweep_tree(const Rows<T>& rows, const std::vector<std::size_t>& order, Found found) {
  const DominanceTree<T> tree(rows, order);
  for (std::size_t j = 1; j < order.size(); ++j)
    if (tree.any_before(j, order[j]) && !found(j)) return;
}

template <class T, class Found>
void sweep(const Rows<T>& rows, const std::vector<std::size_t>& order, Found found) {
  if (rows.d == 1) {
    for (std::size_t j = 1; j < order.size(); ++j)  // any two one-objective vectors compare
      if (!found(j)) return;
  } else if (rows.d == 2) {
    sweep_two(rows, order, found);
  } else if (rows.d == 3) {
    sweep_three(rows, order, found);
  } else {
    sweep_tree(rows, order, found);
  }
}

}  // namespace

template <class T>
std::optional<DominatedPair> find_weakly_dominated(std::span<const T> values, std::size_t d) {
  const Rows<T> rows{values, d};
  if (rows.size() < 2) return std::nullopt;
  const auto order = lexicographic_order(rows);
  std::optional<std::size_t> j;
  sweep(rows, order, [&](std::size_t position) {
    j = position;
    return false;
  });
  if (!j) return std::nullopt;
  // The first earlier vector in lexicographic order that dominates it: one linear scan.
  const std::size_t dominated = order[*j];
  for (std::size_t k = 0; k < *j; ++k)
    if (rows.weakly_dominates(order[k], dominated)) return DominatedPair{dominated, order[k]};
  return std::nullopt;  // unreachable: the sweep found such a vector
}

template <class T>
std::vector<std::size_t> weakly_dominated_rows(std::span<const T> values, std::size_t d) {
  const Rows<T> rows{values, d};
  std::vector<std::size_t> dominated;
  if (rows.size() < 2) return dominated;
  const auto order = lexicographic_order(rows);
  sweep(rows, order, [&](std::size_t position) {
    dominated.push_back(order[position]);
    return true;
  });
  std::sort(dominated.begin(), dominated.end());
  return dominated;
}

template std::vector<std::size_t> weakly_dominated_rows<double>(std::span<const double>,
                                                                std::size_t);
template std::optional<DominatedPair> find_weakly_dominated<std::uint64_t>(
    std::span<const std::uint64_t>, std::size_t);
template std::optional<DominatedPair> find_weakly_dominated<std::int64_t>(
    std::span<const std::int64_t>, std::size_t);
template std::optional<DominatedPair> find_weakly_dominated<double>(std::span<const double>,
                                                                    std::size_t);

}  // namespace mosb::solutions_internal
