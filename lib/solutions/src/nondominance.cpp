#include "nondominance.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <vector>

#include "front_index.hpp"

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
// Only a vector at or before v in this order can weakly dominate v. Rows already in that order
// (as solvers and mosb's writer often leave a front) cost one pass, not a sort.
template <class T>
std::vector<std::size_t> lexicographic_order(const Rows<T>& rows) {
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto before = [&](std::size_t a, std::size_t b) {
    const T *x = rows.at(a), *y = rows.at(b);
    for (std::size_t i = 0; i < rows.d; ++i)
      if (x[i] != y[i]) return x[i] < y[i];
    return a < b;
  };
  if (!std::is_sorted(order.begin(), order.end(), before))
    std::sort(order.begin(), order.end(), before);
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

// d >= 4: the front index (front_index.hpp) over every vector, ranked by sweep position: a query
// for position j sees only the vectors before it.
template <class T, class Found>
void sweep_tree(const Rows<T>& rows, const std::vector<std::size_t>& order, Found found) {
  std::vector<std::size_t> position(order.size());
  for (std::size_t j = 0; j < order.size(); ++j) position[order[j]] = j;
  const FrontIndex<T> index(rows.values, rows.d, position);
  for (std::size_t j = 1; j < order.size(); ++j)
    if (index.any_at_most(rows.at(order[j]), j) && !found(j)) return;
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

template std::vector<std::size_t> weakly_dominated_rows<std::uint64_t>(
    std::span<const std::uint64_t>, std::size_t);
template std::vector<std::size_t> weakly_dominated_rows<double>(std::span<const double>,
                                                                std::size_t);
template std::optional<DominatedPair> find_weakly_dominated<std::uint64_t>(
    std::span<const std::uint64_t>, std::size_t);
template std::optional<DominatedPair> find_weakly_dominated<std::int64_t>(
    std::span<const std::int64_t>, std::size_t);
template std::optional<DominatedPair> find_weakly_dominated<double>(std::span<const double>,
                                                                    std::size_t);

}  // namespace mosb::solutions_internal
