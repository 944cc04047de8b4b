// `lumaslam run` on real monocular data (its own executable: about a minute on a loaded
// 2-core machine).
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "lumaslam/io/trajectory_io.h"
#include "test_cli.h"
#include "test_trajectory_length.h"

namespace {

using lumaslam::test::pathLength;
using lumaslam::test::readRunSummary;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

// Real monocular data: the first 160 frames of KITTI odometry 07 (10 Hz, ~90 m with turns).
TEST(CliRunKittiMono, Sequence07Excerpt) {
  const auto sequence = lumaslam::test::dataDir() / "kitti/odometry_07_first160/sequences/07";
  ASSERT_TRUE(std::filesystem::exists(sequence))
      << sequence << " is missing: the shared data is a required test input (LUMASLAM_SHARED_DIR)";
  TempDir dir("cli_run_kitti_mono");
  const auto settings = lumaslam::test::sourceDir() / "configs/kitti_04-12_mono.yaml";
  const auto run = runCli("run --dataset kitti:" + sequence.string() + " --settings " +
                          settings.string() + " --sequential --out " + dir.path().string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto summary = readRunSummary(dir.path());
  EXPECT_GE(summary["tracked"].get<double>(), 0.9 * summary["frames"].get<double>());
  ASSERT_TRUE(summary.contains("evaluation")) << run.output;
  EXPECT_EQ(summary["evaluation"]["alignment"]["mode"].get<std::string>(), "sim3");
  const auto ground_truth = lumaslam::io::readTrajectory(
      sequence.parent_path().parent_path() / "poses/07.txt", lumaslam::io::TrajectoryFormat::Kitti);
  // Issue 7's target is 2 % of the path; the bound is ~2x the measured ATE (issue 22): 0.259 m
  // over 90.6 m = 0.29 %, the same to 1e-15 in 3 runs of this command (--sequential).
  EXPECT_LT(summary["evaluation"]["ate"]["rmse"].get<double>(), 0.006 * pathLength(ground_truth));
}

}  // namespace
