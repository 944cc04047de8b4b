// Loop closing in the running Pipeline on `loop-stereo` (system_loop_run.h): one lap of the
// room, then 150 degrees of a second lap from other viewpoints. The same input is run with
// loop closing off and on; the loop must be detected and closed and the ATE of the whole
// trajectory must drop.
#include <gtest/gtest.h>

#include "system_loop_run.h"

namespace {

using namespace lumaslam;

TEST(SystemLoop, ClosesTheLoopOnLoopStereoAndLowersTheAte) {
  const test::LoopInput input(600, 250, 1);  // 250 frames: 150 degrees past the start
  const test::LoopRun open = test::runLoop(input, false);
  const test::LoopRun closed = test::runLoop(input, true);
  EXPECT_GE(open.tracked, static_cast<std::size_t>(input.frames() * 95 / 100));
  EXPECT_GE(closed.tracked, static_cast<std::size_t>(input.frames() * 95 / 100));
  EXPECT_TRUE(open.loops.empty());
  ASSERT_GE(closed.loops.size(), 1U);
  // The loop joins the second lap to keyframes made long before (not a recent neighbour).
  EXPECT_GT(closed.loops.front().current, closed.loops.front().loop + 5);
  // Issue 7's acceptance: ATE after closing <= 50 % of the ATE with loop closing off.
  EXPECT_LE(closed.ate, 0.5 * open.ate);
  // ~2x the measured ATE (issue 22): 4.8 mm closed (13.1 mm open) on 2026-12-04 (sequential,
  // deterministic; the "loop closing on" line the test prints).
  EXPECT_LE(closed.ate, 0.010);
}

}  // namespace
