#include "lumaslam/eval/alignment.h"

#include <cmath>

#include <spdlog/spdlog.h>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "lumaslam/core/error.h"

namespace lumaslam::eval {

namespace {

Eigen::Matrix3Xd positions(const Trajectory& trajectory) {
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(trajectory.size()));
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    points.col(static_cast<Eigen::Index>(i)) = trajectory[i].T_w_c.translation();
  }
  return points;
}

}  // namespace

AlignMode parseAlignMode(std::string_view name) {
  if (name == "none") return AlignMode::None;
  if (name == "se3") return AlignMode::SE3;
  if (name == "sim3") return AlignMode::Sim3;
  fail("alignment mode '{}' is not one of none, se3, sim3", name);
}

std::string toString(AlignMode mode) {
  switch (mode) {
    case AlignMode::None:
      return "none";
    case AlignMode::SE3:
      return "se3";
    case AlignMode::Sim3:
      return "sim3";
  }
  return "unknown";
}

SE3 Alignment::apply(const SE3& T_w_c) const {
  SE3 aligned = SE3::Identity();
  aligned.linear() = R * T_w_c.linear();
  aligned.translation() = apply(Eigen::Vector3d(T_w_c.translation()));
  return aligned;
}

Trajectory Alignment::apply(const Trajectory& trajectory) const {
  Trajectory aligned = trajectory;
  for (StampedPose& pose : aligned) pose.T_w_c = apply(pose.T_w_c);
  return aligned;
}

Alignment align(const Trajectory& estimate, const Trajectory& ground_truth, AlignMode mode) {
  if (estimate.size() != ground_truth.size()) {
    fail("alignment: {} estimate poses but {} ground-truth poses (associate them first)",
         estimate.size(), ground_truth.size());
  }
  Alignment alignment;
  alignment.mode = mode;
  if (mode == AlignMode::None) return alignment;
  if (estimate.size() < 3) {
    fail("alignment ({}): needs at least 3 matched poses, got {}", toString(mode), estimate.size());
  }

  const Eigen::Matrix3Xd source = positions(estimate);
  const Eigen::Matrix3Xd target = positions(ground_truth);
  const Eigen::Matrix3Xd centred = source.colwise() - source.rowwise().mean();
  const Eigen::Vector3d spread =
      Eigen::JacobiSVD<Eigen::Matrix3d>(centred * centred.transpose()).singularValues();
  if (mode == AlignMode::Sim3 && !(spread(0) > 1e-18)) {
    fail(
        "alignment (sim3): the {} matched estimate positions are all the same point, so "
        "the scale is undefined",
        estimate.size());
  }
  if (spread(1) <= 1e-12 * spread(0)) {
    spdlog::warn(
        "alignment ({}): the matched estimate positions lie on a line; the rotation about it "
        "is undetermined",
        toString(mode));
  }

  const Eigen::Matrix4d transform = Eigen::umeyama(source, target, mode == AlignMode::Sim3);
  if (!transform.allFinite()) fail("alignment ({}): Umeyama's method failed", toString(mode));
  const Eigen::Matrix3d sR = transform.topLeftCorner<3, 3>();
  alignment.scale = mode == AlignMode::Sim3 ? std::cbrt(sR.determinant()) : 1.0;
  alignment.R = sR / alignment.scale;
  alignment.t = transform.topRightCorner<3, 1>();
  return alignment;
}

}  // namespace lumaslam::eval
