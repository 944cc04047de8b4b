// Missed detections (issue 6's weak spot): with the detector blind on every other 5-frame
// burst, tracking's memory of recent boxes (Detector.memoryFrames) keeps the people out of
// pose estimation and out of the map.
#include <gtest/gtest.h>

#include "test_paths.h"
#include "test_system_dynamic.h"

namespace {

using namespace lumaslam;

TEST(SystemDynamicMemory, RecentBoxesCoverForMissedDetections) {
  const synth::SequenceRenderer sequence(synth::findPreset("walking-xyz-rgbd"), 100, 1);
  test::TempDir dir("system_dynamic_memory");
  test::GroundTruthBoxes bursts;  // frames 0-4, 10-14, ... detected; 5-9, 15-19, ... missed
  for (int i = 0; i < sequence.frameCount(); ++i) {
    if ((i / 5) % 2 == 0) bursts.add(sequence.render(i));
  }
  const auto boxes = dir.path() / "bursts.txt";
  bursts.write(boxes);
  PipelineOptions options;
  options.detector = "boxes:" + boxes.string();
  options.motion_evidence = false;  // box removal alone (issue 6)

  const auto with_memory = test::runSynthetic(sequence, options);
  const auto without_memory =
      test::runSynthetic(sequence, options, {}, "Detector.memoryFrames: 0\n");
  EXPECT_EQ(with_memory.tracked, with_memory.frames);
  EXPECT_LE(with_memory.ate(), 0.01);  // issue 6's box-file target
  // ~2x the measured ATE (issue 22): 4.0 mm on 2026-12-04 (sequential, deterministic; the
  // first "ATE rmse" line the test logs).
  EXPECT_LE(with_memory.ate(), 0.0085);
  EXPECT_LE(with_memory.ate(), without_memory.ate() / 2.0)
      << "without memory " << without_memory.ate();
}

}  // namespace
