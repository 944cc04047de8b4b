// The loop closer's Loop.* keys reach it (issue 21: every documented key has an effect): on a
// lap of loop-stereo and the start of a second lap (one loop closed with the defaults, keyframe
// 20 -> 8, then a global bundle adjustment), Loop.globalBundleAdjustment: false closes the loop
// without one, and a Loop.minInliers no candidate can reach closes none.
#include <gtest/gtest.h>

#include "system_loop_run.h"

namespace {

using namespace lumaslam;

test::SettingsEdit appending(const std::string& lines) {
  return [lines](std::string yaml) { return yaml + "\n" + lines; };
}

TEST(SystemLoopSettings, LoopKeysChangeWhatTheLoopCloserDoes) {
  const test::LoopInput input(400, 170, 1);
  const auto no_global_ba =
      test::runLoop(input, true, std::nullopt, appending("Loop.globalBundleAdjustment: false\n"));
  ASSERT_GE(no_global_ba.loops.size(), 1U);
  EXPECT_EQ(no_global_ba.global_ba.started, 0);

  const auto strict =
      test::runLoop(input, true, std::nullopt, appending("Loop.minInliers: 5000\n"));
  EXPECT_TRUE(strict.loops.empty());
  EXPECT_GE(strict.tracked, static_cast<std::size_t>(input.frames() * 95 / 100));
}

}  // namespace
