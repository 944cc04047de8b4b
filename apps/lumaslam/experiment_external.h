#pragma once
// The `external:` rows of an experiment plan (docs/experiments.md): other systems'
// trajectories evaluated against the dataset's ground truth with the evaluation `lumaslam run`
// uses (SE3; Sim3 for monocular), each written as a complete run folder
// DIR/runs/<dataset>/<name>/run_<k>/ (summary.json, trajectory.txt, evaluation.svg), so that
// the tables and `collect` read them like any run.
#include <filesystem>

#include "experiment_plan.h"

namespace lumaslam::cli {

// Evaluates every external trajectory (after the synth data is prepared: the specs point at
// it). Throws Error naming the plan file and key when a dataset has no ground truth or a
// trajectory does not match it.
void evaluateExternals(const Plan& plan, const std::filesystem::path& runs_dir);

}  // namespace lumaslam::cli
