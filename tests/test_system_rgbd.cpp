#include <gtest/gtest.h>

#include "test_system_run.h"

namespace {

using namespace lumaslam;

TEST(SystemRgbd, TracksStaticSceneWithXyzMotion) {
  const auto run = test_support::runSynthetic("xyz-rgbd", 150, 1);
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LT(run.report.ate.stats.rmse, 0.01);
  EXPECT_GT(run.keyframes, 1U);
}

}  // namespace
