// `lumaslam experiment PLAN --out DIR --emit parallel|slurm` and `experiment collect DIR`: the
// jobs, run by GNU parallel, give the rows of the direct run; every job line reads back to
// itself through `lumaslam run --print-command`; a finished experiment emits no job; the Slurm
// script runs one line per array task; collect without a run list names the folder.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "experiment_tables.h"
#include "test_cli.h"

namespace {

using lumaslam::test::readCsv;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::runShell;
using lumaslam::test::TempDir;
using lumaslam::test::writeFile;
namespace fs = std::filesystem;

// 2 synthetic datasets x 2 configurations x 2 runs, all sequential (deterministic).
constexpr const char* kPlan = R"(runs: 2
datasets:
  - spec: "synth:xyz-rgbd"
    seeds: [1, 2]
    frames: 30
configurations:
  - name: enhance-off
    enhance: off
    sequential: true
  - name: no-loops
    sequential: true
    loop_closing: false
)";

// The test's folder names hold a space and a quote; double quotes keep them one word.
std::string inQuotes(const fs::path& path) {
  std::string quoted = "\"";  // not "\"" + path.string(): a GCC 12 -Wrestrict false positive
  quoted += path.string();
  return quoted + '"';
}

std::vector<std::string> linesOf(const fs::path& file) {
  std::vector<std::string> lines;
  std::istringstream in(readTextFile(file));
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void expectSameRows(const fs::path& a, const fs::path& b, const std::vector<std::string>& columns) {
  const auto rows_a = readCsv(a);
  const auto rows_b = readCsv(b);
  ASSERT_EQ(rows_a.size(), rows_b.size()) << a << " " << b;
  for (std::size_t i = 0; i < rows_a.size(); ++i) {
    for (const auto& column : columns) {
      EXPECT_EQ(rows_a[i].at(column), rows_b[i].at(column)) << b << " row " << i << " " << column;
    }
  }
}

int countStatus(const fs::path& results, const std::string& status) {
  int n = 0;
  for (const auto& row : readCsv(results)) n += row.at("status") == status ? 1 : 0;
  return n;
}

TEST(CliExperimentEmit, JobsRunByGnuParallelGiveTheRowsOfTheDirectRun) {
  ASSERT_EQ(std::system("command -v parallel > /dev/null 2>&1"), 0)
      << "GNU parallel is not installed: run scripts/install-deps.sh";
  TempDir dir("cli_experiment_emit");
  const auto plan = writeFile(dir.path() / "plan.yaml", kPlan);
  const auto direct = dir.path() / "direct";
  const auto ran = runCli("experiment " + plan.string() + " --out " + direct.string());
  ASSERT_EQ(ran.exit_code, 0) << ran.output;

  const auto out = dir.path() / "emit 'B'";
  const std::string emit = "experiment " + plan.string() + " --out " + inQuotes(out) + " --emit ";
  const auto emitted = runCli(emit + "parallel");
  ASSERT_EQ(emitted.exit_code, 0) << emitted.output;
  EXPECT_NE(emitted.output.find("parallel --jobs N <"), std::string::npos) << emitted.output;
  EXPECT_NE(emitted.output.find("experiment collect"), std::string::npos) << emitted.output;
  EXPECT_FALSE(fs::exists(out / "runs")) << "no SLAM work";
  const auto jobs = linesOf(out / "jobs.txt");
  const std::string binary = fs::canonical(lumaslam::test::cliPath()).string();
  ASSERT_EQ(jobs.size(), 8U);
  for (const auto& job : jobs) {
    EXPECT_EQ(job.rfind(binary + " run ", 0), 0U) << job;
    EXPECT_NE(job.find("--dataset=tum:"), std::string::npos) << job;
    const auto printed = runShell(job + " --print-command");
    EXPECT_EQ(printed.output, job + "\n") << "the job's options read back differently";
  }

  const std::string jobs_file = inQuotes(out / "jobs.txt");
  ASSERT_EQ(std::system(("parallel --jobs 2 < " + jobs_file + " > /dev/null 2>&1").c_str()), 0);
  const auto collected = runCli("experiment collect " + inQuotes(out));
  ASSERT_EQ(collected.exit_code, 0) << collected.output;
  EXPECT_NE(collected.output.find("8 of 8 runs complete"), std::string::npos) << collected.output;
  expectSameRows(direct / "results.csv", out / "results.csv",
                 {"dataset", "config", "run", "status", "frames", "tracked", "ate_rmse", "ate_mean",
                  "ate_median", "ate_std"});
  expectSameRows(direct / "summary.csv", out / "summary.csv",
                 {"dataset", "config", "runs", "complete", "ate_rmse_min", "ate_rmse_max"});
  EXPECT_EQ(countStatus(out / "results.csv", "complete"), 8);

  // Every run complete: nothing to do, an empty jobs.txt and no Slurm array of 0 tasks.
  const auto again = runCli(emit + "slurm");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("nothing to do"), std::string::npos) << again.output;
  EXPECT_TRUE(linesOf(out / "jobs.txt").empty());
  EXPECT_FALSE(fs::exists(out / "jobs.slurm"));

  // Three runs undone: three jobs, an array of three tasks; task 2 runs the second line.
  for (const char* run : {"run_1", "run_2"}) {
    fs::remove_all(out / "runs" / "xyz-rgbd-s1" / "no-loops" / run);
  }
  fs::remove(out / "runs" / "xyz-rgbd-s2" / "enhance-off" / "run_2" / "summary.json");
  const auto slurm = runCli(emit + "slurm");
  ASSERT_EQ(slurm.exit_code, 0) << slurm.output;
  EXPECT_NE(slurm.output.find("sbatch "), std::string::npos) << slurm.output;
  EXPECT_EQ(linesOf(out / "jobs.txt").size(), 3U);
  const std::string script = readTextFile(out / "jobs.slurm");
  EXPECT_NE(script.find("#SBATCH --array=1-3\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --cpus-per-task=1\n"), std::string::npos) << script;
  const auto task = runShell("SLURM_ARRAY_TASK_ID=2 sh " + inQuotes(out / "jobs.slurm"));
  ASSERT_EQ(task.exit_code, 0) << task.output;
  ASSERT_EQ(runCli("experiment collect " + inQuotes(out)).exit_code, 0);
  EXPECT_EQ(countStatus(out / "results.csv", "not run"), 2) << readTextFile(out / "results.csv");
  EXPECT_EQ(countStatus(out / "results.csv", "complete"), 6);
}

TEST(CliExperimentEmit, RunPrintCommandReadsBackToTheSameLine) {
  const std::string options =
      "--dataset \"tum:/data/it's here\" --settings s.yaml --out=-o --max-frames 5 "
      "--on-bad-frame stop --strict-settings --enhance clahe --detector none --vocabulary none "
      "--sequential --no-loop-closing --no-motion-evidence --load-map m.bin --localization "
      "--save-map o.bin --save-map-every 25 --viewer 0 --viewer-address 0.0.0.0 --viewer-paused "
      "--viewer-keep";
  const auto first = runCli("run " + options + " --print-command");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  for (const char* word : {"'--dataset=tum:/data/it'\\''s here'",
                           "--settings=s.yaml",
                           "--out=-o",
                           "--max-frames=5",
                           "--on-bad-frame=stop",
                           "--strict-settings",
                           "--enhance=clahe",
                           "--detector=none",
                           "--vocabulary=none",
                           "--sequential",
                           "--no-loop-closing",
                           "--no-motion-evidence",
                           "--load-map=m.bin",
                           "--localization",
                           "--save-map=o.bin",
                           "--save-map-every=25",
                           "--viewer=0",
                           "--viewer-address=0.0.0.0",
                           "--viewer-paused",
                           "--viewer-keep"}) {
    EXPECT_NE(first.output.find(std::string(" ") + word), std::string::npos)
        << word << " in " << first.output;
  }
  const std::string line = first.output.substr(0, first.output.find('\n'));
  const auto second = runShell(line + " --print-command");
  EXPECT_EQ(second.output, first.output);

  const auto defaults = runCli("run --dataset tum:x --print-command");
  EXPECT_EQ(defaults.output.substr(defaults.output.find(" run ")),
            " run --dataset=tum:x --out=lumaslam_out\n");
}

TEST(CliExperimentEmit, CollectWithoutARunListIsAnErrorNamingTheFolder) {
  TempDir dir("cli_experiment_collect");
  const auto result = runCli("experiment collect " + dir.path().string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find(dir.path().string() + ": not an experiment folder"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir.path() / "results.csv"));
}

}  // namespace
