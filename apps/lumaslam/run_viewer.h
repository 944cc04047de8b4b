#pragma once
// `lumaslam run --viewer`: the live viewer beside the frame loop (docs/viewer.md).
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/pipeline.h"
#include "lumaslam/viewer/viewer.h"
#include "run_pipeline.h"
#include "stop_signal.h"

namespace lumaslam::cli {

// Null unless options.viewer asks for one; prints its address (and a warning when it is
// reachable from other machines).
std::unique_ptr<viewer::Viewer> startViewer(const RunOptions& options, const Pipeline& system);

// Hands one tracked frame to the viewer; `frame`'s images move into the view. Returns the
// time the tracking thread spent on it (ms).
double publishFrame(viewer::Viewer& viewer, io::FrameData& frame, const FrameResult& result,
                    const Pipeline& system);

// `--viewer-keep`: after the results are written, serve the final map until SIGINT / SIGTERM.
void keepServing(const viewer::Viewer& viewer, const StopOnSignal& stop);

// summary.json's "viewer": address, frames handed over and shown, tracking-thread cost.
nlohmann::json viewerSummary(const viewer::Viewer& viewer, const std::vector<double>& handover_ms);

}  // namespace lumaslam::cli
