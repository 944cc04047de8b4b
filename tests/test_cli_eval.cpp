// Runs the built `lumaslam eval` on trajectory files written to a temporary folder.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

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

}  // namespace
}  // namespace lumaslam
