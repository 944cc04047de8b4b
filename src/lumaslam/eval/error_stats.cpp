#include "lumaslam/eval/error_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "lumaslam/core/error.h"

namespace lumaslam::eval {

ErrorStats computeStats(std::span<const double> errors) {
  if (errors.empty()) fail("error statistics: no errors to summarise (0 pose pairs)");
  ErrorStats stats;
  stats.count = errors.size();
  const double n = static_cast<double>(errors.size());
  const double sum = std::accumulate(errors.begin(), errors.end(), 0.0);
  const double sum_squares = std::accumulate(errors.begin(), errors.end(), 0.0,
                                             [](double acc, double e) { return acc + e * e; });
  stats.mean = sum / n;
  stats.rmse = std::sqrt(sum_squares / n);
  stats.std = std::sqrt(std::max(0.0, sum_squares / n - stats.mean * stats.mean));
  const auto [min_it, max_it] = std::minmax_element(errors.begin(), errors.end());
  stats.min = *min_it;
  stats.max = *max_it;

  std::vector<double> sorted(errors.begin(), errors.end());
  const std::size_t middle = sorted.size() / 2;
  std::nth_element(sorted.begin(), sorted.begin() + middle, sorted.end());
  stats.median = sorted[middle];
  if (sorted.size() % 2 == 0) {
    const double lower = *std::max_element(sorted.begin(), sorted.begin() + middle);
    stats.median = 0.5 * (stats.median + lower);
  }
  return stats;
}

}  // namespace lumaslam::eval
