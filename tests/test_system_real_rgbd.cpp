// Real Kinect v1 RGB-D (7-Scenes redkitchen in ../shared/data, registered depth, KinectFusion
// poses): tracking must not reject the first frame after initialisation when the hand-held
// camera has already turned several degrees (the TUM fr1 case of issue 15: the motion model
// has no velocity yet and the last pose's search window is far too small).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include <gtest/gtest.h>

#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/io/tum_rgbd_reader.h"
#include "lumaslam/pipeline.h"
#include "test_paths.h"

namespace lumaslam {
namespace {

std::filesystem::path redKitchen() {
  return test::dataDir() / "7scenes_redkitchen";
}

// Frames `indices` of the sequence (ascending), as the reader delivers them.
std::map<std::size_t, io::FrameData> readFrames(const std::vector<std::size_t>& indices) {
  io::ReaderOptions options;
  options.first_frame = indices.front();
  options.max_frames = indices.back() - indices.front() + 1;
  auto reader = io::openDataset("tum:" + redKitchen().string(), options);
  std::map<std::size_t, io::FrameData> frames;
  while (auto frame = reader->next()) {
    if (std::find(indices.begin(), indices.end(), frame->index) != indices.end()) {
      frames.emplace(frame->index, std::move(*frame));
    }
  }
  return frames;
}

double rotationDegrees(const SE3& T) {
  const double c = std::clamp((T.linear().trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

struct FirstFrameCase {
  std::size_t init;
  std::size_t next;
};

class RealRgbdFirstFrame : public ::testing::TestWithParam<FirstFrameCase> {};

// Pairs where the full 30 Hz run agrees with the ground truth's relative motion to < 1 cm (in
// the fastest stretch, frames 180-216, the two differ by 3-5 cm whatever tracks them: Kinect v1
// colour and depth are not synchronised). Measured (sequential, default settings; logged below;
// the same on 2026-12-04):
//   120 -> 132 (5.3 deg, 10 cm): 9.1 mm, 0.49 deg, 171 inliers
//   120 -> 136 (5.7 deg, 13 cm): 9.1 mm, 0.54 deg, 175 inliers
//   340 -> 356 (4.7 deg, 11 cm): 0.2 mm, 0.18 deg, 204 inliers
// Before the reference-keyframe fallback the first two were lost (the last pose's 14 px search
// window); bounds: ~2x the larger error.
TEST_P(RealRgbdFirstFrame, IsTrackedAfterAFastTurn) {
  const auto [init, next] = GetParam();
  auto frames = readFrames({init, next});
  ASSERT_EQ(frames.size(), 2U);
  const auto settings = io::loadSettings(redKitchen() / "settings.yaml");
  PipelineOptions options;
  options.sequential = true;
  Pipeline system(settings, options);
  const auto first = system.track(toSensorFrame(frames.at(init)));
  ASSERT_EQ(first.outcome.state, track::TrackingState::Ok);
  const auto second = system.track(toSensorFrame(frames.at(next)));
  ASSERT_EQ(second.outcome.state, track::TrackingState::Ok) << second.outcome.inliers << " inliers";
  EXPECT_GE(second.outcome.inliers, 100);

  const auto truth = io::TumRgbdReader::readGroundTruth(redKitchen());
  const SE3 true_motion = truth.at(init).T_w_c.inverse() * truth.at(next).T_w_c;
  const SE3 motion = first.outcome.T_w_c->inverse() * *second.outcome.T_w_c;
  ASSERT_GT(rotationDegrees(true_motion), 4.0);  // the case is a fast turn
  const SE3 error = true_motion.inverse() * motion;
  std::printf("%zu -> %zu: %.1f mm, %.2f deg, %d inliers\n", init, next,
              1000.0 * error.translation().norm(), rotationDegrees(error), second.outcome.inliers);
  EXPECT_LT(error.translation().norm(), 0.02);
  EXPECT_LT(rotationDegrees(error), 1.1);
}

// A blackout while the hand-held camera keeps moving (frames 121-140 dark: 20 frames, 0.7 s,
// ~6 deg and 12 cm): the frames are reported lost with their own (zero) inliers, and tracking
// comes back at the first real frame by matching the last reference keyframe's points, with no
// vocabulary. Before: the lost frames kept reporting the last tracked frame's inliers, and the
// 40 px window around the last pose did not reach.
TEST(RealRgbdRecovery, AfterABlackoutWithoutAVocabulary) {
  std::vector<std::size_t> indices;
  for (std::size_t i = 100; i <= 145; ++i) indices.push_back(i);
  auto frames = readFrames(indices);
  ASSERT_EQ(frames.size(), indices.size());
  const auto settings = io::loadSettings(redKitchen() / "settings.yaml");
  PipelineOptions options;
  options.sequential = true;
  options.vocabulary = "none";  // what recovers here must be the tracker's own fallback
  Pipeline system(settings, options);
  ASSERT_EQ(system.placeRecognition(), nullptr);
  std::optional<std::size_t> recovered;
  for (auto& [index, frame] : frames) {
    const bool dark = index > 120 && index <= 140;
    if (dark) frame.image.setTo(cv::Scalar::all(3));
    const auto result = system.track(toSensorFrame(frame));
    if (index <= 120) {
      ASSERT_EQ(result.outcome.state, track::TrackingState::Ok) << "frame " << index;
    } else if (dark) {
      ASSERT_EQ(result.outcome.state, track::TrackingState::Lost) << "frame " << index;
      EXPECT_EQ(result.outcome.inliers, 0) << "frame " << index;
    } else if (!recovered && result.outcome.state == track::TrackingState::Ok) {
      recovered = index;
    }
  }
  ASSERT_TRUE(recovered.has_value());
  EXPECT_EQ(*recovered, 141U);
}

INSTANTIATE_TEST_SUITE_P(SevenScenes, RealRgbdFirstFrame,
                         ::testing::Values(FirstFrameCase{120, 132}, FirstFrameCase{120, 136},
                                           FirstFrameCase{340, 356}),
                         [](const auto& info) {
                           return "frame" + std::to_string(info.param.init) + "to" +
                                  std::to_string(info.param.next);
                         });

}  // namespace
}  // namespace lumaslam
