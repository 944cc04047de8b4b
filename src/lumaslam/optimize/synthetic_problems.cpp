#include "lumaslam/optimize/synthetic_problems.h"

#include <cmath>
#include <numbers>
#include <random>

#include "lumaslam/core/error.h"
#include "lumaslam/optimize/se3_parameter.h"

namespace lumaslam::optimize {

namespace {

Eigen::Vector3d randomUnitVector(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d v(normal(rng), normal(rng), normal(rng));
  return v.normalized();
}

SE3 perturbPose(const SE3& T, double translation, double rotationDeg, std::mt19937& rng) {
  SE3 delta = SE3::Identity();
  delta.linear() =
      expSO3(randomUnitVector(rng) * rotationDeg * std::numbers::pi / 180.0).toRotationMatrix();
  delta.translation() = randomUnitVector(rng) * translation;
  return delta * T;
}

// A keypoint measurement of a camera point with level-scaled noise, or a wrong match.
struct Keypoint {
  Eigen::Vector2d uv;
  double uRight = -1.0;
  double invSigma2 = 1.0;
  bool outlier = false;
};

Keypoint observe(const CameraIntrinsics& camera, const Eigen::Vector3d& P_c, bool stereo,
                 const SyntheticNoise& noise, std::mt19937& rng) {
  std::uniform_int_distribution<int> level(0, std::max(0, noise.pyramidLevels - 1));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double scale = std::pow(noise.pyramidScale, level(rng));
  std::normal_distribution<double> pixelNoise(0.0, noise.pixelSigma * scale);
  Keypoint kp;
  kp.invSigma2 = 1.0 / (scale * scale);
  const double u = camera.fx * P_c.x() / P_c.z() + camera.cx;
  const double v = camera.fy * P_c.y() / P_c.z() + camera.cy;
  kp.uv = {u + pixelNoise(rng), v + pixelNoise(rng)};
  if (stereo) kp.uRight = u - camera.bf / P_c.z() + pixelNoise(rng);
  if (unit(rng) < noise.outlierRatio) {
    // A wrong match: somewhere else in the image, far from the true projection.
    kp.outlier = true;
    do {
      kp.uv = {unit(rng) * kSyntheticImageWidth, unit(rng) * kSyntheticImageHeight};
    } while ((kp.uv - Eigen::Vector2d(u, v)).norm() < noise.minOutlierOffset);
    if (stereo) kp.uRight = std::max(0.0, kp.uv.x() - unit(rng) * 60.0);
  }
  return kp;
}

bool projectsIntoImage(const CameraIntrinsics& camera, const Eigen::Vector3d& P_c) {
  if (P_c.z() < 0.3) return false;
  const double u = camera.fx * P_c.x() / P_c.z() + camera.cx;
  const double v = camera.fy * P_c.y() / P_c.z() + camera.cy;
  return u >= 0.0 && u < kSyntheticImageWidth && v >= 0.0 && v < kSyntheticImageHeight;
}

}  // namespace

CameraIntrinsics syntheticCamera() {
  return {.fx = 458.0, .fy = 458.0, .cx = 367.0, .cy = 248.0, .bf = 0.11 * 458.0};
}

SE3 perturbPose(const SE3& T, double translation, double rotationDeg, std::uint32_t seed) {
  std::mt19937 rng(seed);
  return perturbPose(T, translation, rotationDeg, rng);
}

SyntheticPoseOnly makeSyntheticPoseOnly(const SyntheticPoseOnlySpec& spec) {
  if (spec.numObservations < 0) fail("synthetic pose-only: numObservations < 0");
  std::mt19937 rng(spec.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SyntheticPoseOnly out;
  out.problem.camera = syntheticCamera();
  const CameraIntrinsics& camera = out.problem.camera;
  out.T_c_w_true = perturbPose(SE3::Identity(), 1.0, 30.0, rng);
  const SE3 T_w_c = out.T_c_w_true.inverse();
  for (int i = 0; i < spec.numObservations; ++i) {
    // Uniform over the image, depth 1..10 m.
    const double u = unit(rng) * kSyntheticImageWidth;
    const double v = unit(rng) * kSyntheticImageHeight;
    const double z = 1.0 + 9.0 * unit(rng);
    const Eigen::Vector3d P_c((u - camera.cx) / camera.fx * z, (v - camera.cy) / camera.fy * z, z);
    const Keypoint kp = observe(camera, P_c, spec.stereo, spec.noise, rng);
    out.problem.observations.push_back(
        {.X_w = T_w_c * P_c, .uv = kp.uv, .uRight = kp.uRight, .invSigma2 = kp.invSigma2});
    out.isInjectedOutlier.push_back(kp.outlier);
  }
  out.problem.T_c_w =
      perturbPose(out.T_c_w_true, spec.initialTranslationError, spec.initialRotationErrorDeg, rng);
  return out;
}

SyntheticBundle makeSyntheticBundle(const SyntheticBundleSpec& spec) {
  if (spec.numKeyFrames < 1 || spec.numPoints < 1 || spec.numFixedKeyFrames < 0)
    fail("synthetic bundle: needs keyframes and points (got {} and {})", spec.numKeyFrames,
         spec.numPoints);
  std::mt19937 rng(spec.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  SyntheticBundle out;
  LocalBAProblem& problem = out.problem;
  problem.camera = syntheticCamera();

  // Keyframes every 20 cm along x, looking down +z, with a slight yaw wobble.
  for (int k = 0; k < spec.numKeyFrames; ++k) {
    SE3 T_w_c = SE3::Identity();
    T_w_c.linear() =
        expSO3(Eigen::Vector3d(0.02 * normal(rng), 0.05 * std::sin(0.7 * k), 0.02 * normal(rng)))
            .toRotationMatrix();
    T_w_c.translation() = Eigen::Vector3d(0.2 * k, 0.05 * std::sin(0.5 * k), 0.0);
    out.T_c_w_true.push_back(T_w_c.inverse());
  }
  // Points in a slab 3..9 m in front of the path, kept if enough keyframes see them.
  const double pathLength = 0.2 * (spec.numKeyFrames - 1);
  const int minObservations = std::min(spec.minObservations, spec.numKeyFrames);
  while (static_cast<int>(out.X_w_true.size()) < spec.numPoints) {
    const Eigen::Vector3d X_w(-2.5 + (pathLength + 5.0) * unit(rng), -1.8 + 3.6 * unit(rng),
                              3.0 + 6.0 * unit(rng));
    int seenBy = 0;
    for (const SE3& T_c_w : out.T_c_w_true)
      seenBy += projectsIntoImage(problem.camera, T_c_w * X_w);
    if (seenBy >= minObservations) out.X_w_true.push_back(X_w);
  }

  for (int k = 0; k < spec.numKeyFrames; ++k) {
    const bool fixed = k < spec.numFixedKeyFrames;
    const SE3 T_c_w = fixed ? out.T_c_w_true[k]
                            : perturbPose(out.T_c_w_true[k], spec.poseTranslationError,
                                          spec.poseRotationErrorDeg, rng);
    problem.keyFrames.push_back(
        {.id = static_cast<std::uint64_t>(100 + k), .T_c_w = T_c_w, .fixed = fixed});
  }
  for (int j = 0; j < spec.numPoints; ++j) {
    const Eigen::Vector3d offset(normal(rng), normal(rng), normal(rng));
    problem.points.push_back({.id = static_cast<std::uint64_t>(5000 + j),
                              .X_w = out.X_w_true[j] + spec.pointError * offset});
  }
  for (int k = 0; k < spec.numKeyFrames; ++k) {
    for (int j = 0; j < spec.numPoints; ++j) {
      const Eigen::Vector3d P_c = out.T_c_w_true[k] * out.X_w_true[j];
      if (!projectsIntoImage(problem.camera, P_c)) continue;
      const Keypoint kp = observe(problem.camera, P_c, spec.stereo, spec.noise, rng);
      problem.observations.push_back({.keyFrameId = problem.keyFrames[k].id,
                                      .pointId = problem.points[j].id,
                                      .uv = kp.uv,
                                      .uRight = kp.uRight,
                                      .invSigma2 = kp.invSigma2});
      out.isInjectedOutlier.push_back(kp.outlier);
    }
  }
  return out;
}

}  // namespace lumaslam::optimize
