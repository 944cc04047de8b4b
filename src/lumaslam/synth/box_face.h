#pragma once
// Face geometry shared by scene building and lightmap baking, see BoxInstance.
#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace lumaslam::synth {

// Size in metres of a face's texture: (u extent, v extent), see BoxInstance.
inline cv::Size2f faceSize(const Eigen::Vector3f& size, int face) {
  switch (face / 2) {
    case 0:
      return {size.y(), size.z()};
    case 1:
      return {size.x(), size.z()};
    default:
      return {size.x(), size.y()};
  }
}

}  // namespace lumaslam::synth
