// The plans shipped in experiments/ (docs/experiments.md): each one parses and gives the
// expected number of jobs, checked with `experiment PLAN --dry-run` (the job lines --emit would
// write, without generating the synthetic data: hundreds of MB for the shipped plans), and its
// relative model paths resolve to the shared models folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <string>

#include "test_cli.h"

namespace {

using lumaslam::test::modelsDir;
using lumaslam::test::readTextFile;
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
    {"enhancement_ablation.yaml", 2 * 4 * 2},
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
}

}  // namespace
