#pragma once
// The cells of an experiment (dataset x configuration x run index), each run into
// DIR/runs/<dataset>/<config>/run_<k>/ exactly as `lumaslam run --out` would. Resumable: a run
// whose summary.json says "complete" is kept, any other run folder is run again.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "experiment_plan.h"
#include "run_pipeline.h"

namespace lumaslam::cli {

struct ExperimentRun {
  std::string dataset;
  std::string config;
  int run = 1;
  RunOptions options;     // options.out is the run folder
  bool external = false;  // an `external:` trajectory: evaluated, never run (no job)
};

// DIR/runs/<dataset>/<config>/run_<k>/
std::filesystem::path runFolder(const std::filesystem::path& runs_dir, const std::string& dataset,
                                const std::string& config, int run);

// Per dataset: its configurations' runs, then its external trajectories (external = true).
std::vector<ExperimentRun> experimentRuns(const Plan& plan, const std::filesystem::path& runs_dir);

// True when the run folder holds a summary.json with status "complete".
bool isComplete(const std::filesystem::path& run_folder);

struct RunsOutcome {
  int done = 0;                                         // runs done now
  int kept = 0;                                         // complete from before, not redone
  std::map<std::filesystem::path, std::string> errors;  // run folder -> error
  int exit_code = 0;  // non-zero if any run failed; 128 + signal when stopped by one
};

// Runs every run that is not complete (external ones are not runs); stops at the first run stopped
// by a signal.
RunsOutcome runMissing(const std::vector<ExperimentRun>& runs);

}  // namespace lumaslam::cli
