#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/dataset_reader.h"
#include "test_paths.h"
#include "test_system_run.h"

namespace {

using namespace lumaslam;

// The generator's rectified-rig settings as a PinHole camera 1 without Stereo.T_c1_c2, for a
// test to describe its own rig.
std::string asPinHoleWithoutPose(const std::string& yaml) {
  const std::string pinhole = std::regex_replace(yaml, std::regex("Camera.type: \"Rectified\""),
                                                 "Camera.type: \"PinHole\"");
  return std::regex_replace(pinhole, std::regex("Stereo.T_c1_c2: !!opencv-matrix\n(  .*\n)+"), "");
}

TEST(SystemStereo, TracksSyntheticStereoWithXyzMotion) {
  const auto run = test::runOnPreset("xyz-stereo", 150, 1);
  EXPECT_EQ(run.tracked, run.frames);
  // ~2x the measured ATE (issue 22): 3.0 mm (sequential, deterministic; logged by runOnPreset).
  EXPECT_LE(run.report.ate.stats.rmse, 0.006);
  EXPECT_GT(run.keyframes, 1U);
}

// A rig whose two cameras are both turned by 8 degrees from the row-aligned synthetic one (the
// raw images are the rendered ones warped by K Q K^-1): the rectifier has to turn them back,
// and the trajectory must come out for the turned camera 1, not for the rectified one.
TEST(SystemStereo, ReportsPosesOfTheCalibratedCameraOfARotatedRig) {
  const int frames = 60;
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-stereo"), frames, 1);
  const auto& cam = sequence.rig().camera;
  const Eigen::Matrix3d Q =
      (Eigen::AngleAxisd(8.0 * M_PI / 180.0, Eigen::Vector3d(0.3, 1.0, 0.2).normalized()))
          .toRotationMatrix();  // p_c = Q p_rendered
  Eigen::Matrix3d K;
  K << cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1;
  const Eigen::Matrix3d H = K * Q * K.inverse();
  cv::Mat H_cv(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H_cv.at<double>(r, c) = H(r, c);
  const Eigen::Vector3d t = Q * Eigen::Vector3d(sequence.rig().baseline_m, 0, 0);
  const auto rotated_rig = [&](std::string yaml) {
    yaml = std::regex_replace(asPinHoleWithoutPose(yaml), std::regex("Stereo.b: .*\n"), "");
    yaml = std::regex_replace(yaml, std::regex("Camera.bf: .*\n"), "");
    return yaml + fmt::format(
                      "Camera2.fx: {}\nCamera2.fy: {}\nCamera2.cx: {}\nCamera2.cy: {}\n"
                      "Stereo.T_c1_c2: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: d\n"
                      "  data: [1, 0, 0, {}, 0, 1, 0, {}, 0, 0, 1, {}, 0, 0, 0, 1]\n",
                      cam.fx, cam.fy, cam.cx, cam.cy, t.x(), t.y(), t.z());
  };
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  Pipeline system(test::presetSettings(sequence, rotated_rig), options);

  std::vector<SE3> truth;  // T_w_c1 of the turned camera 1
  SE3 T_rendered_c1 = SE3::Identity();
  T_rendered_c1.linear() = Q.transpose();
  for (int i = 0; i < frames; ++i) {
    const auto frame = sequence.render(i);
    auto input = test::sensorFrame(frame);
    cv::warpPerspective(frame.cam0.image, input.image, H_cv, frame.cam0.image.size());
    cv::warpPerspective(frame.cam1->image, input.right, H_cv, frame.cam1->image.size());
    system.track(input);
    truth.push_back(frame.cam0.T_w_c * T_rendered_c1);
  }
  system.shutdown();
  const auto trajectory = system.frameTrajectory();
  ASSERT_EQ(trajectory.size(), static_cast<std::size_t>(frames));
  // Motion relative to the first frame, in camera 1's first frame: no alignment needed. Left in
  // the rectified camera it would be off by the ~8 degree turn (several cm here).
  double worst_position = 0.0;
  double worst_angle = 0.0;
  for (int i = 0; i < frames; ++i) {
    const SE3 estimated = trajectory.front().T_w_c.inverse() * trajectory[i].T_w_c;
    const SE3 expected = truth.front().inverse() * truth[i];
    worst_position =
        std::max(worst_position, (estimated.translation() - expected.translation()).norm());
    worst_angle = std::max(
        worst_angle, Eigen::AngleAxisd(estimated.linear().transpose() * expected.linear()).angle());
  }
  spdlog::info("rotated rig: worst position error {:.4f} m, worst angle {:.3f} deg", worst_position,
               worst_angle * 180.0 / M_PI);
  // ~2x the measured errors (issue 22; sequential, deterministic; logged above): 6.6 mm (the
  // 1 cm bound was already within 2x) and 0.110 deg.
  EXPECT_LT(worst_position, 0.01);
  EXPECT_LT(worst_angle * 180.0 / M_PI, 0.22);
}

// EuRoC V1_01 starts with the MAV at rest on the floor: an unrectified pair with real
// calibration, which the Pipeline rectifies before tracking.
TEST(SystemStereo, RealEurocAtRestTracksEveryFrameWithoutDrift) {
  const auto root = test::dataDir() / "euroc" / "V1_01_easy_micro";
  ASSERT_TRUE(std::filesystem::exists(root))
      << root << " is missing: the shared data is a required test input (LUMASLAM_SHARED_DIR)";
  const auto settings = io::loadSettings(test::sourceDir() / "configs" / "euroc_stereo.yaml");
  ASSERT_TRUE(settings.stereo && settings.stereo->right);
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  Pipeline system(settings, options);
  // Tracking runs in the rectified camera: no distortion, bf from the rectified baseline.
  EXPECT_FALSE(system.frameCamera().pinhole.hasDistortion());
  EXPECT_NEAR(system.frameCamera().bf / system.frameCamera().pinhole.fx(), 0.110, 0.002);

  auto reader = io::openDataset("euroc:" + root.string());
  std::size_t frames = 0;
  std::size_t tracked = 0;
  while (auto frame = reader->next()) {
    const auto result = system.track(toSensorFrame(*frame));
    ++frames;
    if (result.outcome.state == track::TrackingState::Ok) ++tracked;
  }
  system.shutdown();
  EXPECT_EQ(frames, 95U);
  EXPECT_EQ(tracked, frames);
  const auto trajectory = system.frameTrajectory();
  ASSERT_EQ(trajectory.size(), frames);
  double drift = 0.0;
  for (const auto& pose : trajectory) {
    drift =
        std::max(drift, (pose.T_w_c.translation() - trajectory.front().T_w_c.translation()).norm());
  }
  // ~2x the measured drift (issue 22): 2.8 mm (sequential, deterministic; logged below).
  EXPECT_LE(drift, 0.006);
  spdlog::info("EuRoC V1_01 micro: {}/{} tracked, {} keyframes, drift {:.4f} m", tracked, frames,
               system.keyFrameCount(), drift);
}

TEST(SystemStereo, MissingOrMismatchedRightImageIsAClearError) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-stereo"), 1, 1);
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  Pipeline system(test::presetSettings(sequence), options);
  auto input = test::sensorFrame(sequence.render(0));

  auto without_right = input;
  without_right.right = cv::Mat();
  // A missing right image is an error.
  const std::string message = test::errorOf([&] { system.track(without_right); });
  EXPECT_NE(message.find("right image"), std::string::npos) << message;
  auto smaller_right = input;
  cv::resize(input.right, smaller_right.right, cv::Size(), 0.5, 0.5);
  EXPECT_THROW(system.track(smaller_right), Error);
  auto gray_right = input;
  cv::cvtColor(input.right, gray_right.right, cv::COLOR_BGR2GRAY);
  EXPECT_THROW(system.track(gray_right), Error);

  auto wrong_mask = input;
  wrong_mask.dynamic_mask = cv::Mat::zeros(10, 10, CV_8UC1);
  EXPECT_THROW(system.track(wrong_mask), Error);

  // After the errors, a good frame still initialises the map.
  const auto result = system.track(input);
  EXPECT_EQ(result.outcome.state, track::TrackingState::Ok);
  EXPECT_GT(system.mapPointCount(), 300U);
}

TEST(SystemStereo, DistortedPairWithoutSecondCalibrationIsRejected) {
  // A PinHole pair with only camera 1 and Stereo.b is taken as rectified (ORB-SLAM2 files):
  // with distortion, its rows cannot agree, so the Pipeline refuses it.
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-stereo"), 1, 1);
  const auto distorted = [](std::string yaml) {
    return std::regex_replace(asPinHoleWithoutPose(yaml), std::regex("Camera.k1: 0.0"),
                              "Camera.k1: -0.28");
  };
  // A distorted pair without Camera2.* is an error.
  const std::string message =
      test::errorOf([&] { Pipeline system(test::presetSettings(sequence, distorted)); });
  EXPECT_NE(message.find("distortion"), std::string::npos) << message;
}

}  // namespace
