// `lumaslam run` on real monocular data (its own executable: about a minute on a loaded
// 2-core machine).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <vector>

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

// Issue 17: a monocular map of real data, saved and loaded: the same drive localized in it
// (no keyframe added) gives the mapping run's poses, in the map's frame and scale.
TEST(CliRunKittiMono, MapOfTheDriveLocalizesItsOwnFrames) {
  const auto sequence = lumaslam::test::dataDir() / "kitti/odometry_07_first160/sequences/07";
  ASSERT_TRUE(std::filesystem::exists(sequence)) << sequence << " is missing";
  TempDir dir("cli_run_kitti_map");
  const auto map = dir.path() / "drive.map";
  const std::string common =
      "run --dataset kitti:" + sequence.string() + " --settings " +
      (lumaslam::test::sourceDir() / "configs/kitti_04-12_mono.yaml").string() +
      " --sequential --out ";
  const auto mapped =
      runCli(common + (dir.path() / "mapped").string() + " --save-map " + map.string());
  ASSERT_EQ(mapped.exit_code, 0) << mapped.output;
  const auto localized = runCli(common + (dir.path() / "localized").string() + " --load-map " +
                                map.string() + " --localization");
  ASSERT_EQ(localized.exit_code, 0) << localized.output;
  const auto summary = readRunSummary(dir.path() / "localized");
  EXPECT_EQ(summary["map_file"]["keyframes_added"].get<int>(), 0);
  EXPECT_GT(summary["map_file"]["loaded_keyframes"].get<int>(), 50);
  EXPECT_GE(summary["tracked"].get<double>(), 0.95 * summary["frames"].get<double>());

  const auto by_time = [](const lumaslam::Trajectory& trajectory) {
    std::map<long long, Eigen::Vector3d> positions;
    for (const auto& pose : trajectory) {
      positions[std::llround(pose.timestamp * 1e5)] = pose.T_w_c.translation();
    }
    return positions;
  };
  const auto mapping = lumaslam::io::readTrajectory(dir.path() / "mapped/trajectory.txt");
  const auto in_map =
      by_time(lumaslam::io::readTrajectory(dir.path() / "localized/trajectory.txt"));
  std::vector<double> differences;
  for (const auto& [stamp, position] : by_time(mapping)) {
    if (const auto it = in_map.find(stamp); it != in_map.end()) {
      differences.push_back((it->second - position).norm());
    }
  }
  ASSERT_GE(differences.size(), mapping.size() - 2);
  std::sort(differences.begin(), differences.end());
  const double length = pathLength(mapping);  // in the map's (monocular) scale
  // Measured (sequential, deterministic): median 2.6e-5 and max 1.4e-4 of the path length.
  EXPECT_LT(differences[differences.size() / 2], 1e-4 * length);
  EXPECT_LT(differences.back(), 5e-4 * length);
}

}  // namespace
