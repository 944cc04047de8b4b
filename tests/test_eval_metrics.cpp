#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/eval/alignment.h"
#include "lumaslam/eval/ate.h"
#include "lumaslam/eval/error_stats.h"
#include "lumaslam/eval/rpe.h"
#include "test_eval_synthetic.h"

namespace lumaslam::eval {
namespace {

using test::errorOf;
using test::helix;
using test::someRotation;
using test::straightLine;
using test::transformed;
using test::withPositionNoise;

TEST(ErrorStats, MatchesHandComputedValues) {
  const std::vector<double> errors{4.0, 1.0, 3.0, 2.0};
  const ErrorStats stats = computeStats(errors);
  EXPECT_EQ(stats.count, 4u);
  EXPECT_DOUBLE_EQ(stats.mean, 2.5);
  EXPECT_DOUBLE_EQ(stats.median, 2.5);
  EXPECT_DOUBLE_EQ(stats.rmse, std::sqrt(7.5));
  EXPECT_NEAR(stats.std, std::sqrt(1.25), 1e-12);
  EXPECT_DOUBLE_EQ(stats.min, 1.0);
  EXPECT_DOUBLE_EQ(stats.max, 4.0);
  const std::vector<double> odd{5.0, 0.5, 2.0};
  EXPECT_DOUBLE_EQ(computeStats(odd).median, 2.0);
  EXPECT_THROW(computeStats(std::vector<double>{}), Error);
}

TEST(Alignment, Sim3RecoversAKnownSimilarityAndGivesZeroAte) {
  const Trajectory ground_truth = helix(300);
  const double scale = 2.5;
  const Eigen::Matrix3d R = someRotation();
  const Eigen::Vector3d t(1.0, -3.0, 0.25);
  // The estimate lives in a frame where ground truth = s R estimate + t.
  const Trajectory estimate =
      transformed(transformed(ground_truth, 1.0, Eigen::Matrix3d::Identity(), -t), 1.0 / scale,
                  R.transpose(), Eigen::Vector3d::Zero());

  const Alignment alignment = align(estimate, ground_truth, AlignMode::Sim3);
  EXPECT_NEAR(alignment.scale, scale, 1e-9);
  EXPECT_TRUE(alignment.R.isApprox(R, 1e-9)) << alignment.R;
  EXPECT_TRUE(alignment.t.isApprox(t, 1e-9)) << alignment.t.transpose();

  const AbsoluteTrajectoryError ate = computeAte(alignment.apply(estimate), ground_truth);
  EXPECT_EQ(ate.stats.count, 300u);
  EXPECT_LT(ate.stats.max, 1e-9);
  // Orientations are carried into the ground-truth frame too.
  const RelativePoseError rpe = computeRpe(alignment.apply(estimate), ground_truth, RpeSettings{});
  EXPECT_LT(rpe.rotation.max, 1e-6);
}

TEST(Alignment, Se3RecoversARigidTransformAndKeepsScaleOne) {
  const Trajectory ground_truth = helix(300);
  const Eigen::Matrix3d R = someRotation();
  const Eigen::Vector3d t(-0.5, 2.0, 1.0);
  const Trajectory estimate =
      transformed(transformed(ground_truth, 1.0, Eigen::Matrix3d::Identity(), -t), 1.0,
                  R.transpose(), Eigen::Vector3d::Zero());
  const Alignment alignment = align(estimate, ground_truth, AlignMode::SE3);
  EXPECT_DOUBLE_EQ(alignment.scale, 1.0);
  EXPECT_TRUE(alignment.R.isApprox(R, 1e-9));
  EXPECT_TRUE(alignment.t.isApprox(t, 1e-9));
  EXPECT_LT(computeAte(alignment.apply(estimate), ground_truth).stats.max, 1e-9);

  // A scaled estimate cannot be fixed without Sim3: the ATE stays large under SE3.
  const Trajectory scaled =
      transformed(ground_truth, 0.5, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  const Alignment rigid = align(scaled, ground_truth, AlignMode::SE3);
  EXPECT_DOUBLE_EQ(rigid.scale, 1.0);
  EXPECT_GT(computeAte(rigid.apply(scaled), ground_truth).stats.rmse, 0.5);
  const Alignment similar = align(scaled, ground_truth, AlignMode::Sim3);
  EXPECT_NEAR(similar.scale, 2.0, 1e-9);
}

TEST(Alignment, NoneIsTheIdentity) {
  const Trajectory ground_truth = helix(10);
  const Alignment alignment = align(ground_truth, ground_truth, AlignMode::None);
  EXPECT_EQ(alignment.scale, 1.0);
  EXPECT_TRUE(alignment.R.isIdentity());
  EXPECT_TRUE(alignment.t.isZero());
}

TEST(Alignment, RejectsTooFewOrDegeneratePoses) {
  const Trajectory two = helix(2);
  const std::string message = errorOf([&] { align(two, two, AlignMode::SE3); });
  EXPECT_NE(message.find("at least 3 matched poses, got 2"), std::string::npos) << message;
  Trajectory still = helix(5);
  for (StampedPose& pose : still) pose.T_w_c.translation().setConstant(1.0);
  EXPECT_THROW(align(still, helix(5), AlignMode::Sim3), Error);
  EXPECT_THROW(align(helix(5), helix(6), AlignMode::SE3), Error);
  EXPECT_THROW(parseAlignMode("affine"), Error);
  EXPECT_EQ(parseAlignMode("sim3"), AlignMode::Sim3);
}

TEST(Ate, GaussianPositionNoiseGivesSigmaTimesSqrt3) {
  const Trajectory ground_truth = helix(3000, 0.01);
  const double sigma = 0.03;
  const Trajectory estimate = withPositionNoise(ground_truth, sigma, 42);
  const AbsoluteTrajectoryError unaligned = computeAte(estimate, ground_truth);
  EXPECT_NEAR(unaligned.stats.rmse, sigma * std::sqrt(3.0), 0.03 * sigma * std::sqrt(3.0));
  // Aligning removes at most the 6 of 9000 degrees of freedom the noise gave to the frame.
  const Alignment alignment = align(estimate, ground_truth, AlignMode::SE3);
  const AbsoluteTrajectoryError aligned = computeAte(alignment.apply(estimate), ground_truth);
  EXPECT_LE(aligned.stats.rmse, unaligned.stats.rmse);
  EXPECT_NEAR(aligned.stats.rmse, unaligned.stats.rmse, 0.01 * unaligned.stats.rmse);
  EXPECT_LT(alignment.t.norm(), 0.01);
}

TEST(Rpe, ScaleDriftGivesAConstantTranslationError) {
  // An estimate that runs 10% too fast along the helix: every relative translation is 10%
  // too long, and the helix's chord over a fixed frame gap is constant.
  const Trajectory ground_truth = helix(300);
  const Trajectory estimate =
      transformed(ground_truth, 1.1, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  for (const int delta : {1, 10}) {
    const RelativePoseError rpe =
        computeRpe(estimate, ground_truth, RpeSettings{.delta = static_cast<double>(delta)});
    const double chord =
        (ground_truth[delta].T_w_c.translation() - ground_truth[0].T_w_c.translation()).norm();
    EXPECT_EQ(rpe.translation.count, static_cast<std::size_t>(299 / delta));
    EXPECT_NEAR(rpe.translation.mean, 0.1 * chord, 1e-9);
    EXPECT_NEAR(rpe.translation.max - rpe.translation.min, 0.0, 1e-9);
    EXPECT_LT(rpe.rotation.max, 1e-6);
  }
}

TEST(Rpe, YawDriftGivesAConstantRotationError) {
  // Straight line along z; the estimate turns about z at 2 deg/s, which moves no position.
  const Trajectory ground_truth = straightLine(200, 1.0, 0.1);
  Trajectory estimate = ground_truth;
  const double degrees_per_second = 2.0;
  for (StampedPose& pose : estimate) {
    pose.T_w_c.linear() = Eigen::AngleAxisd(degrees_per_second * pose.timestamp * M_PI / 180.0,
                                            Eigen::Vector3d::UnitZ())
                              .toRotationMatrix();
  }
  const RelativePoseError rpe = computeRpe(estimate, ground_truth, RpeSettings{.delta = 5});
  EXPECT_NEAR(rpe.rotation.mean, degrees_per_second * 0.5, 1e-9);
  EXPECT_NEAR(rpe.rotation.std, 0.0, 1e-9);
  EXPECT_LT(rpe.translation.max, 1e-9);
}

TEST(Rpe, DeltaInMetresPairsByTravelledDistance) {
  // 0.5 m/s at 10 Hz: 5 cm per frame, so 1 m is 20 frames.
  const Trajectory ground_truth = straightLine(201, 0.5, 0.1);
  const PosePairs pairs =
      rpePairs(ground_truth, RpeSettings{.delta = 1.0, .unit = DeltaUnit::Meters});
  ASSERT_FALSE(pairs.empty());
  for (const auto& [i, j] : pairs) {
    const double travelled =
        (ground_truth[j].T_w_c.translation() - ground_truth[i].T_w_c.translation()).norm();
    EXPECT_NEAR(travelled, 1.0, 1e-9);
  }
  EXPECT_EQ(pairs.size(), 9u);  // evo's rule: ids at 1, 2, ..., 10 m, consecutive pairs
  const PosePairs all = rpePairs(
      ground_truth, RpeSettings{.delta = 1.0, .unit = DeltaUnit::Meters, .all_pairs = true});
  // Every start with a pose 1 m further (181) plus the two whose last pose is 0.95 m and
  // 0.9 m away, inside evo's 10% tolerance.
  EXPECT_EQ(all.size(), 183u);
  EXPECT_EQ(all.front(), std::make_pair(std::size_t{0}, std::size_t{20}));
  EXPECT_EQ(all.back(), std::make_pair(std::size_t{182}, std::size_t{200}));
}

TEST(Rpe, AllPairsInFramesOverlap) {
  const Trajectory ground_truth = helix(30);
  EXPECT_EQ(rpePairs(ground_truth, RpeSettings{.delta = 10}).size(), 2u);
  EXPECT_EQ(rpePairs(ground_truth, RpeSettings{.delta = 10, .all_pairs = true}).size(), 20u);
}

TEST(Rpe, RejectsBadDeltasAndTooShortTrajectories) {
  const Trajectory ground_truth = helix(5);
  EXPECT_THROW(computeRpe(ground_truth, ground_truth, RpeSettings{.delta = 5}), Error);
  EXPECT_THROW(rpePairs(ground_truth, RpeSettings{.delta = 0}), Error);
  EXPECT_THROW(rpePairs(ground_truth, RpeSettings{.delta = 1.5}), Error);
  EXPECT_THROW(parseDeltaUnit("km"), Error);
  EXPECT_EQ(parseDeltaUnit("m"), DeltaUnit::Meters);
}

}  // namespace
}  // namespace lumaslam::eval
