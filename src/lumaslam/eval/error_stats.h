#pragma once
// Summary statistics of a list of errors, with the same definitions as evo
// (std is the population standard deviation, as numpy.std).
#include <cstddef>
#include <span>

namespace lumaslam::eval {

struct ErrorStats {
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double std = 0.0;
  double min = 0.0;
  double max = 0.0;
  std::size_t count = 0;
};

// Throws Error when `errors` is empty.
ErrorStats computeStats(std::span<const double> errors);

}  // namespace lumaslam::eval
