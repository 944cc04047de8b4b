#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/dataset_reader.h"
#include "test_paths.h"
#include "test_system_run.h"

namespace {

using namespace lumaslam;

TEST(SystemStereo, TracksSyntheticStereoWithXyzMotion) {
  const auto run = test::runOnPreset("xyz-stereo", 150, 1);
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LE(run.report.ate.stats.rmse, 0.02);
  EXPECT_GT(run.keyframes, 1U);
}

// The same rig described as an unrectified pair (Camera.type PinHole with Camera2.* and
// Stereo.T_c1_c2, as for EuRoC): the System rectifies it (cv::stereoRectify picks a new common
// K, so the images are resampled) and must still track the motion in the rectified camera.
TEST(SystemStereo, TracksSyntheticMotionThroughTheRectifier) {
  const auto as_unrectified = [](std::string yaml) {
    const std::string rectified = "Camera.type: \"Rectified\"";
    const auto at = yaml.find(rectified);
    if (at == std::string::npos) throw std::runtime_error("no Camera.type in the settings");
    yaml.replace(at, rectified.size(), "Camera.type: \"PinHole\"");
    return yaml +
           "Camera2.fx: 458.654\nCamera2.fy: 457.296\nCamera2.cx: 367.215\n"
           "Camera2.cy: 248.375\nCamera2.k1: 0.0\nCamera2.k2: 0.0\nCamera2.p1: 0.0\n"
           "Camera2.p2: 0.0\n";
  };
  const auto run = test::runOnPreset("xyz-stereo", 60, 1, as_unrectified);
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LE(run.report.ate.stats.rmse, 0.02);
}

// EuRoC V1_01 starts with the MAV at rest on the floor: an unrectified pair with real
// calibration, which the System rectifies before tracking.
TEST(SystemStereo, RealEurocAtRestTracksEveryFrameWithoutDrift) {
  const auto root = test::dataDir() / "euroc" / "V1_01_easy_micro";
  if (!std::filesystem::exists(root)) GTEST_SKIP() << "no " << root;
  const auto settings = io::loadSettings(test::sourceDir() / "configs" / "euroc_stereo.yaml");
  ASSERT_TRUE(settings.stereo && settings.stereo->right);
  SystemOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  System system(settings, options);
  // Tracking runs in the rectified camera: no distortion, bf from the rectified baseline.
  EXPECT_FALSE(system.frameCamera().hasDistortion());
  EXPECT_NEAR(system.frameCamera().bf / system.frameCamera().fx, 0.110, 0.002);

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
  EXPECT_LE(drift, 0.01);
  spdlog::info("EuRoC V1_01 micro: {}/{} tracked, {} keyframes, drift {:.4f} m", tracked, frames,
               system.keyFrameCount(), drift);
}

TEST(SystemStereo, MissingOrMismatchedRightImageIsAClearError) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-stereo"), 1, 1);
  SystemOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  System system(test::presetSettings(sequence), options);
  auto input = test::sensorFrame(sequence.render(0));

  auto without_right = input;
  without_right.right = cv::Mat();
  try {
    system.track(without_right);
    FAIL() << "no error for a missing right image";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("right image"), std::string::npos) << e.what();
  }
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
  // with distortion, its rows cannot agree, so the System refuses it.
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-stereo"), 1, 1);
  const auto distorted = [](std::string yaml) {
    yaml = std::regex_replace(yaml, std::regex("Camera.type: \"Rectified\""),
                              "Camera.type: \"PinHole\"");
    yaml = std::regex_replace(yaml, std::regex("Camera.k1: 0.0"), "Camera.k1: -0.28");
    return std::regex_replace(yaml, std::regex("Stereo.T_c1_c2: !!opencv-matrix\n(  .*\n)+"), "");
  };
  try {
    System system(test::presetSettings(sequence, distorted));
    FAIL() << "no error for a distorted pair without Camera2.*";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("distortion"), std::string::npos) << e.what();
  }
}

}  // namespace
