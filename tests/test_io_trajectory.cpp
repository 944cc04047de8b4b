#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/trajectory_io.h"
#include "test_paths.h"

namespace lumaslam::io {
namespace {

using test::dataDir;
using test::TempDir;

void writeText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

using test::errorOf;

double pathLength(const Trajectory& trajectory) {
  double length = 0.0;
  for (std::size_t i = 1; i < trajectory.size(); ++i)
    length += (trajectory[i].T_w_c.translation() - trajectory[i - 1].T_w_c.translation()).norm();
  return length;
}

// A helix with rotating orientation and EuRoC-like nanosecond timestamps (seconds ~1.4e9).
Trajectory syntheticTrajectory() {
  Trajectory trajectory;
  for (int i = 0; i < 50; ++i) {
    StampedPose pose;
    pose.timestamp = 1403715273.262142976 + 0.05 * i + 1e-9 * (i % 7);
    const double angle = 0.13 * i;
    pose.T_w_c.linear() =
        Eigen::AngleAxisd(angle, Eigen::Vector3d(0.3, -0.5, 1.0).normalized()).toRotationMatrix();
    pose.T_w_c.translation() = Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.01 * i);
    trajectory.push_back(pose);
  }
  return trajectory;
}

void expectSameTrajectory(const Trajectory& expected, const Trajectory& actual,
                          bool exact_timestamps = true) {
  ASSERT_EQ(expected.size(), actual.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (exact_timestamps) {
      EXPECT_EQ(expected[i].timestamp, actual[i].timestamp) << i;
    }
    EXPECT_TRUE(expected[i].T_w_c.matrix().isApprox(actual[i].T_w_c.matrix(), 1e-12)) << i;
  }
}

TEST(TrajectoryIo, ReadsTumGroundTruthOfFr1Xyz) {
  const auto file = dataDir() / "tum/rgbd_dataset_freiburg1_xyz_textonly/groundtruth.txt";
  EXPECT_EQ(detectTrajectoryFormat(file), TrajectoryFormat::Tum);
  const Trajectory gt = readTrajectory(file);
  ASSERT_EQ(gt.size(), 3000u);
  // First line: 1305031098.6659 1.3563 0.6305 1.6380 0.6132 0.5962 -0.3311 -0.3986
  EXPECT_DOUBLE_EQ(gt.front().timestamp, 1305031098.6659);
  EXPECT_TRUE(gt.front().T_w_c.translation().isApprox(Eigen::Vector3d(1.3563, 0.6305, 1.6380)));
  const Eigen::Quaterniond q(gt.front().T_w_c.rotation());
  const Eigen::Quaterniond expected =
      Eigen::Quaterniond(-0.3986, 0.6132, 0.5962, -0.3311).normalized();
  EXPECT_NEAR(std::abs(q.dot(expected)), 1.0, 1e-12);
}

TEST(TrajectoryIo, ReadsOrbSlam3EurocLeftCameraCsv) {
  const auto file = dataDir() / "euroc/V1_01_easy_micro/V101_GT_cam0_orbslam3.csv";
  EXPECT_EQ(detectTrajectoryFormat(file), TrajectoryFormat::EurocCsv);
  const Trajectory gt = readTrajectory(file);
  ASSERT_EQ(gt.size(), 74u);
  EXPECT_DOUBLE_EQ(gt.front().timestamp, 1403715274.312143104);
  EXPECT_DOUBLE_EQ(gt.back().timestamp, 1403715277.962142976);
  EXPECT_TRUE(gt.front().T_w_c.translation().isApprox(
      Eigen::Vector3d(0.8687393558, 2.2070275302, 0.9257726725)));
  // The MAV sits on the ground in this excerpt (MANIFEST: 1.5 cm path).
  EXPECT_LT(pathLength(gt), 0.05);
}

TEST(TrajectoryIo, ReadsKittiPosesWithTimes) {
  const auto root = dataDir() / "kitti/odometry_07_first160";
  const auto poses = root / "poses/07.txt";
  EXPECT_EQ(detectTrajectoryFormat(poses), TrajectoryFormat::Kitti);
  const Trajectory gt =
      readTrajectory(poses, TrajectoryFormat::Auto, root / "sequences/07/times.txt");
  ASSERT_EQ(gt.size(), 160u);
  EXPECT_TRUE(gt.front().T_w_c.isApprox(SE3::Identity(), 1e-9));
  EXPECT_DOUBLE_EQ(gt.back().timestamp, 16.53376);
  EXPECT_NEAR(gt.back().T_w_c.translation().z(), 15.68785, 1e-5);  // MANIFEST row 159
  EXPECT_NEAR(pathLength(gt), 90.6, 0.5);
  for (const auto& pose : gt)
    EXPECT_NEAR(
        (pose.T_w_c.rotation().transpose() * pose.T_w_c.rotation() - Eigen::Matrix3d::Identity())
            .norm(),
        0.0, 1e-12);

  const Trajectory indexed = readTrajectory(poses, TrajectoryFormat::Kitti);
  ASSERT_EQ(indexed.size(), 160u);
  EXPECT_EQ(indexed[37].timestamp, 37.0);
}

TEST(TrajectoryIo, TumRoundTripKeepsNanosecondTimestamps) {
  TempDir dir("traj_tum");
  const Trajectory original = syntheticTrajectory();
  writeTrajectory(dir.path() / "t.txt", original, TrajectoryFormat::Tum);
  EXPECT_EQ(detectTrajectoryFormat(dir.path() / "t.txt"), TrajectoryFormat::Tum);
  expectSameTrajectory(original, readTrajectory(dir.path() / "t.txt"));
}

TEST(TrajectoryIo, EurocRoundTrip) {
  TempDir dir("traj_euroc");
  const Trajectory original = syntheticTrajectory();
  writeTrajectory(dir.path() / "gt.csv", original, TrajectoryFormat::EurocCsv);
  EXPECT_EQ(detectTrajectoryFormat(dir.path() / "gt.csv"), TrajectoryFormat::EurocCsv);
  expectSameTrajectory(original, readTrajectory(dir.path() / "gt.csv"));
}

TEST(TrajectoryIo, KittiRoundTripWithAndWithoutTimes) {
  TempDir dir("traj_kitti");
  const Trajectory original = syntheticTrajectory();
  writeTrajectory(dir.path() / "poses.txt", original, TrajectoryFormat::Kitti,
                  dir.path() / "times.txt");
  expectSameTrajectory(original, readTrajectory(dir.path() / "poses.txt", TrajectoryFormat::Auto,
                                                dir.path() / "times.txt"));
  const Trajectory indexed = readTrajectory(dir.path() / "poses.txt");
  expectSameTrajectory(original, indexed, /*exact_timestamps=*/false);
  EXPECT_EQ(indexed.back().timestamp, 49.0);
}

TEST(TrajectoryIo, NormalisesSlightlyOffQuaternion) {
  TempDir dir("traj_norm");
  writeText(dir.path() / "t.txt", "1.0 0 0 0 0 0 0 1.0005\n2.0 0 0 0 0 0 0.7071068 0.7071068\n");
  const Trajectory trajectory = readTrajectory(dir.path() / "t.txt");
  ASSERT_EQ(trajectory.size(), 2u);
  EXPECT_TRUE(trajectory[0].T_w_c.isApprox(SE3::Identity(), 1e-12));
  EXPECT_NEAR(Eigen::AngleAxisd(trajectory[1].T_w_c.rotation()).angle(), M_PI / 2, 1e-6);
}

TEST(TrajectoryIo, BadInputsNameFileAndLine) {
  TempDir dir("traj_bad");
  const auto missing = dir.path() / "missing.txt";
  EXPECT_NE(errorOf([&] { readTrajectory(missing); }).find(missing.string()), std::string::npos);

  const auto empty = dir.path() / "empty.txt";
  writeText(empty, "# only a comment\n\n");
  EXPECT_NE(errorOf([&] { readTrajectory(empty); }).find("empty.txt: no trajectory data"),
            std::string::npos);

  const auto garbage = dir.path() / "garbage.txt";
  writeText(garbage, "# t x y z qx qy qz qw\n1 0 0 0 0 0 0 1\n2 0 0 zero 0 0 0 1\n");
  const std::string garbage_error = errorOf([&] { readTrajectory(garbage); });
  EXPECT_NE(garbage_error.find("garbage.txt:3"), std::string::npos) << garbage_error;
  EXPECT_NE(garbage_error.find("'zero'"), std::string::npos) << garbage_error;

  const auto short_line = dir.path() / "short.txt";
  writeText(short_line, "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
  EXPECT_NE(errorOf([&] { readTrajectory(short_line, TrajectoryFormat::Tum); }).find("short.txt:2"),
            std::string::npos);

  const auto bad_quaternion = dir.path() / "quat.txt";
  writeText(bad_quaternion, "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1.1\n");
  const std::string quaternion_error = errorOf([&] { readTrajectory(bad_quaternion); });
  EXPECT_NE(quaternion_error.find("quat.txt:2: quaternion norm"), std::string::npos)
      << quaternion_error;

  const auto backwards = dir.path() / "backwards.txt";
  writeText(backwards, "1 0 0 0 0 0 0 1\n3 0 0 0 0 0 0 1\n3 0 0 0 0 0 0 1\n");
  const std::string order_error = errorOf([&] { readTrajectory(backwards); });
  EXPECT_NE(order_error.find("backwards.txt:3"), std::string::npos) << order_error;
  EXPECT_NE(order_error.find("does not increase"), std::string::npos) << order_error;

  const auto not_rotation = dir.path() / "kitti.txt";
  writeText(not_rotation, "2 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_NE(errorOf([&] { readTrajectory(not_rotation); }).find("kitti.txt:1: the 3x3 part"),
            std::string::npos);

  const auto bad_ns = dir.path() / "bad.csv";
  writeText(bad_ns, "#timestamp [ns],x\n1403715274.5e9,0,0,0,1,0,0,0\n");
  EXPECT_NE(errorOf([&] { readTrajectory(bad_ns); }).find("bad.csv:2: bad number"),
            std::string::npos);

  const auto unknown = dir.path() / "unknown.txt";
  writeText(unknown, "1 2 3\n");
  EXPECT_NE(errorOf([&] { readTrajectory(unknown); }).find("cannot tell the trajectory format"),
            std::string::npos);

  EXPECT_NE(errorOf([] { parseTrajectoryFormat("g2o"); }).find("'g2o'"), std::string::npos);
  EXPECT_EQ(parseTrajectoryFormat("euroc"), TrajectoryFormat::EurocCsv);
}

}  // namespace
}  // namespace lumaslam::io
