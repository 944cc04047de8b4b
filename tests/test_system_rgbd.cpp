#include <gtest/gtest.h>

#include "test_system_synthetic.h"

namespace {

using namespace lumaslam;

TEST(SystemRgbd, TracksStaticSceneWithXyzMotion) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 150, 1);
  const auto run = test::runSynthetic(sequence, {});
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LT(run.ate(), 0.01);
  EXPECT_GT(run.keyframes, 1U);
}

}  // namespace
