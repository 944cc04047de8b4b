// Monocular SLAM on the left camera of a synthetic EuRoC-format stereo sequence (its own
// executable: 752x480 stereo frames take long to render on a loaded machine).
#include <gtest/gtest.h>

#include "test_system_run.h"

namespace {

using namespace lumaslam;

TEST(SystemMono, LeftCameraOfStereoSequence) {
  test::expectMonocularAcceptance(
      test::runOnPreset("xyz-stereo", 220, 2, {.sensor = io::SensorType::Monocular}),
      // ~2x the measured ATE (issue 22): 3.12 mm over 2.94 m = 0.106 % (sequential,
      // deterministic; logged by runOnPreset).
      /*max_ate_fraction=*/0.0021);
}

}  // namespace
