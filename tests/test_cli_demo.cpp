// `lumaslam demo` (the README's main job): synthetic walking sequence, baseline run and
// lumaslam run (enhancement + features on moving objects dropped), both evaluated.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "test_cli.h"

namespace {

using lumaslam::test::readRunSummary;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

TEST(CliDemo, RunsBaselineAndLumaslamOnAWalkingSequence) {
  TempDir dir("cli_demo");
  const auto demo = runCli("demo --out " + dir.path().string() + " --frames 60");
  ASSERT_EQ(demo.exit_code, 0) << demo.output;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "data" / "detections.txt"));

  const auto baseline = readRunSummary(dir.path() / "baseline");
  const auto full = readRunSummary(dir.path() / "lumaslam");
  EXPECT_EQ(baseline["detector"]["name"].get<std::string>(), "none");
  EXPECT_NE(full["detector"]["name"].get<std::string>(), "none");
  EXPECT_GT(full["detector"]["dropped_features_per_frame"].get<double>(), 10.0);
  EXPECT_EQ(full["tracked"].get<int>(), 60);
  ASSERT_TRUE(full.contains("evaluation")) << demo.output;
  // ~2x the worst measured ATE (issue 22): the demo maps threaded, so it was run 3 times
  // (`lumaslam demo --frames 60`): 4.22, 4.22, 4.24 mm.
  EXPECT_LT(full["evaluation"]["ate"]["rmse"].get<double>(), 0.0085);
  EXPECT_NE(demo.output.find("baseline (no enhance, no removal)"), std::string::npos);
}

TEST(CliDemo, UnknownPresetIsAClearError) {
  TempDir dir("cli_demo_bad");
  const auto demo = runCli("demo --out " + dir.path().string() + " --preset no-such-preset");
  EXPECT_NE(demo.exit_code, 0);
  EXPECT_NE(demo.output.find("no-such-preset"), std::string::npos) << demo.output;
}

}  // namespace
