// The map-start test of motion evidence (issue 16; docs/dynamic.md "Map start",
// track/origin_segmentation.h): in a map's first frames the static motion since the origin
// keyframe gives the pose, so that a mover in view from frame 0 cannot pull it along.
// Synthetic RGB-D sequences, no detector, sequential mapping (deterministic).
#include <gtest/gtest.h>

#include "test_system_dynamic.h"

namespace {

using namespace lumaslam;

constexpr const char* kOn = "\nDynamic.mapStartSegmentation: 1\n";

using test::runWithoutDetector;

// Seed 3 of walking_xyz: the crate is large and close in frame 0; without the test the pose
// follows it by ~2 cm a frame for 40 frames. Measured 2026-12-08: 8.2 mm on, 156.1
// mm off (sequential; `build/tests/test_system_map_start --gtest_filter=*Crate*`, the two "ATE
// rmse" lines). Bounds ~2x (issue 22).
TEST(SystemMapStart, KeepsThePoseOffACrateCloseInFrameZero) {
  const synth::SequenceRenderer sequence(synth::findPreset("walking-xyz-rgbd"), 150, 3);
  const auto off = runWithoutDetector(sequence);
  const auto on = runWithoutDetector(sequence, kOn);
  EXPECT_EQ(on.tracked, on.frames);
  EXPECT_LE(on.ate(), 0.016);
  EXPECT_LE(on.ate(), 0.1 * off.ate()) << "without " << off.ate();
}

// Nothing moves: no more than 10 % above the run without it (+ 0.5 mm for a few-mm ATE),
// issue 16's rule for the motion test.
TEST(SystemMapStart, DoesNoHarmOnAStaticScene) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 100, 1);
  const auto off = runWithoutDetector(sequence);
  const auto on = runWithoutDetector(sequence, kOn);
  EXPECT_EQ(on.tracked, on.frames);
  EXPECT_LE(on.ate(), 1.1 * off.ate() + 0.0005) << "without " << off.ate();
}

}  // namespace
