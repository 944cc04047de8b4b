// Monocular walking (issue 16): the rgb stream of walking-xyz-rgbd with walkers cut from real
// person photos, as a monocular camera, with YOLOv5n-320 and the motion test in the loop.
#include <gtest/gtest.h>

#include "test_paths.h"
#include "test_people.h"
#include "test_system_dynamic.h"

namespace {

using namespace lumaslam;

TEST(SystemDynamicMono, YoloAndMotionEvidenceKeepMonocularWalkingWithinTheIssueTarget) {
  synth::SynthOptions photo_walkers;
  photo_walkers.moving_boxes = 0;  // then the settings' Detector.classes is "person"
  photo_walkers.people = test::labelledPeople();
  const synth::SequenceRenderer sequence(synth::findPreset("walking-xyz-rgbd"), 100, 2,
                                         photo_walkers);
  PipelineOptions options;
  options.detector = "yolo:" + (test::modelsDir() / "yolov5n-320.onnx").string();
  options.motion_evidence = true;  // off by default for monocular
  std::size_t frames_with_drops = 0;
  const auto run = test::runSynthetic(
      sequence, options,
      [&](const synth::Frame&, const FrameResult& r) {
        if (!r.dropped_features.empty()) ++frames_with_drops;
      },
      /*extra_settings=*/"", io::SensorType::Monocular);
  EXPECT_EQ(run.report.alignment.mode, eval::AlignMode::Sim3);
  EXPECT_GT(frames_with_drops, 50U);  // YOLO sees the walkers most of the time
  EXPECT_GE(run.tracked, 85U);        // a monocular map starts after a few frames of parallax
  EXPECT_LE(run.ate(), 0.02);         // issue 16's target (Sim3 ATE)
  // ~2x the measured ATE (issue 22): 5.2 mm, 88/100 tracked (sequential; 2026-12-04 and
  // 2026-12-08, `build/tests/test_system_dynamic_mono`, the log's "ATE rmse").
  EXPECT_LE(run.ate(), 0.011);
}

}  // namespace
