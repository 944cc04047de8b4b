// The plans shipped in experiments/ (docs/experiments.md): each one parses and gives the
// expected number of jobs, checked with `experiment PLAN --dry-run` (the job lines --emit would
// write, without generating the synthetic data: hundreds of MB for the shipped plans), and its
// relative model paths resolve to the shared models folder. Also `detector_classes:`, which
// the YOLO rows of dynamic.yaml need: the runs get a copy of the dataset's settings with only
// Detector.classes replaced.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>

#include "test_cli.h"

namespace {

using lumaslam::test::modelsDir;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::runShell;
using lumaslam::test::sourceDir;
using lumaslam::test::TempDir;
namespace fs = std::filesystem;

// `lumaslam experiment PLAN --out OUT --dry-run`, its stdout (the job lines) into `jobs`; the
// result holds stderr.
lumaslam::test::CliResult dryRun(const fs::path& plan, const fs::path& out, const fs::path& jobs) {
  return lumaslam::test::runShell("{ " + lumaslam::test::cliPath().string() + " experiment " +
                                  plan.string() + " --out " + out.string() + " --dry-run > " +
                                  jobs.string() + "; }");
}

// Runs (= jobs of a fresh --out) of each shipped plan: datasets x configurations x runs.
const std::map<std::string, long> kJobs = {
    {"dynamic.yaml", 3 * 5 * 2},
    {"enhancement_ablation.yaml", (2 + 3) * 4 * 2},  // 2 synth + V1_01 at 3 dark levels
    {"timing.yaml", 3 * 2 * 3},
};

TEST(CliExperimentPlans, EveryShippedPlanParsesAndGivesItsJobs) {
  TempDir dir("cli_experiment_plans");
  int plans = 0;
  for (const auto& entry : fs::directory_iterator(sourceDir() / "experiments")) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().filename().string();
    ASSERT_EQ(kJobs.count(name), 1U) << name << ": a new shipped plan; add its job count here";
    const auto out = dir.path() / entry.path().stem();
    const auto jobs = dir.path() / (name + ".jobs");
    const auto result = dryRun(entry.path(), out, jobs);
    ASSERT_EQ(result.exit_code, 0) << name << ": " << result.output;
    const std::string lines = readTextFile(jobs);
    EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), kJobs.at(name)) << name;
    EXPECT_FALSE(fs::exists(out)) << name << ": --dry-run wrote " << out;
    ++plans;
  }
  EXPECT_EQ(plans, static_cast<int>(kJobs.size()));
}

// The YOLO configurations name ../../shared/models/ from experiments/: the shared folder next
// to the checkout, LUMASLAM_SHARED_DIR's default.
TEST(CliExperimentPlans, DynamicYoloRowsUseTheSharedModel) {
  TempDir dir("cli_experiment_plans_yolo");
  const auto jobs = dir.path() / "jobs.txt";
  const auto plan = sourceDir() / "experiments" / "dynamic.yaml";
  const auto result = dryRun(plan, dir.path() / "out", jobs);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::string lines = readTextFile(jobs);
  static const std::regex yolo("--detector=yolo:([^ \n]+)");
  int found = 0;
  for (auto it = std::sregex_iterator(lines.begin(), lines.end(), yolo);
       it != std::sregex_iterator(); ++it) {
    const fs::path model = (*it)[1].str();
    EXPECT_TRUE(model.is_absolute()) << model;
    EXPECT_EQ(fs::weakly_canonical(model),
              fs::weakly_canonical(sourceDir() / ".." / "shared" / "models" / "yolov5n-320.onnx"));
    std::error_code same_folder_unknown;
    if (fs::exists(modelsDir() / "yolov5n-320.onnx") &&
        fs::equivalent(modelsDir(), sourceDir() / ".." / "shared" / "models",
                       same_folder_unknown)) {
      EXPECT_TRUE(fs::exists(model)) << model;
    }
    ++found;
  }
  EXPECT_EQ(found, 3 * 2 * 2);  // yolo and yolo-geometry on 3 datasets, 2 runs
  // Each with its person-only settings (detector_classes: person).
  static const std::regex person_settings(
      "--settings=[^ \n]+/settings/[^ \n/]+/yolo[^ \n/]*\\.yaml "
      "[^\n]*--detector=yolo:");
  const auto with_settings = std::distance(
      std::sregex_iterator(lines.begin(), lines.end(), person_settings), std::sregex_iterator());
  EXPECT_EQ(with_settings, 3 * 2 * 2);
}

std::vector<std::string> linesOf(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(CliExperimentPlans, DetectorClassesRunWithACopyOfTheSettings) {
  TempDir dir("cli_experiment_plans_classes");
  const auto data = dir.path() / "walk";
  const auto synth = runCli("synth " + data.string() + " --preset walking-xyz-rgbd --frames 5");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const auto plan = dir.path() / "plan.yaml";
  std::ofstream(plan) << "datasets:\n  - spec: \"tum:walk\"\n    frames: 5\nconfigurations:\n"
                         "  - name: person\n    detector: \"boxes:{dataset}/detections.txt\"\n"
                         "    detector_classes: person\n    sequential: true\n";
  const auto out = dir.path() / "out";
  const auto emit =
      runCli("experiment " + plan.string() + " --out " + out.string() + " --emit parallel");
  ASSERT_EQ(emit.exit_code, 0) << emit.output;
  const auto copy = out / "settings" / "walk" / "person.yaml";
  const auto original = linesOf(data / "settings.yaml");
  const auto copied = linesOf(copy);
  ASSERT_EQ(copied.size(), original.size());
  int replaced = 0;
  for (std::size_t i = 0; i < copied.size(); ++i) {
    if (original[i].rfind("Detector.classes:", 0) == 0) {
      EXPECT_EQ(original[i], "Detector.classes: \"person,box\"");
      EXPECT_EQ(copied[i], "Detector.classes: \"person\"");
      ++replaced;
    } else {
      EXPECT_EQ(copied[i], original[i]);
    }
  }
  EXPECT_EQ(replaced, 1);
  const std::string jobs = readTextFile(out / "jobs.txt");
  EXPECT_NE(jobs.find("--settings=" + copy.string()), std::string::npos) << jobs;
  const auto job = runShell("sh " + (out / "jobs.txt").string());
  ASSERT_EQ(job.exit_code, 0) << job.output;
  const auto collect = runCli("experiment collect " + out.string());
  ASSERT_EQ(collect.exit_code, 0) << collect.output;
  EXPECT_NE(readTextFile(out / "results.csv").find("walk,person,1,complete,5,"), std::string::npos)
      << readTextFile(out / "results.csv");
}

}  // namespace
