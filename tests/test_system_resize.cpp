// Camera.newWidth / Camera.newHeight (issue 22: documented and parsed, but only the intrinsics
// were scaled, so a file with them tracked full-size images with half-size intrinsics): the
// Pipeline resizes every image of the calibrated size to the working size, as ORB-SLAM3 does.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include <opencv2/imgproc.hpp>

#include "test_system_run.h"

namespace lumaslam {
namespace {

int keyValue(const std::string& yaml, const std::string& key) {
  std::smatch match;
  const std::regex line(key + ": *([0-9]+)");
  EXPECT_TRUE(std::regex_search(yaml, match, line)) << key;
  return std::stoi(match[1]);
}

// The generator's settings with the working size at half the image size.
std::string atHalfSize(std::string yaml) {
  const int width = keyValue(yaml, "Camera.width");
  const int height = keyValue(yaml, "Camera.height");
  return yaml + "\nCamera.newWidth: " + std::to_string(width / 2) +
         "\nCamera.newHeight: " + std::to_string(height / 2) + "\n";
}

cv::Mat resized(const cv::Mat& image, const camera::ImageSize& size, int interpolation) {
  cv::Mat out;
  cv::resize(image, out, cv::Size(size.width, size.height), 0.0, 0.0, interpolation);
  return out;
}

// The oracle: the same frames resized by the test and tracked with a calibration written for
// the small images (no newWidth) give the very same poses (sequential runs are deterministic).
TEST(SystemResize, NewWidthTracksAsImagesResizedBeforehand) {
  constexpr int kFrames = 40;
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), kFrames, 1);
  const io::Settings resizing = test::presetSettings(sequence, atHalfSize);
  ASSERT_TRUE(resizing.camera.resizeTo.has_value());
  io::Settings small = resizing;
  small.camera = resizing.camera.atWorkingSize();
  PipelineOptions options;
  options.sequential = true;
  options.enhance_preset = "off";
  Pipeline by_settings(resizing, options);
  Pipeline by_hand(small, options);
  for (int i = 0; i < kFrames; ++i) {
    const SensorFrame input = test::sensorFrame(sequence.render(i));
    SensorFrame small_input = input;
    small_input.image = resized(input.image, small.camera.size, cv::INTER_LINEAR);
    small_input.depth = resized(input.depth, small.camera.size, cv::INTER_NEAREST);
    const auto a = by_settings.track(input);
    const auto b = by_hand.track(small_input);
    ASSERT_EQ(a.outcome.state, b.outcome.state) << "frame " << i;
    EXPECT_EQ(a.feature_image.size(), b.feature_image.size());
  }
  const auto poses_a = by_settings.frameTrajectory();
  const auto poses_b = by_hand.frameTrajectory();
  ASSERT_EQ(poses_a.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(poses_a.size(), poses_b.size());
  for (std::size_t i = 0; i < poses_a.size(); ++i) {
    EXPECT_EQ(poses_a[i].T_w_c.matrix(), poses_b[i].T_w_c.matrix()) << "frame " << i;
  }
}

TEST(SystemResize, HalfSizeRgbdTracksEveryFrame) {
  test::RunConfig half_size;
  half_size.edit = atHalfSize;
  const auto half = test::runOnPreset("xyz-rgbd", 100, 1, half_size);
  EXPECT_EQ(half.tracked, 100U);
  // ~2x the measured ATE (issue 22): 10.54 mm at half size (sequential; 2026-12-08,
  // `build/tests/test_system_resize --gtest_filter=*HalfSize*`, runOnPreset's log line; 11.5 mm
  // on 2026-12-04), 3.0 mm at full size: coarser pixels, and the full-size tests hold the
  // full-size bound.
  EXPECT_LE(half.report.ate.stats.rmse, 0.021);
}

}  // namespace
}  // namespace lumaslam
