#pragma once
// Absolute trajectory error: the translation part of evo's APE, |p_gt,i - p_est,i| for
// every associated (and already aligned) pose pair.
#include <vector>

#include "lumaslam/core/pose.h"
#include "lumaslam/eval/error_stats.h"

namespace lumaslam::eval {

struct AbsoluteTrajectoryError {
  ErrorStats stats;                // metres
  std::vector<double> timestamps;  // ground-truth stamp of each pair
  std::vector<double> errors;      // metres, one per pair
};

// Inputs are associated pose for pose; throws Error when sizes differ or both are empty.
AbsoluteTrajectoryError computeAte(const Trajectory& aligned_estimate,
                                   const Trajectory& ground_truth);

}  // namespace lumaslam::eval
