// The median of a list of numbers (the upper one of an even count), NaN for an empty list.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

namespace brdfrig {

inline double Median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace brdfrig
