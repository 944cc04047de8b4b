#pragma once
// Synthetic trajectories with known geometry for the eval tests.
#include <cmath>
#include <cstddef>
#include <random>

#include <Eigen/Geometry>

#include "lumaslam/core/pose.h"

namespace lumaslam::test {

// A helix around z (radius 2 m, 1 turn per 10 s, rising 0.1 m/s), sampled every dt seconds
// from t0, camera looking along the tangent and rolling slowly, so every axis moves.
inline Trajectory helix(std::size_t poses, double dt = 0.05, double t0 = 1000.0) {
  Trajectory trajectory;
  const double omega = 2.0 * M_PI / 10.0;
  for (std::size_t i = 0; i < poses; ++i) {
    const double t = static_cast<double>(i) * dt;
    StampedPose pose;
    pose.timestamp = t0 + t;
    pose.T_w_c.translation() =
        Eigen::Vector3d(2.0 * std::cos(omega * t), 2.0 * std::sin(omega * t), 0.1 * t);
    pose.T_w_c.linear() = (Eigen::AngleAxisd(omega * t, Eigen::Vector3d::UnitZ()) *
                           Eigen::AngleAxisd(0.3 * std::sin(t), Eigen::Vector3d::UnitX()))
                              .toRotationMatrix();
    trajectory.push_back(pose);
  }
  return trajectory;
}

// A straight line along z at `speed` m/s, camera axes aligned with the world.
inline Trajectory straightLine(std::size_t poses, double speed, double dt = 0.1) {
  Trajectory trajectory;
  for (std::size_t i = 0; i < poses; ++i) {
    StampedPose pose;
    pose.timestamp = static_cast<double>(i) * dt;
    pose.T_w_c.translation() = Eigen::Vector3d(0.0, 0.0, speed * pose.timestamp);
    trajectory.push_back(pose);
  }
  return trajectory;
}

// Applies p -> s R p + t to positions and R to orientations (a similarity of the world frame).
inline Trajectory transformed(const Trajectory& trajectory, double s, const Eigen::Matrix3d& R,
                              const Eigen::Vector3d& t) {
  Trajectory result = trajectory;
  for (StampedPose& pose : result) {
    pose.T_w_c.translation() = s * R * pose.T_w_c.translation() + t;
    pose.T_w_c.linear() = R * pose.T_w_c.linear();
  }
  return result;
}

inline Trajectory withPositionNoise(const Trajectory& trajectory, double sigma, unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Trajectory result = trajectory;
  for (StampedPose& pose : result) {
    pose.T_w_c.translation() +=
        Eigen::Vector3d(noise(generator), noise(generator), noise(generator));
  }
  return result;
}

inline Eigen::Matrix3d someRotation() {
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized())).toRotationMatrix();
}

}  // namespace lumaslam::test
