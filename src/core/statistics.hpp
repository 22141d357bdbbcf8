#pragma once
// Small summaries of measured series, the one definition the report and the sweep share.
#include <algorithm>
#include <vector>

namespace lzb {

// The median of v (the mean of the middle two for an even count); 0 for an empty series.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace lzb
