// Order statistics the benches report: the median and quartiles of a sample (element
// size / 4, / 2 and 3 · size / 4 of the sorted values, no interpolation).
#pragma once

#include <algorithm>
#include <array>
#include <vector>

namespace shanshui::bench {

//! Lower quartile, median and upper quartile; `v` must not be empty.
inline std::array<double, 3> quartiles(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return {v[v.size() / 4], v[v.size() / 2], v[(3 * v.size()) / 4]};
}

inline double median(std::vector<double> v) {
  return quartiles(std::move(v))[1];
}

}  // namespace shanshui::bench
