// The tracker's fast path: on a smooth sequence nearly every frame is tracked by the motion
// model (ORB-SLAM's TrackWithMotionModel), the reference keyframe and the last-pose window
// being fallbacks. Without this test, dropping the motion model went unnoticed by every
// accuracy test (`make test-strength`): the fallbacks kept the poses, at a higher cost.
// Sequential mapping (deterministic). Measured: xyz-rgbd 60 frames, seed 1: 58 of the 59
// frames after initialisation by the motion model, 1 by the reference keyframe (the first).
#include <map>

#include <gtest/gtest.h>

#include "test_system_run.h"

namespace lumaslam {
namespace {

std::map<track::TrackingStep, int> stepsOf(const std::string& preset, int frames) {
  const synth::SequenceRenderer sequence(synth::findPreset(preset), frames, 1);
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  Pipeline system(test::presetSettings(sequence), options);
  std::map<track::TrackingStep, int> steps;
  for (int i = 0; i < frames; ++i) {
    ++steps[system.track(test::sensorFrame(sequence.render(i))).outcome.step];
  }
  for (const auto& [step, count] : steps) std::printf("%s: %d\n", track::toString(step), count);
  return steps;
}

TEST(TrackingSteps, TheMotionModelTracksASmoothSequence) {
  constexpr int kFrames = 60;
  auto steps = stepsOf("xyz-rgbd", kFrames);
  EXPECT_EQ(steps[track::TrackingStep::Initialization], 1);
  EXPECT_EQ(steps[track::TrackingStep::None], 0);
  // The first frame after initialisation has no velocity: the reference keyframe tracks it.
  EXPECT_GE(steps[track::TrackingStep::ReferenceKeyFrame], 1);
  EXPECT_GE(steps[track::TrackingStep::MotionModel], (kFrames - 1) * 9 / 10);
}

}  // namespace
}  // namespace lumaslam
