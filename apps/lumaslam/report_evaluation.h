#pragma once
// The run's evaluation again, for the plots of `lumaslam report`: trajectory.txt against the
// dataset's ground truth, aligned as `lumaslam run` aligns it (SE3; Sim3 for monocular). The
// numbers of the report come from summary.json; this gives the per-pose errors behind them.
#include <optional>
#include <string>

#include "lumaslam/eval/evaluation.h"
#include "run_folder.h"

namespace lumaslam::cli {

struct Reevaluation {
  std::optional<eval::EvaluationReport> report;
  std::string problem;  // why there is no report (no ground truth, dataset gone, ...)
};

// Never throws: what went wrong is in `problem`.
Reevaluation reevaluate(const RunFolder& run);

}  // namespace lumaslam::cli
