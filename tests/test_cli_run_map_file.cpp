// `lumaslam run --save-map / --load-map --localization` and `lumaslam map info` (docs/maps.md).
#include <gtest/gtest.h>

#include <fstream>

#include "test_cli.h"

namespace {

using lumaslam::test::readRunSummary;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

TEST(CliRunMapFile, SavesDescribesAndLocalizesInAMap) {
  TempDir dir("cli_map");
  const auto data = dir.path() / "data";
  const auto map = dir.path() / "room.map";
  ASSERT_EQ(runCli("synth " + data.string() + " --preset xyz-rgbd --frames 60 --seed 3").exit_code,
            0);
  const auto mapped = runCli("run --dataset tum:" + data.string() + " --sequential --out " +
                             (dir.path() / "mapped").string() + " --save-map " + map.string());
  ASSERT_EQ(mapped.exit_code, 0) << mapped.output;
  const auto mapped_summary = readRunSummary(dir.path() / "mapped");
  EXPECT_EQ(mapped_summary["map_file"]["saved"].get<std::string>(), map.string());

  const auto info = runCli("map info " + map.string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("keyframes " + std::to_string(mapped_summary["keyframes"].get<int>())),
            std::string::npos)
      << info.output;
  EXPECT_NE(info.output.find("sensor rgbd"), std::string::npos) << info.output;

  const auto localized = runCli("run --dataset tum:" + data.string() + " --sequential --out " +
                                (dir.path() / "localized").string() + " --load-map " +
                                map.string() + " --localization");
  ASSERT_EQ(localized.exit_code, 0) << localized.output;
  const auto summary = readRunSummary(dir.path() / "localized");
  EXPECT_GE(summary["tracked"].get<int>(), 57);
  EXPECT_EQ(summary["map_file"]["keyframes_added"].get<int>(), 0);
  EXPECT_TRUE(summary["map_file"]["localization"].get<bool>());
  EXPECT_LT(summary["evaluation"]["ate"]["rmse"].get<double>(), 0.02);
}

TEST(CliRunMapFile, BadMapFilesAndFlagsAreClearErrors) {
  TempDir dir("cli_map");
  const auto bogus = dir.path() / "bogus.map";
  std::ofstream(bogus) << "not a map";
  const auto info = runCli("map info " + bogus.string());
  EXPECT_EQ(info.exit_code, 1);
  EXPECT_NE(info.output.find(bogus.string() + ": not a lumaslam map file"), std::string::npos)
      << info.output;
  const auto data = dir.path() / "data";
  ASSERT_EQ(runCli("synth " + data.string() + " --preset xyz-rgbd --frames 5 --seed 3").exit_code,
            0);
  const auto load = runCli("run --dataset tum:" + data.string() + " --out " +
                           (dir.path() / "out").string() + " --load-map " + bogus.string());
  EXPECT_EQ(load.exit_code, 1);
  EXPECT_NE(load.output.find("not a lumaslam map file"), std::string::npos) << load.output;
  const auto flags = runCli("run --dataset tum:" + data.string() + " --localization");
  EXPECT_EQ(flags.exit_code, 1);
  EXPECT_NE(flags.output.find("--load-map"), std::string::npos) << flags.output;
}

}  // namespace
