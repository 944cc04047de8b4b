// Runs the built `lumaslam eval` on trajectory files written to a temporary folder.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "lumaslam/io/trajectory_io.h"
#include "test_cli.h"
#include "test_eval_synthetic.h"
#include "test_paths.h"

namespace lumaslam {
namespace {

using test::runCli;
using RunResult = test::CliResult;

nlohmann::json readJson(const std::filesystem::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

// Runs eval with `arguments` after EST GT --json, returns the report ({} when it fails).
nlohmann::json evalJson(const std::filesystem::path& dir, const std::filesystem::path& estimate,
                        const std::filesystem::path& ground_truth, const std::string& arguments) {
  const auto json_path = dir / "report.json";
  std::filesystem::remove(json_path);
  const RunResult run = runCli("eval " + estimate.string() + " " + ground_truth.string() +
                               " --json " + json_path.string() + " " + arguments);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return run.exit_code == 0 ? readJson(json_path) : nlohmann::json{};
}

TEST(CliEval, WritesTableJsonAndPlotForAMonocularEstimate) {
  test::TempDir dir("cli_eval");
  const Trajectory ground_truth = test::helix(300);
  // Estimate at a third of the scale, in another frame, with 1 cm noise.
  const Trajectory estimate =
      test::transformed(test::withPositionNoise(ground_truth, 0.01, 5), 1.0 / 3.0,
                        test::someRotation(), Eigen::Vector3d(0.5, 0.0, -1.0));
  const auto gt_path = dir.path() / "gt.txt";
  const auto est_path = dir.path() / "est.txt";
  io::writeTrajectory(gt_path, ground_truth, io::TrajectoryFormat::Tum);
  io::writeTrajectory(est_path, estimate, io::TrajectoryFormat::Tum);
  const auto json_path = dir.path() / "report.json";
  const auto plot_path = dir.path() / "plot.svg";

  const RunResult run =
      runCli("eval " + est_path.string() + " " + gt_path.string() +
             " --align sim3 --max-dt 0.02 --rpe-delta 5 --rpe-unit frames --json " +
             json_path.string() + " --plot " + plot_path.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("ATE [m]"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("RPE rot [deg]"), std::string::npos) << run.output;

  const nlohmann::json report = readJson(json_path);
  EXPECT_EQ(report["ate"]["count"], 300);
  EXPECT_DOUBLE_EQ(report["ate"]["coverage"].get<double>(), 1.0);
  EXPECT_NEAR(report["ate"]["rmse"].get<double>(), 0.01 * std::sqrt(3.0), 0.002);
  for (const char* stat : {"rmse", "mean", "median", "std", "min", "max", "count"}) {
    EXPECT_TRUE(report["rpe"]["trans"].contains(stat)) << stat;
    EXPECT_TRUE(report["rpe"]["rot"].contains(stat)) << stat;
  }
  EXPECT_EQ(report["rpe"]["trans"]["count"], 59);  // 299 / 5 consecutive pairs
  EXPECT_EQ(report["alignment"]["mode"], "sim3");
  EXPECT_NEAR(report["alignment"]["scale"].get<double>(), 3.0, 0.01);
  EXPECT_EQ(report["alignment"]["rotation"].size(), 3u);
  EXPECT_EQ(report["alignment"]["translation"].size(), 3u);

  std::ifstream plot(plot_path);
  std::string first_line;
  std::getline(plot, first_line);
  EXPECT_EQ(first_line.rfind("<?xml", 0), 0u);
}

TEST(CliEval, ReadsGroundTruthFromADatasetSpec) {
  test::TempDir dir("cli_eval_spec");
  const auto sequence = test::dataDir() / "kitti/odometry_07_first160/sequences/07";
  const auto est_path = dir.path() / "est.txt";
  const auto json_path = dir.path() / "report.json";
  // The KITTI ground truth itself, as a TUM file with the times.txt stamps.
  io::writeTrajectory(est_path,
                      io::readTrajectory(sequence / "../../poses/07.txt",
                                         io::TrajectoryFormat::Kitti, sequence / "times.txt"),
                      io::TrajectoryFormat::Tum);
  const RunResult run = runCli("eval " + est_path.string() + " kitti:" + sequence.string() +
                               " --rpe-delta 10 --rpe-unit m --json " + json_path.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json report = readJson(json_path);
  EXPECT_EQ(report["ate"]["count"], 160);
  EXPECT_LT(report["ate"]["max"].get<double>(), 1e-6);
  EXPECT_EQ(report["rpe"]["unit"], "m");

  // The table on stdout is a result too: a full device is an error, not exit 0 (issue 20).
  const RunResult full =
      runCli("eval " + est_path.string() + " kitti:" + sequence.string() + " > /dev/full");
  EXPECT_NE(full.exit_code, 0);
}

TEST(CliEval, AFailedPlotWriteLeavesTheEarlierFileUntouched) {
  test::TempDir dir("cli_eval_write");
  const auto gt_path = dir.path() / "gt.txt";
  io::writeTrajectory(gt_path, test::helix(300), io::TrajectoryFormat::Tum);
  const auto plot_path = dir.path() / "plot.svg";
  std::ofstream(plot_path) << "earlier plot\n";

  // Files limited to 1 block, SIGXFSZ ignored: writing the plot fails with EFBIG.
  const RunResult run =
      runCli("eval " + gt_path.string() + " " + gt_path.string() + " --plot " + plot_path.string(),
             "trap '' XFSZ; ulimit -f 1; ");
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find(plot_path.string()), std::string::npos) << run.output;
  std::ifstream plot(plot_path);
  std::string content((std::istreambuf_iterator<char>(plot)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "earlier plot\n");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "plot.svg.partial"));
}

TEST(CliEval, MissingOrBadInputFailsWithAMessageNamingIt) {
  test::TempDir dir("cli_eval_bad");
  const auto gt_path = dir.path() / "gt.txt";
  io::writeTrajectory(gt_path, test::helix(50), io::TrajectoryFormat::Tum);
  const auto missing = dir.path() / "no_such_estimate.txt";

  const RunResult run = runCli("eval " + missing.string() + " " + gt_path.string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.output.find(missing.string()), std::string::npos) << run.output;

  // An estimate that shares no time with the ground truth: the message names both files.
  const auto late_path = dir.path() / "late.txt";
  io::writeTrajectory(late_path, test::helix(50, 0.05, 9000.0), io::TrajectoryFormat::Tum);
  const RunResult no_overlap = runCli("eval " + late_path.string() + " " + gt_path.string());
  EXPECT_NE(no_overlap.exit_code, 0);
  EXPECT_NE(no_overlap.output.find(late_path.string()), std::string::npos) << no_overlap.output;
  EXPECT_NE(no_overlap.output.find("no estimate pose is within"), std::string::npos)
      << no_overlap.output;

  // A window wide enough to pair them anyway: poses are matched, the coverage says 0 %.
  const auto json_path = dir.path() / "late.json";
  const RunResult wide = runCli("eval " + late_path.string() + " " + gt_path.string() +
                                " --max-dt 1e9 --json " + json_path.string());
  ASSERT_EQ(wide.exit_code, 0) << wide.output;
  EXPECT_NE(wide.output.find("coverage 0.0%"), std::string::npos) << wide.output;
  EXPECT_DOUBLE_EQ(readJson(json_path)["ate"]["coverage"].get<double>(), 0.0);

  // A very long file name is shortened in the message, not echoed whole (issue 20).
  const std::string long_name = dir.path().string() + "/" + std::string(100000, 'n') + ".txt";
  const RunResult long_run = runCli("eval " + long_name + " " + gt_path.string());
  EXPECT_NE(long_run.exit_code, 0);
  EXPECT_NE(long_run.output.find(long_name.substr(0, 200) + "..."), std::string::npos)
      << long_run.output.substr(0, 1000);
  EXPECT_LT(long_run.output.size(), 2000u) << long_run.output.substr(0, 1000);
  // The same for a bad option value, which CLI11 reports.
  const RunResult long_option = runCli("eval " + gt_path.string() + " " + gt_path.string() +
                                       " --align " + std::string(100000, 'a'));
  EXPECT_NE(long_option.exit_code, 0);
  EXPECT_NE(long_option.output.find(std::string(200, 'a') + "..."), std::string::npos)
      << long_option.output.substr(0, 1000);
  EXPECT_LT(long_option.output.size(), 2000u) << long_option.output.substr(0, 1000);

  const RunResult bad_mode =
      runCli("eval " + gt_path.string() + " " + gt_path.string() + " --align affine");
  EXPECT_NE(bad_mode.exit_code, 0);
  EXPECT_NE(bad_mode.output.find("affine"), std::string::npos) << bad_mode.output;
}

TEST(CliEval, EstFormatAndEstTimesReadTheSameTrajectoryInTumEurocAndKittiForm) {
  test::TempDir dir("cli_eval_formats");
  const Trajectory ground_truth = test::helix(40);
  const auto gt_path = dir.path() / "gt.txt";
  io::writeTrajectory(gt_path, ground_truth, io::TrajectoryFormat::Tum);

  // The estimate, written by hand (not by io::writeTrajectory): the ground truth shifted by a
  // constant 1 cm along x. Without alignment every ATE error is exactly 0.01 m; the shift
  // cancels in relative poses, so the RPE is 0 unless a rotation was misread.
  const auto tum = dir.path() / "est_tum.txt";
  const auto euroc = dir.path() / "est_euroc.csv";
  const auto kitti = dir.path() / "est_kitti.txt";
  const auto times = dir.path() / "times.txt";
  {
    std::ofstream tum_out(tum), euroc_out(euroc), kitti_out(kitti), times_out(times);
    for (auto* out : {&tum_out, &euroc_out, &kitti_out, &times_out}) *out << std::setprecision(17);
    euroc_out << "#timestamp [ns],px,py,pz,qw,qx,qy,qz\n";
    for (const auto& [t, T] : ground_truth) {
      const Eigen::Vector3d p = T.translation() + Eigen::Vector3d(0.01, 0.0, 0.0);
      const Eigen::Quaterniond q(T.rotation());
      const Eigen::Matrix3d R = T.rotation();
      tum_out << t << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << q.x() << ' ' << q.y()
              << ' ' << q.z() << ' ' << q.w() << '\n';
      euroc_out << std::llround(t * 1e9) << ',' << p.x() << ',' << p.y() << ',' << p.z() << ','
                << q.w() << ',' << q.x() << ',' << q.y() << ',' << q.z() << '\n';
      for (int r = 0; r < 3; ++r)
        kitti_out << R(r, 0) << ' ' << R(r, 1) << ' ' << R(r, 2) << ' ' << p(r)
                  << (r < 2 ? ' ' : '\n');
      times_out << t << '\n';
    }
  }

  const std::string kitti_times = " --est-times " + times.string();
  const std::vector<std::pair<std::filesystem::path, std::string>> runs = {
      {tum, ""},
      {tum, "--est-format tum"},
      {euroc, ""},
      {euroc, "--est-format euroc"},
      {kitti, kitti_times},
      {kitti, "--est-format kitti" + kitti_times}};
  for (const auto& [estimate, arguments] : runs) {
    SCOPED_TRACE(estimate.filename().string() + " " + arguments);
    const nlohmann::json report =
        evalJson(dir.path(), estimate, gt_path, "--align none " + arguments);
    if (report.empty()) continue;
    EXPECT_EQ(report["ate"]["count"], 40);
    for (const char* stat : {"rmse", "mean", "median", "min", "max"})
      EXPECT_NEAR(report["ate"][stat].get<double>(), 0.01, 1e-9) << stat;
    EXPECT_LT(report["rpe"]["trans"]["max"].get<double>(), 1e-9);
    EXPECT_LT(report["rpe"]["rot"]["max"].get<double>(), 1e-6);
  }

  // KITTI rows carry no stamps: without --est-times pose i is at i s, far from the ground
  // truth's 1000 s, so nothing matches.
  const RunResult no_times = runCli("eval " + kitti.string() + " " + gt_path.string());
  EXPECT_NE(no_times.exit_code, 0);
  EXPECT_NE(no_times.output.find("no estimate pose is within"), std::string::npos)
      << no_times.output;
  // A forced format that does not fit the file is an error, not a guess.
  const RunResult wrong =
      runCli("eval " + euroc.string() + " " + gt_path.string() + " --est-format tum");
  EXPECT_NE(wrong.exit_code, 0);
  EXPECT_NE(wrong.output.find("est_euroc.csv"), std::string::npos) << wrong.output;
}

TEST(CliEval, RpeAllPairsStartsAPairAtEveryPose) {
  test::TempDir dir("cli_eval_all_pairs");
  // 21 poses 10 cm apart along x, no rotation; the estimate is 1 cm off along x at the poses
  // with i % 4 == 1 only. With identity rotations the RPE of (i, j) is |e_j - e_i|.
  const std::size_t n = 21;
  Trajectory ground_truth, estimate;
  for (std::size_t i = 0; i < n; ++i) {
    StampedPose pose;
    pose.timestamp = 10.0 + 0.1 * static_cast<double>(i);
    pose.T_w_c.translation() = Eigen::Vector3d(0.1 * static_cast<double>(i), 0.0, 0.0);
    ground_truth.push_back(pose);
    if (i % 4 == 1) pose.T_w_c.translation().x() += 0.01;
    estimate.push_back(pose);
  }
  const auto gt_path = dir.path() / "gt.txt";
  const auto est_path = dir.path() / "est.txt";
  io::writeTrajectory(gt_path, ground_truth, io::TrajectoryFormat::Tum);
  io::writeTrajectory(est_path, estimate, io::TrajectoryFormat::Tum);

  // Delta 2, consecutive pairs (0,2), (2,4), ..., (18,20): 10 pairs of even poses, all exact.
  const std::string options = "--align none --rpe-delta 2";
  const nlohmann::json consecutive = evalJson(dir.path(), est_path, gt_path, options);
  ASSERT_FALSE(consecutive.empty());
  EXPECT_EQ(consecutive["rpe"]["all_pairs"], false);
  EXPECT_EQ(consecutive["rpe"]["trans"]["count"], 10);
  EXPECT_LT(consecutive["rpe"]["trans"]["max"].get<double>(), 1e-12);

  // All pairs (i, i+2), i = 0..18: 19 pairs; the 9 with odd i touch one shifted pose (1 cm),
  // the 10 with even i none.
  const nlohmann::json all = evalJson(dir.path(), est_path, gt_path, options + " --rpe-all-pairs");
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all["rpe"]["all_pairs"], true);
  const auto& trans = all["rpe"]["trans"];
  EXPECT_EQ(trans["count"], 19);
  EXPECT_NEAR(trans["rmse"].get<double>(), 0.01 * std::sqrt(9.0 / 19.0), 1e-9);
  EXPECT_NEAR(trans["mean"].get<double>(), 0.09 / 19.0, 1e-9);
  EXPECT_NEAR(trans["max"].get<double>(), 0.01, 1e-9);
  EXPECT_NEAR(trans["min"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(trans["median"].get<double>(), 0.0, 1e-9);
}

}  // namespace
}  // namespace lumaslam
