// Monocular SLAM on the left camera of a synthetic EuRoC-format stereo sequence (its own
// executable: 752x480 stereo frames take long to render on a loaded machine).
#include <gtest/gtest.h>

#include "test_system_run.h"

namespace {

using namespace lumaslam;

TEST(SystemMono, LeftCameraOfStereoSequence) {
  test::expectMonocularAcceptance(
      test::runOnPreset("xyz-stereo", 220, 2, {.sensor = io::SensorType::Monocular}));
}

}  // namespace
