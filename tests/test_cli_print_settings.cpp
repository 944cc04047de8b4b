// `lumaslam run --print-settings` (issue 21): the effective values of a shipped settings file
// for its sensor, with the command line's overrides, as a settings file that reads back; no
// dataset is opened and nothing is run.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "lumaslam/core/settings_file.h"
#include "test_cli.h"

namespace {

using lumaslam::test::runCli;
using lumaslam::test::sourceDir;

std::string printed(const std::string& config, const std::string& flags = "") {
  const auto result =
      runCli("run --dataset tum:/nowhere --settings " +
             (sourceDir() / "configs" / config).string() + " --print-settings " + flags);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const auto start = result.output.find("%YAML:1.0");
  EXPECT_NE(start, std::string::npos) << result.output;
  return start == std::string::npos ? "" : result.output.substr(start);
}

TEST(CliPrintSettings, ShowsTheSensorDefaultsOfAMonocularFile) {
  const std::string text = printed("kitti_04-12_mono.yaml");
  EXPECT_NE(text.find("Tracking.waitForBusyMapper: true\n"), std::string::npos) << text;
  EXPECT_NE(text.find("LocalMapping.triangulationNeighbours: 20\n"), std::string::npos);
  EXPECT_NE(text.find("Tracking.maxFramesBetweenKeyframes: 10\n"), std::string::npos);  // 10 Hz
  EXPECT_NE(text.find("ORBextractor.nFeatures: 2000\n"), std::string::npos);
  EXPECT_NE(text.find("System.sequential: false\n"), std::string::npos);
  EXPECT_EQ(text.find("lumaslam_out"), std::string::npos);  // nothing was run
}

TEST(CliPrintSettings, ShowsCommandLineOverrides) {
  const std::string text = printed("tum_fr1_rgbd.yaml", "--sequential --no-motion-evidence");
  EXPECT_NE(text.find("System.sequential: true\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Dynamic.motionEvidence: false\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Tracking.waitForBusyMapper: false\n"), std::string::npos) << text;
}

TEST(CliPrintSettings, TheOutputIsASettingsFile) {
  const std::string text = printed("euroc_stereo.yaml");
  const auto file = lumaslam::core::SettingsFile::fromString(text, "printed");
  EXPECT_EQ(file.get<int>("Tracking.minInitialFeatures"), 250);  // the stereo default
  EXPECT_EQ(file.get<bool>("LocalMapping.bundleAdjustment"), true);
  EXPECT_EQ(file.get<int>("Loop.minInliers"), 40);
}

TEST(CliPrintSettings, ABadValueIsAnErrorNamingTheKey) {
  lumaslam::test::TempDir dir("print_settings");
  const auto settings = dir.path() / "bad.yaml";
  std::ofstream(settings) << lumaslam::test::readTextFile(sourceDir() / "configs" /
                                                          "tum_fr1_rgbd.yaml")
                          << "\nTracking.minLocalMapInliers: 0\n";
  const auto result =
      runCli("run --dataset tum:/nowhere --settings " + settings.string() + " --print-settings");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("key 'Tracking.minLocalMapInliers': must be >= 1, found 0"),
            std::string::npos)
      << result.output;
}

}  // namespace
