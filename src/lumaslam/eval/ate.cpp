#include "lumaslam/eval/ate.h"

#include "lumaslam/core/error.h"

namespace lumaslam::eval {

AbsoluteTrajectoryError computeAte(const Trajectory& aligned_estimate,
                                   const Trajectory& ground_truth) {
  if (aligned_estimate.size() != ground_truth.size()) {
    fail("ATE: {} estimate poses but {} ground-truth poses (associate them first)",
         aligned_estimate.size(), ground_truth.size());
  }
  if (ground_truth.empty()) fail("ATE: no associated pose pairs");
  AbsoluteTrajectoryError ate;
  ate.timestamps.reserve(ground_truth.size());
  ate.errors.reserve(ground_truth.size());
  for (std::size_t i = 0; i < ground_truth.size(); ++i) {
    ate.timestamps.push_back(ground_truth[i].timestamp);
    ate.errors.push_back(
        (ground_truth[i].T_w_c.translation() - aligned_estimate[i].T_w_c.translation()).norm());
  }
  ate.stats = computeStats(ate.errors);
  return ate;
}

}  // namespace lumaslam::eval
