// The evaluation on the real ground-truth files in shared/data, read with the io module.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/eval/evaluation.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/trajectory_io.h"
#include "test_eval_synthetic.h"
#include "test_paths.h"

namespace lumaslam::eval {
namespace {

const std::filesystem::path kTumGroundTruth =
    test::dataDir() / "tum/rgbd_dataset_freiburg1_xyz_textonly/groundtruth.txt";
const std::filesystem::path kEurocRoot = test::dataDir() / "euroc/V1_01_easy_micro";
const std::filesystem::path kKittiSequence =
    test::dataDir() / "kitti/odometry_07_first160/sequences/07";

TEST(EvalRealData, TumGroundTruthUnderAKnownSim3AndNoiseIsRecovered) {
  const Trajectory ground_truth = io::readTrajectory(kTumGroundTruth);
  ASSERT_EQ(ground_truth.size(), 3000u);
  // A monocular-like estimate: in its own frame and scale, with 5 mm noise per axis, and
  // stored through a TUM file like a real run.
  const double scale = 0.4;
  const Eigen::Matrix3d R = test::someRotation();
  const Eigen::Vector3d t(0.3, -1.2, 2.0);
  const double sigma = 0.005;
  const Trajectory in_gt_units = test::withPositionNoise(ground_truth, sigma, 11);
  const Trajectory estimate =
      test::transformed(test::transformed(in_gt_units, 1.0, Eigen::Matrix3d::Identity(), -t),
                        1.0 / scale, R.transpose(), Eigen::Vector3d::Zero());
  test::TempDir dir("eval_tum");
  io::writeTrajectory(dir.path() / "estimate.txt", estimate, io::TrajectoryFormat::Tum);

  const EvaluationReport report =
      evaluate(io::readTrajectory(dir.path() / "estimate.txt"), ground_truth,
               {.align = AlignMode::Sim3, .max_dt = 0.02, .rpe = {}});
  EXPECT_EQ(report.matched_poses, 3000u);
  EXPECT_DOUBLE_EQ(report.coverage, 1.0);
  // fr1/xyz moves only ~0.5 m, so 5 mm noise leaves the transform a little uncertain.
  EXPECT_NEAR(report.alignment.scale, scale, 0.01 * scale);
  EXPECT_LT(Eigen::AngleAxisd(report.alignment.R.transpose() * R).angle(), 0.01);
  EXPECT_LT((report.alignment.t - t).norm(), 0.01);
  EXPECT_NEAR(report.ate.stats.rmse, sigma * std::sqrt(3.0), 0.05 * sigma * std::sqrt(3.0));
  // Noise on both ends of each 1-frame pair: RPE translation rmse is sigma * sqrt(6).
  EXPECT_NEAR(report.rpe.translation.rmse, sigma * std::sqrt(6.0), 0.05 * sigma * std::sqrt(6.0));
  EXPECT_LT(report.rpe.rotation.max, 1e-4);  // orientations were not perturbed
}

TEST(EvalRealData, TumGroundTruthSubsampledAtCameraRateCoversAThird) {
  // An estimate at about 30 Hz of the 100 Hz ground truth, stamped 1 ms late.
  const Trajectory ground_truth = io::readTrajectory(kTumGroundTruth);
  Trajectory estimate;
  for (std::size_t i = 0; i < ground_truth.size(); i += 3) {
    estimate.push_back(ground_truth[i]);
    estimate.back().timestamp += 0.001;
  }
  const EvaluationReport report =
      evaluate(estimate, ground_truth, {.align = AlignMode::SE3, .max_dt = 0.005, .rpe = {}});
  EXPECT_EQ(report.matched_poses, estimate.size());
  EXPECT_LT(report.ate.stats.max, 1e-6);
  EXPECT_NEAR(report.coverage, 1.0 / 3.0, 0.01);
}

TEST(EvalRealData, EurocGroundTruthAgainstItself) {
  const Trajectory ground_truth = io::loadGroundTruth("euroc:" + kEurocRoot.string());
  const Trajectory from_csv = io::readTrajectory(kEurocRoot / "V101_GT_cam0_orbslam3.csv");
  ASSERT_EQ(ground_truth.size(), 74u);
  ASSERT_EQ(from_csv.size(), 74u);
  const EvaluationReport report =
      evaluate(from_csv, ground_truth, {.align = AlignMode::SE3, .max_dt = 0.02, .rpe = {}});
  EXPECT_EQ(report.matched_poses, 74u);
  EXPECT_DOUBLE_EQ(report.coverage, 1.0);
  EXPECT_LT(report.ate.stats.max, 1e-9);
  EXPECT_LT(report.rpe.translation.max, 1e-9);
  EXPECT_LT(report.rpe.rotation.max, 1e-4);
  EXPECT_TRUE(report.alignment.R.isIdentity(1e-6));
}

TEST(EvalRealData, KittiGroundTruthAtMonocularScale) {
  const Trajectory ground_truth = io::loadGroundTruth("kitti:" + kKittiSequence.string());
  ASSERT_EQ(ground_truth.size(), 160u);
  EXPECT_NEAR(ground_truth.back().timestamp, 16.53376, 1e-6);  // times from times.txt
  // A monocular run of the car: right shape, arbitrary scale (here 1/20) and frame.
  const Trajectory estimate =
      test::transformed(ground_truth, 0.05, test::someRotation(), Eigen::Vector3d(1.0, 2.0, 3.0));
  const EvaluationReport report = evaluate(estimate, ground_truth,
                                           {.align = AlignMode::Sim3,
                                            .max_dt = 0.02,
                                            .rpe = {.delta = 10.0, .unit = DeltaUnit::Meters}});
  EXPECT_NEAR(report.alignment.scale, 20.0, 1e-6);
  EXPECT_LT(report.ate.stats.max, 1e-6);
  EXPECT_LT(report.rpe.translation.max, 1e-6);
  EXPECT_GE(report.rpe.pairs.size(), 7u);  // 90 m of path in 10 m steps

  // Without scale the same estimate is far off.
  const EvaluationReport rigid =
      evaluate(estimate, ground_truth, {.align = AlignMode::SE3, .max_dt = 0.02, .rpe = {}});
  EXPECT_GT(rigid.ate.stats.rmse, 5.0);
}

TEST(EvalRealData, BadFilesAndTooLittleOverlapGiveClearErrors) {
  test::TempDir dir("eval_bad");
  const auto empty = dir.path() / "empty.txt";
  std::ofstream(empty).close();
  const auto garbage = dir.path() / "garbage.txt";
  std::ofstream(garbage) << "1.0 2.0 3.0 4.0 0 0 0 1\nthis is not a pose line\n";
  for (const auto& path : {empty, garbage}) {
    const std::string message = test::errorOf([&] { io::readTrajectory(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << "for " << path << ": " << message;
  }

  // Only two estimate poses fall on the ground truth: too few to align.
  const Trajectory ground_truth = io::readTrajectory(kTumGroundTruth);
  const Trajectory two(ground_truth.begin(), ground_truth.begin() + 2);
  const std::string message = test::errorOf([&] { evaluate(two, ground_truth, {}); });
  EXPECT_NE(message.find("at least 3 matched poses, got 2"), std::string::npos) << message;
  // Shifted a minute later: no overlap in time.
  Trajectory later = ground_truth;
  for (StampedPose& pose : later) pose.timestamp += 60.0;
  EXPECT_THROW(evaluate(later, ground_truth, {}), Error);
}

}  // namespace
}  // namespace lumaslam::eval
