// `lumaslam experiment PLAN.yaml --out DIR`: every dataset x configuration x run of a plan
// into DIR/runs/, resumable, and the tables of the results (docs/experiments.md). With
// `--emit parallel|slurm` the runs become jobs for a scheduler instead, and
// `lumaslam experiment collect DIR` tabulates what they wrote.
#include <algorithm>
#include <cstdio>
#include <memory>

#include <spdlog/spdlog.h>

#include "command_registry.h"
#include "experiment_cells.h"
#include "experiment_data.h"
#include "experiment_external.h"
#include "experiment_jobs.h"
#include "experiment_plan.h"
#include "experiment_report.h"
#include "experiment_results.h"
#include "experiment_run_list.h"
#include "experiment_settings.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"
#include "run_command_line.h"

namespace lumaslam::cli {
namespace {

struct ExperimentOptions {
  std::filesystem::path plan;
  std::filesystem::path out;
  std::string emit;  // "", "parallel" or "slurm"
  bool dry_run = false;
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

// The runs that are SLAM runs (external trajectories are evaluated, not run).
std::size_t slamRuns(const std::vector<ExperimentRun>& runs) {
  return std::count_if(runs.begin(), runs.end(),
                       [](const ExperimentRun& r) { return !r.external; });
}

int emitJobs(const std::vector<ExperimentRun>& runs, const std::filesystem::path& out,
             const std::string& emit) {
  const int jobs = writeJobs(runs, out);
  if (emit == "slurm") writeSlurmScript(out, jobs);
  printHowToRun(out, emit, jobs, slamRuns(runs));
  return 0;
}

// --dry-run: the plan checked and the job lines --emit would write, on stdout; nothing is
// generated, evaluated or written.
int printDryRun(Plan& plan, const std::filesystem::path& out) {
  pointAtSynthData(plan, out / "data");
  const auto runs = experimentRuns(plan, out / "runs");
  const auto lines = jobLines(runs);
  for (const auto& line : lines) std::printf("%s\n", line.c_str());
  std::fprintf(stderr,
               "experiment: %s: %zu datasets, %zu configurations, %zu runs (%zu to do), %zu "
               "external trajectories\n",
               plan.file.string().c_str(), plan.datasets.size(), plan.configs.size(),
               slamRuns(runs), lines.size(), runs.size() - slamRuns(runs));
  return 0;
}

// Absolute paths throughout, so that emitted jobs run from any folder.
int runExperiment(const ExperimentOptions& options) {
  const auto plan_file = std::filesystem::absolute(options.plan);
  const auto out = std::filesystem::absolute(options.out);
  Plan plan = readPlan(plan_file);
  checkPerturbModels(plan);
  if (options.dry_run) return printDryRun(plan, out);
  io::requireWritableFolder(out);
  prepareSynthData(plan, out / "data");
  writeConfigSettings(plan, out);
  evaluateExternals(plan, out / "runs");
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
    if (!options.plan.empty() || !options.out.empty() || !options.emit.empty() || options.dry_run) {
      fail("experiment collect DIR takes no PLAN, --out, --emit or --dry-run");
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
      cmd.add_flag("--dry-run", options->dry_run,
                   "Check the plan and print the job lines --emit would write (one per run not "
                   "yet complete); generate, run and write nothing");
      addCollect(cmd, *options);
      return [options] { return runCommand(*options); };
    });

}  // namespace
}  // namespace lumaslam::cli
