#include <gtest/gtest.h>

#include "lumaslam/core/error.h"
#include "lumaslam/track/dynamic_point_memory.h"

namespace {

using lumaslam::track::DynamicMemoryParams;
using lumaslam::track::DynamicPointMemory;

const cv::Rect2f kPerson(100, 100, 50, 150);
const cv::Point2f kOnPerson(120, 180);
const cv::Point2f kFarAway(400, 50);

DynamicMemoryParams params(int frames, int strikes) {
  DynamicMemoryParams p;
  p.frames = frames;
  p.strikes = strikes;
  p.margin_px = 10;
  return p;
}

TEST(DynamicPointMemory, RepeatedFailuresNearARecentBoxMakeAPointDynamic) {
  DynamicPointMemory memory(params(10, 2));
  memory.beginFrame(0, {kPerson});
  EXPECT_FALSE(memory.likelyMissedDetection());
  memory.beginFrame(1, {});  // the detector missed the person
  EXPECT_TRUE(memory.likelyMissedDetection());
  EXPECT_TRUE(memory.nearRecentBox(kOnPerson));
  EXPECT_TRUE(memory.nearRecentBox({95, 100}));  // within the margin
  EXPECT_FALSE(memory.nearRecentBox(kFarAway));
  EXPECT_FALSE(memory.recordOutcome(7, kOnPerson, true));  // first strike
  EXPECT_FALSE(memory.isDynamic(7));
  memory.beginFrame(2, {});
  EXPECT_TRUE(memory.recordOutcome(7, kOnPerson, true));  // second strike
  EXPECT_TRUE(memory.isDynamic(7));
  EXPECT_EQ(memory.dynamicCount(), 1U);
  EXPECT_FALSE(memory.recordOutcome(7, kOnPerson, true));  // already dynamic: reported once
}

TEST(DynamicPointMemory, FailuresAwayFromBoxesOrInterruptedBySuccessAreForgiven) {
  DynamicPointMemory memory(params(10, 2));
  memory.beginFrame(0, {kPerson});
  for (int k = 0; k < 5; ++k) EXPECT_FALSE(memory.recordOutcome(1, kFarAway, true));
  EXPECT_FALSE(memory.isDynamic(1));

  EXPECT_FALSE(memory.recordOutcome(2, kOnPerson, true));
  EXPECT_FALSE(memory.recordOutcome(2, kOnPerson, false));  // an inlier clears the strike
  EXPECT_FALSE(memory.recordOutcome(2, kOnPerson, true));
  EXPECT_FALSE(memory.isDynamic(2));
}

TEST(DynamicPointMemory, BoxesAreForgottenAfterTheWindow) {
  DynamicPointMemory memory(params(3, 2));
  memory.beginFrame(10, {kPerson});
  EXPECT_FALSE(memory.recordOutcome(3, kOnPerson, true));
  memory.beginFrame(12, {});
  EXPECT_TRUE(memory.nearRecentBox(kOnPerson));
  memory.beginFrame(13, {});  // frame 10 is 3 frames old: forgotten, and the strikes with it
  EXPECT_FALSE(memory.nearRecentBox(kOnPerson));
  EXPECT_FALSE(memory.recordOutcome(3, kOnPerson, true));
  memory.beginFrame(14, {kPerson});
  EXPECT_FALSE(memory.recordOutcome(3, kOnPerson, true));  // strikes started again
  EXPECT_FALSE(memory.isDynamic(3));
}

TEST(DynamicPointMemory, ZeroFramesSwitchesItOff) {
  DynamicPointMemory memory(params(0, 1));
  memory.beginFrame(0, {kPerson});
  EXPECT_FALSE(memory.nearRecentBox(kOnPerson));
  EXPECT_FALSE(memory.recordOutcome(1, kOnPerson, true));
  EXPECT_FALSE(memory.isDynamic(1));
}

TEST(DynamicPointMemory, RejectsNonsenseParameters) {
  EXPECT_THROW(DynamicPointMemory(params(-1, 2)), lumaslam::Error);
  EXPECT_THROW(DynamicPointMemory(params(5, 0)), lumaslam::Error);
}

}  // namespace
