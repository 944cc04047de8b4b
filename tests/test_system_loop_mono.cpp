// Monocular loop closing (Sim3) in the running System: the left camera of `loop-stereo`
// (system_loop_run.h), one lap and part of a second, with loop closing off and on. Monocular
// drifts in scale as well as in pose, so the loop is corrected with a Sim3 and the
// trajectories are compared after a Sim3 alignment. The lap is played 1.5x faster than the
// preset's 600 frames (400 frames; 170 frames of the second lap, 150 degrees past the start):
// the monocular drift of the 600-frame lap is small (Sim3 ATE 14.4 mm over ~8 m), and closing
// its loop took it to 10.2 mm (71 %). Measured numbers: docs/accuracy.md, loop section.
#include <gtest/gtest.h>

#include "system_loop_run.h"

namespace {

using namespace lumaslam;

TEST(SystemLoopMono, ClosesASim3LoopOnTheLeftCameraOfLoopStereoAndLowersTheAte) {
  const test::LoopInput input(400, 170, 1);
  const auto mono = io::SensorType::Monocular;
  const test::LoopRun open = test::runLoop(input, false, mono);
  const test::LoopRun closed = test::runLoop(input, true, mono);
  EXPECT_GE(open.tracked, static_cast<std::size_t>(input.frames() * 95 / 100));
  EXPECT_GE(closed.tracked, static_cast<std::size_t>(input.frames() * 95 / 100));
  EXPECT_TRUE(open.loops.empty());
  ASSERT_GE(closed.loops.size(), 1U);
  // The loop joins the second lap to keyframes made long before (not a recent neighbour).
  EXPECT_GT(closed.loops.front().current, closed.loops.front().loop + 5);
  EXPECT_NE(closed.loops.front().correction_scale, 1.0);  // a Sim3 loop, not an SE3 one
  EXPECT_EQ(closed.global_ba.completed, static_cast<int>(closed.loops.size()));
  // Closing the loop must lower the Sim3-aligned ATE clearly: within issue 7's 50 %, at
  // ~2x what is measured (issue 22): 20.5 -> 3.8 mm (19 %), sequential, 2026-12-05
  // (`test_system_loop_mono` prints "mono, loop closing off/on: ... Sim3 ... mm"). Earlier
  // code gave 43 % and 64 % (2026-12-01), when the bound was 75 %.
  EXPECT_LE(closed.ate_sim3, 0.4 * open.ate_sim3) << "open " << open.ate_sim3;
  EXPECT_LE(closed.ate_sim3, 0.008);
}

}  // namespace
