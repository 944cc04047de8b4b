// Monocular loop closing (Sim3) in the running System: the left camera of `loop-stereo`
// (system_loop_run.h), one lap and part of a second, with loop closing off and on. Monocular
// drifts in scale as well as in pose, so the loop is corrected with a Sim3 and the
// trajectories are compared after a Sim3 alignment.
#include <cstdlib>

#include <gtest/gtest.h>

#include "system_loop_run.h"

namespace {

using namespace lumaslam;

int envInt(const char* name, int fallback) {
  const char* value = std::getenv(name);
  return value ? std::atoi(value) : fallback;
}

TEST(SystemLoopMono, ClosesASim3LoopOnTheLeftCameraOfLoopStereoAndLowersTheAte) {
  const test::LoopInput input(envInt("LAP", 600), envInt("SECOND", 250), envInt("SEED", 1));
  const auto vocabulary = test::trainLoopVocabulary(input);
  const auto mono = io::SensorType::Monocular;
  const test::LoopRun open = test::runLoop(input, vocabulary, false, mono);
  const test::LoopRun closed = test::runLoop(input, vocabulary, true, mono);
  std::filesystem::remove(vocabulary);
  EXPECT_GE(open.tracked, static_cast<std::size_t>(input.frames() * 95 / 100));
  EXPECT_GE(closed.tracked, static_cast<std::size_t>(input.frames() * 95 / 100));
  EXPECT_TRUE(open.loops.empty());
  ASSERT_GE(closed.loops.size(), 1U);
  EXPECT_GT(closed.loops.front().current, closed.loops.front().loop + 5);
  EXPECT_LE(closed.ate_sim3, 0.5 * open.ate_sim3);
}

}  // namespace
