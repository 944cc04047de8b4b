// Monocular SLAM on the rgb stream of a synthetic RGB-D sequence, run without depth: scale is
// unobservable, so the trajectory is compared after a Sim3 alignment.
#include <gtest/gtest.h>

#include "test_system_run.h"

namespace {

using namespace lumaslam;

// The xyz camera eases in from rest, so initialisation needs ~13 frames of motion; 260 frames
// leave room for the 95% tracked criterion.
TEST(SystemMono, RgbStreamOfXyzSequence) {
  test::expectMonocularAcceptance(
      test::runOnPreset("xyz-rgbd", 260, 1, {.sensor = io::SensorType::Monocular}),
      // ~2x the measured ATE (issue 22): 3.29 mm over 2.26 m = 0.146 % (sequential,
      // deterministic; logged by runOnPreset).
      /*max_ate_fraction=*/0.003);
}

}  // namespace
