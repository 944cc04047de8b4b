// `lumaslam run` in monocular mode: a synthetic TUM-format dataset run with mono settings
// (depth present but unused), evaluated with a Sim3 alignment.
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

TEST(CliRunMono, TracksTheRgbStreamOfASyntheticDatasetWithSim3Evaluation) {
  TempDir dir("cli_run_mono");
  const auto data = dir.path() / "data";
  const auto out = dir.path() / "out";
  const auto synth = runCli("synth " + data.string() + " --preset xyz-rgbd --frames 150 --seed 3");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const auto settings = dir.path() / "mono.yaml";
  std::filesystem::copy_file(data / "settings.yaml", settings);
  std::ofstream(settings, std::ios::app) << "\nSystem.sensor: \"mono\"\n";

  const auto run = runCli("run --dataset tum:" + data.string() + " --settings " +
                          settings.string() + " --sequential --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto summary = readRunSummary(out);
  EXPECT_EQ(summary["frames"].get<int>(), 150);
  // Initialisation waits for ~1 degree of parallax (the camera eases in from rest).
  EXPECT_GE(summary["tracked"].get<int>(), 130);
  ASSERT_TRUE(summary.contains("evaluation")) << run.output;
  EXPECT_EQ(summary["evaluation"]["alignment"]["mode"].get<std::string>(), "sim3");
  const auto ground_truth = lumaslam::io::readTrajectory(data / "groundtruth.txt");
  // Issue 7's target is 2 % of the path; the bound is ~2x the measured ATE (issue 22): 4.96 mm
  // over 1.22 m = 0.41 % (this command, --sequential, deterministic).
  EXPECT_LT(summary["evaluation"]["ate"]["rmse"].get<double>(), 0.008 * pathLength(ground_truth));
}

}  // namespace
