// `perturb:` datasets of an experiment plan (issue 19): one dataset per level, copied as
// `lumaslam perturb` copies it (of a dataset folder, or of a synth dataset once generated).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "experiment_tables.h"
#include "test_cli.h"

namespace {

using lumaslam::test::readCsv;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;
using lumaslam::test::writeFile;
namespace fs = std::filesystem;

// A TUM-layout dataset folder (made by synth beforehand) and a synth dataset, each plain and
// darkened at levels 0 (an exact copy) and 4.
constexpr const char* kPlan = R"(datasets:
  - name: seq
    spec: "tum:seq"
  - name: seq
    spec: "tum:seq"
    perturb: dark
    levels: [0, 4]
  - name: gen
    spec: "synth:xyz-rgbd"
    frames: 20
    perturb: dark
    levels: 4
configurations:
  - name: plain
    enhance: off
    sequential: true
)";

double meanGrey(const fs::path& dataset) {
  fs::path first;
  for (const auto& entry : fs::directory_iterator(dataset / "rgb")) {
    if (first.empty() || entry.path() < first) first = entry.path();
  }
  return cv::mean(cv::imread(first.string(), cv::IMREAD_GRAYSCALE))[0];
}

TEST(CliExperimentPerturb, EachLevelIsADatasetAndLevelZeroRunsAsTheOriginal) {
  TempDir dir("cli_experiment_perturb");
  const auto made =
      runCli("synth " + (dir.path() / "seq").string() + " --preset xyz-rgbd --frames 20");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const auto plan = writeFile(dir.path() / "plan.yaml", kPlan);
  const auto out = dir.path() / "out";
  const auto run = runCli("experiment " + plan.string() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;

  std::map<std::string, std::string> ate;
  for (const auto& row : readCsv(out / "results.csv")) {
    EXPECT_EQ(row.at("status"), "complete") << row.at("dataset");
    ate[row.at("dataset")] = row.at("ate_rmse");
  }
  ASSERT_EQ(ate.size(), 4U);
  for (const char* name : {"seq", "seq-dark0", "seq-dark4", "gen-s1-dark4"}) {
    EXPECT_EQ(ate.count(name), 1U) << name;
  }
  // Level 0 is an exact copy: the same sequential run, to the byte.
  const auto trajectory = [&](const std::string& dataset) {
    return readTextFile(out / "runs" / dataset / "plain" / "run_1" / "trajectory.txt");
  };
  EXPECT_EQ(trajectory("seq-dark0"), trajectory("seq"));
  EXPECT_EQ(ate["seq-dark0"], ate["seq"]);
  // Level 4 darkens the copies, of the folder and of the generated sequence.
  const auto perturbed = out / "data" / "perturbed";
  EXPECT_TRUE(fs::exists(perturbed / "seq-dark4" / "perturbation.txt"));
  EXPECT_LT(meanGrey(perturbed / "seq-dark4"), 0.5 * meanGrey(dir.path() / "seq"));
  EXPECT_LT(meanGrey(perturbed / "xyz-rgbd-s1-f20-dark4"),
            0.5 * meanGrey(out / "data" / "xyz-rgbd-s1-f20"));

  // Run again: the copies are reused, nothing is redone.
  const auto time_before = fs::last_write_time(perturbed / "seq-dark4" / "perturbation.txt");
  const auto again = runCli("experiment " + plan.string() + " --out " + out.string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(fs::last_write_time(perturbed / "seq-dark4" / "perturbation.txt"), time_before);
}

TEST(CliExperimentPerturb, BadPerturbKeysAreErrorsNamingTheKey) {
  TempDir dir("cli_experiment_perturb_errors");
  const auto out = dir.path() / "out";
  const std::string head = "datasets:\n  - spec: \"synth:xyz-rgbd\"\n    frames: 10\n";
  const std::string tail = "configurations:\n  - name: plain\n";
  const std::map<std::string, std::string> cases = {
      {"    perturb: darkk\n    levels: [1]\n", "datasets[0].perturb"},
      {"    perturb: dark\n    levels: [7]\n", "datasets[0].levels"},
      {"    perturb: dark\n", "datasets[0].levels: missing"},
      {"    levels: [1]\n", "datasets[0].levels: only with perturb"},
  };
  for (const auto& [keys, expected] : cases) {
    const auto plan = writeFile(dir.path() / "plan.yaml", head + keys + tail);
    const auto run = runCli("experiment " + plan.string() + " --out " + out.string());
    EXPECT_NE(run.exit_code, 0) << keys;
    EXPECT_NE(run.output.find(expected), std::string::npos) << keys << run.output;
    EXPECT_NE(run.output.find("plan.yaml"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out / "data")) << keys;  // checked before anything is made
  }
}

}  // namespace
