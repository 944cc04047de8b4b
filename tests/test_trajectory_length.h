#pragma once
// Distance travelled along a trajectory (sum of consecutive position differences): the
// denominator of "ATE as a percentage of the trajectory length".
#include "lumaslam/core/pose.h"

namespace lumaslam::test {

inline double pathLength(const Trajectory& trajectory) {
  double length = 0.0;
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    length += (trajectory[i].T_w_c.translation() - trajectory[i - 1].T_w_c.translation()).norm();
  }
  return length;
}

}  // namespace lumaslam::test
