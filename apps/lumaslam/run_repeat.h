#pragma once
// `lumaslam run --repeat N`: the same run N times (threaded mapping makes runs differ), each
// into OUT/run_K, then the spread users report next to ATE tables: min / median / max of ATE
// RMSE, frames tracked and median ms per frame, printed and written to OUT/repeatability.json.
#include "run_pipeline.h"

namespace lumaslam::cli {

// Returns the process exit code (non-zero if any run failed); throws Error for bad input.
int runRepeated(const RunOptions& options, int repeats);

}  // namespace lumaslam::cli
