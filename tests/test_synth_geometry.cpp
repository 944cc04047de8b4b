// Geometry consistency of the synthetic frames with their ground truth: warping one frame
// into another with its depth and the GT relative pose must reproduce the image.
#include <gtest/gtest.h>

#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "lumaslam/synth/sequence.h"

using namespace lumaslam::synth;
using lumaslam::SE3;

namespace {

struct WarpResult {
  double mean_abs_error = 0.0;  // grey levels, over static, unoccluded, in-view pixels
  double used_fraction = 0.0;
};

// Predicts `target` from `source`: each static target pixel is back-projected with the target
// depth, moved by T_source_target and looked up (bilinearly) in the source image.
WarpResult warpError(const CameraFrame& source, const CameraFrame& target, const PinholeCamera& cam,
                     const SE3& T_source_target) {
  cv::Mat map_x(target.depth.size(), CV_32F), map_y(target.depth.size(), CV_32F);
  cv::Mat expected_depth(target.depth.size(), CV_32F);
  for (int y = 0; y < target.depth.rows; ++y)
    for (int x = 0; x < target.depth.cols; ++x) {
      const double z = target.depth.at<float>(y, x);
      const Eigen::Vector3d X = T_source_target * Eigen::Vector3d((x - cam.cx) / cam.fx * z,
                                                                  (y - cam.cy) / cam.fy * z, z);
      map_x.at<float>(y, x) = static_cast<float>(cam.fx * X.x() / X.z() + cam.cx);
      map_y.at<float>(y, x) = static_cast<float>(cam.fy * X.y() / X.z() + cam.cy);
      expected_depth.at<float>(y, x) = static_cast<float>(X.z());
    }
  cv::Mat source_gray, target_gray, predicted, source_depth_at;
  cv::cvtColor(source.image, source_gray, cv::COLOR_BGR2GRAY);
  cv::cvtColor(target.image, target_gray, cv::COLOR_BGR2GRAY);
  cv::remap(source_gray, predicted, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  cv::remap(source.depth, source_depth_at, map_x, map_y, cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);
  double sum = 0.0;
  int used = 0;
  for (int y = 0; y < target.depth.rows; ++y)
    for (int x = 0; x < target.depth.cols; ++x) {
      const float u = map_x.at<float>(y, x), v = map_y.at<float>(y, x);
      if (u < 2 || v < 2 || u > cam.width - 3 || v > cam.height - 3) continue;
      if (target.mask.at<std::uint8_t>(y, x) ||
          source.mask.at<std::uint8_t>(cvRound(v), cvRound(u)))
        continue;
      const float expected = expected_depth.at<float>(y, x);
      if (std::abs(source_depth_at.at<float>(y, x) - expected) > 0.01f * expected)
        continue;  // occluded
      sum += std::abs(static_cast<double>(predicted.at<std::uint8_t>(y, x)) -
                      target_gray.at<std::uint8_t>(y, x));
      ++used;
    }
  return {used ? sum / used : 1e9, used / static_cast<double>(target.depth.total())};
}

SynthOptions cleanOptions() {
  SynthOptions options;
  options.motion_blur = false;
  options.sensor_noise = false;
  return options;
}

}  // namespace

TEST(SynthGeometry, GroundTruthPoseAndDepthWarpFramesOntoEachOther) {
  // Walkers included: their pixels are masked out, everything else must agree.
  const Preset& preset = findPreset("walking-xyz-rgbd");
  const SequenceRenderer sequence(preset, 120, 21, cleanOptions());
  const PinholeCamera& cam = sequence.rig().camera;
  for (const auto& [a, b] : {std::pair{10, 16}, std::pair{40, 55}, std::pair{90, 81}}) {
    const Frame fa = sequence.render(a), fb = sequence.render(b);
    const SE3 T_a_b = fa.cam0.T_w_c.inverse() * fb.cam0.T_w_c;
    const WarpResult right = warpError(fa.cam0, fb.cam0, cam, T_a_b);
    EXPECT_GT(right.used_fraction, 0.3) << a << "->" << b;
    EXPECT_LT(right.mean_abs_error, 5.0) << a << "->" << b;  // resampling only
    std::printf("warp %d->%d: error %.2f grey levels over %.0f%% of the pixels\n", a, b,
                right.mean_abs_error, 100.0 * right.used_fraction);
    // A pose that is off by 2 cm / 0.5 degrees must be clearly worse.
    SE3 wrong = T_a_b;
    wrong.translation() += Eigen::Vector3d(0.02, 0.0, 0.0);
    wrong.linear() =
        wrong.linear() *
        Eigen::AngleAxisd(0.5 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    EXPECT_GT(warpError(fa.cam0, fb.cam0, cam, wrong).mean_abs_error, 2.0 * right.mean_abs_error);
  }
}

TEST(SynthGeometry, WarpErrorWithNoiseStaysNearTheNoiseLevel) {
  const Preset& preset = findPreset("xyz-rgbd");
  SynthOptions options = cleanOptions();
  options.sensor_noise = true;
  const SequenceRenderer sequence(preset, 60, 8, options);
  const Frame fa = sequence.render(20), fb = sequence.render(24);
  // The noise level: two renders of the same view differ only by noise (other frame index).
  const SequenceRenderer clean(preset, 60, 8, cleanOptions());
  cv::Mat noisy_gray, clean_gray, diff;
  cv::cvtColor(fb.cam0.image, noisy_gray, cv::COLOR_BGR2GRAY);
  cv::cvtColor(clean.render(24).cam0.image, clean_gray, cv::COLOR_BGR2GRAY);
  cv::absdiff(noisy_gray, clean_gray, diff);
  const double noise_mad = cv::mean(diff)[0];
  EXPECT_GT(noise_mad, 0.3);
  std::printf("noise: mean abs difference %.2f grey levels\n", noise_mad);
  const WarpResult result =
      warpError(fa.cam0, fb.cam0, sequence.rig().camera, fa.cam0.T_w_c.inverse() * fb.cam0.T_w_c);
  EXPECT_LT(result.mean_abs_error, 2.0 * noise_mad + 3.0);
  std::printf("warp with noise: %.2f grey levels\n", result.mean_abs_error);
}

TEST(SynthGeometry, StereoPairIsConsistentWithBaseline) {
  const SequenceRenderer sequence(findPreset("loop-stereo"), 100, 3, cleanOptions());
  const Frame frame = sequence.render(30);
  const SE3 T_left_right = frame.cam0.T_w_c.inverse() * frame.cam1->T_w_c;
  const WarpResult result = warpError(frame.cam0, *frame.cam1, sequence.rig().camera, T_left_right);
  EXPECT_GT(result.used_fraction, 0.5);
  EXPECT_LT(result.mean_abs_error, 4.0);
}

TEST(SynthGeometry, LoopEndsWhereItStartedAndSpeedsAreHandHeld) {
  const Preset& loop = findPreset("loop-stereo");
  const SequenceRenderer sequence(loop, loop.frames, 1);
  const double t0 = sequence.timestampNs(0) * 1e-9;
  const double duration = loop.frames / sequence.rig().fps;
  const SE3 start = sequence.poseAt(t0), end = sequence.poseAt(t0 + duration);
  EXPECT_LT((start.translation() - end.translation()).norm(), 0.01);
  EXPECT_LT(Eigen::AngleAxisd(start.linear().transpose() * end.linear()).angle(), 0.01);
  for (const char* name :
       {"xyz-rgbd", "rpy-rgbd", "halfsphere-rgbd", "static-rgbd", "loop-stereo"}) {
    const Preset& preset = findPreset(name);
    const SequenceRenderer s(preset, preset.frames, 2);
    const double begin = s.timestampNs(0) * 1e-9, dt = 1.0 / s.rig().fps;
    double max_speed = 0.0, max_rate_deg = 0.0, path = 0.0;
    for (int i = 0; i + 1 < preset.frames; ++i) {
      const SE3 a = s.poseAt(begin + i * dt), b = s.poseAt(begin + (i + 1) * dt);
      const double step = (b.translation() - a.translation()).norm();
      path += step;
      max_speed = std::max(max_speed, step / dt);
      max_rate_deg =
          std::max(max_rate_deg, Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() /
                                     dt * 180.0 / M_PI);
    }
    const double mean_speed = path / (preset.frames * dt);
    SCOPED_TRACE(name);
    EXPECT_LT(max_speed, 0.8);
    EXPECT_LT(max_rate_deg, 120.0);
    if (std::string(name) == "static-rgbd") {
      EXPECT_LT(mean_speed, 0.02);
    } else if (std::string(name) == "rpy-rgbd") {
      EXPECT_GT(max_rate_deg, 40.0);
    } else {
      EXPECT_GT(mean_speed, 0.1);
    }
  }
}
