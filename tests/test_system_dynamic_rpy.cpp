// Dynamic-object removal under fast rotation (issue 6, TUM fr3 walking_rpy's situation): on
// walking-rpy-rgbd the two walkers keep to the turning view, so without removal the tracker
// maps them and drifts; the box-file detector fed the generator's boxes cuts the error to a
// third at most, and below 1 cm.
#include <gtest/gtest.h>

#include "test_paths.h"
#include "test_system_dynamic.h"

namespace {

using namespace lumaslam;

TEST(SystemDynamicRpy, BoxRemovalCutsTheErrorOnWalkingRpy) {
  const synth::SequenceRenderer sequence(synth::findPreset("walking-rpy-rgbd"), 100, 1);
  test::TempDir dir("system_dynamic_rpy");
  test::GroundTruthBoxes truth;
  std::size_t frames_with_walkers = 0;
  PipelineOptions without_options;
  without_options.detector = "none";
  without_options.motion_evidence = false;  // box removal alone (issue 6)
  const auto without = test::runSynthetic(
      sequence, without_options, [&](const synth::Frame& frame, const FrameResult&) {
        truth.add(frame);
        if (cv::countNonZero(frame.cam0.mask) > 0.05 * static_cast<double>(frame.cam0.mask.total()))
          ++frames_with_walkers;
      });
  const auto boxes = dir.path() / "boxes.txt";
  truth.write(boxes);
  // The walkers stay in the turning view: at least 5% of the image on almost every frame.
  EXPECT_GE(frames_with_walkers, 95U);

  PipelineOptions with_options;
  with_options.detector = "boxes:" + boxes.string();
  with_options.motion_evidence = false;  // box removal alone (issue 6)
  const auto with = test::runSynthetic(sequence, with_options);
  EXPECT_EQ(with.tracked, with.frames);
  EXPECT_LE(with.ate(), without.ate() / 3.0) << "without " << without.ate();
  EXPECT_LE(with.ate(), 0.01);
}

}  // namespace
