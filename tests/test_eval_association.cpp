#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <string>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/eval/association.h"
#include "test_eval_synthetic.h"

namespace lumaslam::eval {
namespace {

Trajectory stampsOnly(std::initializer_list<double> stamps) {
  Trajectory trajectory;
  for (const double stamp : stamps) trajectory.push_back({stamp, SE3::Identity()});
  return trajectory;
}

TEST(Association, JitteredStampsWithMissingPosesMatchOneToOne) {
  // Ground truth at 20 Hz; the estimate has every pose with up to 8 ms of jitter, but starts
  // 10 frames late and lost 30 frames in the middle.
  const Trajectory ground_truth = test::helix(300, 0.05);
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> jitter(-0.008, 0.008);
  Trajectory estimate;
  for (std::size_t i = 10; i < 300; ++i) {
    if (i >= 100 && i < 130) continue;
    StampedPose pose = ground_truth[i];
    pose.timestamp += jitter(generator);
    estimate.push_back(pose);
  }

  const AssociatedTrajectories matched = associate(estimate, ground_truth, 0.02);
  ASSERT_EQ(matched.size(), 260u);
  EXPECT_EQ(matched.ground_truth_in_span, 290u);  // frames 10..299
  EXPECT_NEAR(matched.coverage(), 260.0 / 290.0, 1e-12);
  std::set<std::size_t> used;
  for (std::size_t k = 0; k < matched.size(); ++k) {
    EXPECT_LE(std::abs(matched.estimate[k].timestamp - matched.ground_truth[k].timestamp), 0.02);
    // Each estimate pose found the ground-truth pose it was made from.
    EXPECT_TRUE(matched.estimate[k].T_w_c.isApprox(matched.ground_truth[k].T_w_c));
    EXPECT_TRUE(used.insert(matched.ground_truth_indices[k]).second);
    if (k > 0) {
      EXPECT_GT(matched.estimate[k].timestamp, matched.estimate[k - 1].timestamp);
    }
  }
}

TEST(Association, ClosestPairsWinAndEachGroundTruthPoseIsUsedOnce) {
  // Both estimate stamps are nearest to 1.002; the closer one (1.003) gets it and 1.000 falls
  // back to 1.015, as in TUM's associate.py.
  const Trajectory estimate = stampsOnly({1.000, 1.003});
  const Trajectory ground_truth = stampsOnly({1.002, 1.015});
  const AssociatedTrajectories matched = associate(estimate, ground_truth, 0.02);
  ASSERT_EQ(matched.size(), 2u);
  EXPECT_EQ(matched.estimate_indices[0], 0u);
  EXPECT_EQ(matched.ground_truth_indices[0], 1u);
  EXPECT_EQ(matched.estimate_indices[1], 1u);
  EXPECT_EQ(matched.ground_truth_indices[1], 0u);

  // With a tighter window the fallback is out of reach and only one pair remains.
  EXPECT_EQ(associate(estimate, ground_truth, 0.01).size(), 1u);
}

TEST(Association, HigherRateGroundTruthCountsTheSamplesInTheSpan) {
  // 100 Hz ground truth, 25 Hz estimate over 2 s: 51 matches, 201 GT samples in the span.
  const Trajectory ground_truth = test::helix(1000, 0.01, 0.0);
  Trajectory estimate;
  for (std::size_t i = 100; i <= 300; i += 4) estimate.push_back(ground_truth[i]);
  const AssociatedTrajectories matched = associate(estimate, ground_truth, 0.005);
  EXPECT_EQ(matched.size(), 51u);
  EXPECT_EQ(matched.ground_truth_in_span, 201u);
}

TEST(Association, UnsortedInputIsHandled) {
  const Trajectory estimate = stampsOnly({3.0, 1.0, 2.0});
  const Trajectory ground_truth = stampsOnly({2.001, 3.001, 1.001});
  const AssociatedTrajectories matched = associate(estimate, ground_truth, 0.01);
  ASSERT_EQ(matched.size(), 3u);
  EXPECT_DOUBLE_EQ(matched.estimate[0].timestamp, 1.0);
  EXPECT_DOUBLE_EQ(matched.ground_truth[0].timestamp, 1.001);
  EXPECT_DOUBLE_EQ(matched.ground_truth[2].timestamp, 3.001);
}

TEST(Association, BadInputsGiveClearErrors) {
  const Trajectory ground_truth = test::helix(50, 0.05, 100.0);
  const Trajectory later = test::helix(50, 0.05, 500.0);
  const std::string no_overlap = test::errorOf([&] { associate(later, ground_truth, 0.02); });
  EXPECT_NE(no_overlap.find("no estimate pose is within 0.02 s"), std::string::npos) << no_overlap;
  EXPECT_NE(no_overlap.find("500.000000"), std::string::npos) << no_overlap;
  EXPECT_NE(no_overlap.find("100.000000"), std::string::npos) << no_overlap;

  EXPECT_NE(test::errorOf([&] { associate({}, ground_truth, 0.02); }).find("estimated trajectory"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] { associate(ground_truth, {}, 0.02); }).find("ground-truth"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] { associate(ground_truth, ground_truth, -1.0); }).find("max_dt"),
            std::string::npos);
  EXPECT_THROW(associate(ground_truth, ground_truth, NAN), Error);
}

TEST(Association, HugeMaxDtDoesNotMakeDisjointSpansCovered) {
  // Ground truth 1000..1002.45 s, the estimate 9000..9002.45 s: with max_dt 1e9 every pose
  // finds a partner, but the estimate ran beside none of the ground truth.
  const Trajectory ground_truth = test::helix(50);
  const Trajectory estimate = test::helix(50, 0.05, 9000.0);
  const AssociatedTrajectories matched = associate(estimate, ground_truth, 1e9);
  EXPECT_EQ(matched.size(), 50u);
  EXPECT_EQ(matched.ground_truth_in_span, 0u);
  EXPECT_DOUBLE_EQ(matched.coverage(), 0.0);

  // The first half of the estimate runs beside the last half of the ground truth (stamps
  // half an interval apart): those 25 ground-truth poses are in its span, and covered.
  const Trajectory half = test::helix(50, 0.05, 1000.0 + 25.5 * 0.05);
  const AssociatedTrajectories overlap = associate(half, ground_truth, 1e9);
  EXPECT_EQ(overlap.ground_truth_in_span, 25u);
  EXPECT_DOUBLE_EQ(overlap.coverage(), 1.0);
}

}  // namespace
}  // namespace lumaslam::eval
