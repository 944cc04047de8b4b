// `lumaslam experiment PLAN.yaml --out DIR`: every dataset x configuration x run of a plan
// into DIR/runs/, resumable, and the tables of the results (docs/experiments.md). With
// `--emit parallel|slurm` the runs become jobs for a scheduler instead, and
// `lumaslam experiment collect DIR` tabulates what they wrote.
#include <cstdio>
#include <memory>

#include <spdlog/spdlog.h>

#include "command_registry.h"
#include "experiment_cells.h"
#include "experiment_data.h"
#include "experiment_jobs.h"
#include "experiment_plan.h"
#include "experiment_report.h"
#include "experiment_results.h"
#include "experiment_run_list.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"
#include "run_command_line.h"

namespace lumaslam::cli {
namespace {

struct ExperimentOptions {
  std::filesystem::path plan;
  std::filesystem::path out;
  std::string emit;               // "", "parallel" or "slurm"
  std::filesystem::path collect;  // DIR of `experiment collect DIR`
  CLI::App* collect_cmd = nullptr;
};

std::string quoted(const std::filesystem::path& path) {
  return shellQuote(path.string());
}

void printHowToRun(const std::filesystem::path& out, const std::string& emit, int jobs,
                   std::size_t runs) {
  const std::string collect =
      shellCommandLine({thisExecutable().string(), "experiment", "collect", out.string()});
  if (jobs == 0) {
    std::printf(
        "experiment: all %zu runs are complete, nothing to do (%s is empty); "
        "tabulate with\n  %s\n",
        runs, (out / "jobs.txt").string().c_str(), collect.c_str());
    return;
  }
  const std::string run = emit == "slurm" ? "sbatch " + quoted(out / "jobs.slurm")
                                          : "parallel --jobs N < " + quoted(out / "jobs.txt");
  std::printf(
      "experiment: %d of %zu runs to do, one job a line in %s; run them with\n  %s\n"
      "then tabulate the results with\n  %s\n",
      jobs, runs, (out / "jobs.txt").string().c_str(), run.c_str(), collect.c_str());
}

int emitJobs(const std::vector<ExperimentRun>& runs, const std::filesystem::path& out,
             const std::string& emit) {
  const int jobs = writeJobs(runs, out);
  if (emit == "slurm") writeSlurmScript(out, jobs);
  printHowToRun(out, emit, jobs, runs.size());
  return 0;
}

// Absolute paths throughout, so that emitted jobs run from any folder.
int runExperiment(const ExperimentOptions& options) {
  const auto plan_file = std::filesystem::absolute(options.plan);
  const auto out = std::filesystem::absolute(options.out);
  Plan plan = readPlan(plan_file);
  io::requireWritableFolder(out);
  prepareSynthData(plan, out / "data");
  const auto runs = experimentRuns(plan, out / "runs");
  writeRunList(plan, runs, out);
  if (!options.emit.empty()) return emitJobs(runs, out, options.emit);
  const RunsOutcome outcome = runMissing(runs);
  const auto rows = collectResults(runs, outcome.errors);
  writeResults(rows, out);
  writeExperimentReport(rows, plan.baseline, out);
  std::printf("experiment: %d runs done now, %d kept from before; results in %s\n", outcome.done,
              outcome.kept, (out / "results.csv").string().c_str());
  return outcome.exit_code;
}

int collectExperiment(const std::filesystem::path& dir) {
  const RunList list = readRunList(dir);
  const auto rows = collectResults(list.runs, {});
  writeResults(rows, dir);
  writeExperimentReport(rows, list.baseline, dir);
  int complete = 0;
  for (const auto& row : rows) complete += row.status == "complete" ? 1 : 0;
  std::printf("experiment collect: %d of %zu runs complete; results in %s\n", complete, rows.size(),
              (dir / "results.csv").string().c_str());
  return 0;
}

int runCommand(const ExperimentOptions& options) {
  if (options.collect_cmd->parsed()) {
    if (!options.plan.empty() || !options.out.empty() || !options.emit.empty()) {
      fail("experiment collect DIR takes no PLAN, --out or --emit");
    }
    return collectExperiment(options.collect);
  }
  if (options.plan.empty() || options.out.empty()) {
    fail("experiment needs PLAN and --out DIR (or: experiment collect DIR)");
  }
  return runExperiment(options);
}

void addCollect(CLI::App& cmd, ExperimentOptions& options) {
  options.collect_cmd = cmd.add_subcommand(
      "collect",
      "Tabulate DIR/runs/ into DIR/results.csv, results.json, summary.csv and report.html, e.g. "
      "after the "
      "jobs of --emit ran (runs not done yet: status 'not run')");
  options.collect_cmd->add_option("DIR", options.collect, "Experiment folder (the --out)")
      ->required();
}

const bool registered = registerCommand(
    "experiment",
    "Run every dataset x configuration x run of a plan (resumable) and tabulate the results",
    [](CLI::App& cmd) -> Runner {
      auto options = std::make_shared<ExperimentOptions>();
      // Not ->required(): `experiment collect DIR` has neither (checked in runCommand).
      cmd.add_option(
          "PLAN", options->plan,
          "Experiment plan (YAML, docs/experiments.md); required except for `collect DIR`");
      cmd.add_option("--out", options->out,
                     "Experiment folder: data/, runs/, results.csv, results.json, summary.csv, "
                     "report.html; "
                     "required except for `collect DIR`");
      cmd.add_option("--emit", options->emit,
                     "Run nothing: write DIR/jobs.txt, one `lumaslam run` line per run not yet "
                     "complete, for GNU parallel; slurm: also DIR/jobs.slurm, an array job")
          ->check(CLI::IsMember({"parallel", "slurm"}));
      addCollect(cmd, *options);
      return [options] { return runCommand(*options); };
    });

}  // namespace
}  // namespace lumaslam::cli
