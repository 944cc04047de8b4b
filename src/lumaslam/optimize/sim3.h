#pragma once
// A similarity transform S = (s, R, t) acting as X -> s R X + t: the monocular pose of a
// keyframe whose map scale has drifted (ORB-SLAM's Sim3 for loop closing). S_c_w converts back
// to a rigid pose as T_c_w = (R, t / s).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lumaslam/core/pose.h"

namespace lumaslam::optimize {

struct Sim3 {
  double scale = 1.0;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  static Sim3 fromSE3(const SE3& T, double scale = 1.0) {
    return {scale, Eigen::Quaterniond(T.linear()), scale * T.translation()};
  }
  // The rigid pose with the scale divided out of the translation.
  SE3 toSE3() const {
    SE3 T = SE3::Identity();
    T.linear() = rotation.toRotationMatrix();
    T.translation() = translation / scale;
    return T;
  }
  Eigen::Vector3d operator*(const Eigen::Vector3d& X) const {
    return scale * (rotation * X) + translation;
  }
  Sim3 operator*(const Sim3& other) const {
    return {scale * other.scale, rotation * other.rotation,
            scale * (rotation * other.translation) + translation};
  }
  Sim3 inverse() const {
    const Eigen::Quaterniond inv = rotation.conjugate();
    return {1.0 / scale, inv, -(inv * translation) / scale};
  }
};

}  // namespace lumaslam::optimize
