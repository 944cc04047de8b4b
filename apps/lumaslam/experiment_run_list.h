#pragma once
// The runs of an experiment, kept in DIR/plan_runs.json by `lumaslam experiment` (direct or
// --emit) so that `lumaslam experiment collect DIR` tabulates the same rows without the plan:
// the plan's relative paths and synth data need not be found again.
#include <filesystem>
#include <string>
#include <vector>

#include "experiment_cells.h"

namespace lumaslam::cli {

struct RunList {
  std::vector<ExperimentRun> runs;
  std::string baseline;  // the plan's baseline configuration (report.html)
};

// Writes DIR/plan_runs.json: the plan file, its baseline and each run's dataset, config and run
// index.
void writeRunList(const Plan& plan, const std::vector<ExperimentRun>& runs,
                  const std::filesystem::path& dir);

// The runs of DIR/plan_runs.json, each with options.out set to its folder under DIR/runs/ (the
// other options are not kept), and the baseline (default: the first run's configuration).
// Throws Error naming DIR when there is no such file.
RunList readRunList(const std::filesystem::path& dir);

}  // namespace lumaslam::cli
