// `lumaslam experiment PLAN --out DIR`: every dataset x configuration x run of a small plan,
// the result tables, resuming (a finished experiment does no work, a run without its
// summary.json is redone alone), and bad plans as errors naming the plan file and key.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "experiment_tables.h"
#include "test_cli.h"

namespace {

using lumaslam::test::readCsv;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;
using lumaslam::test::writeFile;
namespace fs = std::filesystem;

// 2 synthetic datasets x 2 configurations x 2 runs, all sequential (deterministic).
constexpr const char* kPlan = R"(runs: 2
datasets:
  - spec: "synth:xyz-rgbd"
    seeds: [1, 2]
    frames: 40
configurations:
  - name: enhance-off  # comments end a value, as in YAML: "off", not "off  # ..."
    enhance: off  # no enhancement: the baseline
    sequential: true
  - name: default
    sequential: true
)";

std::map<fs::path, fs::file_time_type> summaryTimes(const fs::path& runs) {
  std::map<fs::path, fs::file_time_type> times;
  for (const auto& entry : fs::recursive_directory_iterator(runs)) {
    if (entry.path().filename() == "summary.json") times[entry.path()] = entry.last_write_time();
  }
  return times;
}

TEST(CliExperiment, RunsEveryCellTabulatesAndResumesOnlyUnfinishedRuns) {
  TempDir dir("cli_experiment");
  const auto plan = writeFile(dir.path() / "plan.yaml", kPlan);
  const auto out = dir.path() / "out";
  const std::string command = "experiment " + plan.string() + " --out " + out.string();
  const auto first = runCli(command);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  for (const char* name : {"results.csv", "results.json", "summary.csv"}) {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  EXPECT_TRUE(fs::exists(out / "data" / "xyz-rgbd-s1-f40" / "settings.yaml"));
  const auto run_folder = out / "runs" / "xyz-rgbd-s2" / "default" / "run_1";
  for (const char* name : {"trajectory.txt", "keyframes.txt", "timing.csv", "summary.json"}) {
    EXPECT_TRUE(fs::exists(run_folder / name)) << name;
  }

  const auto rows = readCsv(out / "results.csv");
  ASSERT_EQ(rows.size(), 8U);
  std::map<std::string, std::string> ate_of_cell;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "complete");
    EXPECT_EQ(row.at("frames"), "40");
    ASSERT_FALSE(row.at("ate_rmse").empty()) << row.at("dataset");
    std::printf("%s / %s: ATE rmse %.2f mm\n", row.at("dataset").c_str(), row.at("config").c_str(),
                1000.0 * std::stod(row.at("ate_rmse")));
    // ~2x the worst cell's ATE (issue 22): 2.03 / 1.88 mm (seed 1, enhance-off / default), 2.29 /
    // 2.77 mm (seed 2), sequential; 2026-12-08, `build/tests/test_cli_experiment
    // --gtest_filter=*RunsEveryCell*`, the printed lines.
    EXPECT_LT(std::stod(row.at("ate_rmse")), 0.0055)
        << row.at("dataset") << " " << row.at("config");
    // Sequential runs are deterministic: both runs of a cell give the same ATE.
    const auto [it, first_run] =
        ate_of_cell.emplace(row.at("dataset") + "/" + row.at("config"), row.at("ate_rmse"));
    if (!first_run) {
      EXPECT_EQ(row.at("ate_rmse"), it->second) << it->first;
    }
  }
  EXPECT_EQ(ate_of_cell.size(), 4U);
  const auto cells = readCsv(out / "summary.csv");
  ASSERT_EQ(cells.size(), 4U);
  for (const auto& cell : cells) {
    EXPECT_EQ(cell.at("runs"), "2");
    EXPECT_EQ(cell.at("complete"), "2");
    EXPECT_EQ(cell.at("ate_rmse_min"),
              ate_of_cell.at(cell.at("dataset") + "/" + cell.at("config")));
    EXPECT_EQ(cell.at("ate_rmse_min"), cell.at("ate_rmse_max"));
    EXPECT_EQ(cell.at("tracked_min"), cell.at("tracked_median"));
  }

  // A finished experiment: no SLAM work, no run folder touched.
  const auto times = summaryTimes(out / "runs");
  ASSERT_EQ(times.size(), 8U);
  const auto again = runCli(command);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("no SLAM work to do"), std::string::npos) << again.output;
  EXPECT_EQ(summaryTimes(out / "runs"), times);

  // A run without its summary.json (as if killed half way) is redone, and only that one.
  fs::remove(run_folder / "summary.json");
  const auto resumed = runCli(command);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("7 complete from before, 1 to run"), std::string::npos)
      << resumed.output;
  const auto after = summaryTimes(out / "runs");
  ASSERT_EQ(after.size(), 8U);
  for (const auto& [file, time] : times) {
    if (file.parent_path() != run_folder) {
      EXPECT_EQ(after.at(file), time) << file;
    }
  }
  EXPECT_EQ(readCsv(out / "results.csv").size(), 8U);
}

TEST(CliExperiment, ABadPlanIsAnErrorNamingThePlanFileAndKey) {
  TempDir dir("cli_experiment_bad");
  const auto out = (dir.path() / "out").string();
  const auto expectError = [&](const std::string& name, const std::string& text,
                               const std::string& key) {
    const auto plan = writeFile(dir.path() / name, text);
    const auto result = runCli("experiment " + plan.string() + " --out " + out);
    EXPECT_NE(result.exit_code, 0) << name;
    EXPECT_NE(result.output.find(plan.string() + ": " + key), std::string::npos) << result.output;
  };
  const std::string configs = "configurations:\n  - name: a\n";
  expectError("unknown.yaml", "datasets:\n  - spec: \"synth:xyz-rgbd\"\n    seed: 1\n" + configs,
              "datasets[0].seed: unknown key");
  expectError("no_datasets.yaml", "runs: 2\n" + configs, "datasets: missing");
  expectError("missing_folder.yaml",
              "datasets:\n  - spec: \"tum:" + (dir.path() / "nothing").string() + "\"\n" + configs,
              "datasets[0].spec");
  expectError("typo.yaml",
              "datasets:\n  - spec: \"synth:xyz-rgbd\"\nconfigurations:\n  - name: a\n"
              "    sequental: true\n",
              "configurations[0].sequental: unknown key");
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "runs"));
}

}  // namespace
