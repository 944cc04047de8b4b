#include <gtest/gtest.h>

#include "test_system_run.h"
#include "threaded_run_checks.h"

namespace {

using lumaslam::test::runOnPreset;

// Issue 5 acceptance: >= 600 frames of xyz and rpy motion, every frame tracked, ATE <= 1 cm.
TEST(SystemRgbd, TracksStaticSceneWithXyzMotion) {
  const auto run = runOnPreset("xyz-rgbd", 600, 1);
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LT(run.report.ate.stats.rmse, 0.01);  // issue 5's target
  // ~2x the measured ATE (issue 22): 2.98 mm on 2026-12-04 (sequential, deterministic; logged
  // by runOnPreset).
  EXPECT_LE(run.report.ate.stats.rmse, 0.006);
  EXPECT_GT(run.keyframes, 1U);
}

// Fast rotations, with local mapping in its own thread as users run it: which frames are
// tracked depends on the scheduling, so properties instead of a count (threaded_run_checks.h).
TEST(SystemRgbd, TracksStaticSceneWithRpyMotionThreaded) {
  const auto run = runOnPreset("rpy-rgbd", 600, 2, {.sequential = false});
  ASSERT_EQ(run.outcomes.size(), run.frames);
  EXPECT_EQ(run.first_tracked, 0U);  // RGB-D: the map starts on the first frame
  lumaslam::test::expectThreadedRun(run.outcomes, run.timestamps, run.trajectory);
  EXPECT_LT(run.report.ate.stats.rmse, 0.01);  // issue 5's target
  // ~2x the worst measured ATE (issue 22): 2.97-3.18 mm in 3 runs on 2026-12-04 (threaded;
  // logged by runOnPreset).
  EXPECT_LE(run.report.ate.stats.rmse, 0.0065);
  EXPECT_GT(run.keyframes, 5U);
}

}  // namespace
