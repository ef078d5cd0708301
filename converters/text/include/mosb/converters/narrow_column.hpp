// The one rule for storing a data column of integers: the first of the candidate element types that
// holds every value exactly (the candidates listed narrowest first).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mosb/graph_builder.hpp"

namespace mosb::converters {

// `values` as a data column of `width` elements per row, stored as the first of `Candidates` that
// holds every value; the last candidate is used when none does (list the input's own type last).
// e.g. narrowest_column<std::uint8_t, std::uint16_t, std::uint32_t, std::uint64_t>("type", 1, v).
template <class... Candidates, class T>
DataColumn narrowest_column(std::string name, std::uint32_t width, const std::vector<T>& values) {
  static_assert(sizeof...(Candidates) > 0 && std::is_integral_v<T>);
  DataColumn column;
  std::size_t rank = 0;
  auto take_if_all_fit = [&]<class C>() {
    const bool last = ++rank == sizeof...(Candidates);
    if (!last &&
        !std::all_of(values.begin(), values.end(), [](T v) { return std::in_range<C>(v); }))
      return false;
    column = DataColumn::from(std::move(name), width, std::vector<C>(values.begin(), values.end()));
    return true;
  };
  (take_if_all_fit.template operator()<Candidates>() || ...);
  return column;
}

}  // namespace mosb::converters
