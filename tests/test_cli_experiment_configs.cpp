// Configurations that change the settings of their runs (issue 19: "settings file + overrides:
// ..., sensor"): `settings:` replaces the dataset's file, `sensor:` runs another sensor of the
// dataset (the rgb stream of an RGB-D dataset as monocular), both through a settings copy.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "experiment_tables.h"
#include "test_cli.h"

namespace {

using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;
using lumaslam::test::writeFile;
namespace fs = std::filesystem;

constexpr const char* kPlan = R"(datasets:
  - name: seq
    spec: "tum:seq"
configurations:
  - name: rgbd
    enhance: off
    sequential: true
  - name: mono
    sensor: mono
    enhance: off
    sequential: true
  - name: fewer
    settings: fewer.yaml
    enhance: off
    sequential: true
  - name: fewer-mono
    settings: fewer.yaml
    sensor: mono
    enhance: off
    sequential: true
)";

nlohmann::json summaryOf(const fs::path& out, const std::string& config) {
  std::ifstream in(out / "runs" / "seq" / config / "run_1" / "summary.json");
  return nlohmann::json::parse(in);
}

std::string alignmentOf(const nlohmann::json& summary) {
  return summary["evaluation"]["alignment"]["mode"].get<std::string>();
}

TEST(CliExperimentConfigs, SettingsAndSensorOfAConfigurationReachItsRuns) {
  TempDir dir("cli_experiment_configs");
  const auto made =
      runCli("synth " + (dir.path() / "seq").string() + " --preset xyz-rgbd --frames 40");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  std::string fewer = readTextFile(dir.path() / "seq" / "settings.yaml");
  const auto at = fewer.find("ORBextractor.nFeatures: 1000");
  ASSERT_NE(at, std::string::npos);
  fewer.replace(at, 28, "ORBextractor.nFeatures: 600");
  writeFile(dir.path() / "fewer.yaml", fewer);
  const auto plan = writeFile(dir.path() / "plan.yaml", kPlan);
  const auto out = dir.path() / "out";
  const auto run = runCli("experiment " + plan.string() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;

  // RGB-D runs are aligned with SE3, monocular ones with Sim3 (their scale is unobservable).
  EXPECT_EQ(alignmentOf(summaryOf(out, "rgbd")), "se3");
  EXPECT_EQ(alignmentOf(summaryOf(out, "mono")), "sim3");
  EXPECT_EQ(alignmentOf(summaryOf(out, "fewer-mono")), "sim3");
  // `settings:` alone is used as it is; with `sensor:` a copy of it is.
  EXPECT_EQ(fs::path(summaryOf(out, "fewer")["settings"].get<std::string>()),
            dir.path() / "fewer.yaml");
  const fs::path copy = summaryOf(out, "fewer-mono")["settings"].get<std::string>();
  EXPECT_EQ(copy, out / "settings" / "seq" / "fewer-mono.yaml");
  const std::string copied = readTextFile(copy);
  EXPECT_NE(copied.find("ORBextractor.nFeatures: 600"), std::string::npos) << copied;
  EXPECT_NE(copied.find("System.sensor: \"mono\""), std::string::npos) << copied;
  // 600 features instead of 1000 change the run.
  EXPECT_NE(readTextFile(out / "runs/seq/fewer/run_1/trajectory.txt"),
            readTextFile(out / "runs/seq/rgbd/run_1/trajectory.txt"));
}

TEST(CliExperimentConfigs, BadSettingsOrSensorAreErrorsNamingTheKey) {
  TempDir dir("cli_experiment_configs_errors");
  const std::string head =
      "datasets:\n  - spec: \"synth:xyz-rgbd\"\n    frames: 10\n"
      "configurations:\n  - name: c\n";
  const std::map<std::string, std::string> cases = {
      {"    sensor: sonar\n", "configurations[0].sensor: 'sonar'"},
      {"    settings: missing.yaml\n", "configurations[0].settings"},
  };
  for (const auto& [keys, expected] : cases) {
    const auto plan = writeFile(dir.path() / "plan.yaml", head + keys);
    const auto run =
        runCli("experiment " + plan.string() + " --out " + (dir.path() / "o").string());
    EXPECT_NE(run.exit_code, 0) << keys;
    EXPECT_NE(run.output.find(expected), std::string::npos) << keys << run.output;
  }
}

}  // namespace
