#pragma once
// `lumaslam run --viewer`: the live viewer beside the frame loop (docs/viewer.md).
#include <memory>
#include <optional>
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

// The tracking thread's time handing one frame over (ms): wall time, which on a loaded machine
// includes the time the thread waited for a core, the thread's own CPU time (the work), and the
// time it was runnable but waiting for a core (the kernel's schedstat run_delay; nullopt where
// the kernel does not report it).
struct HandoverTime {
  double wall_ms = 0.0;
  double cpu_ms = 0.0;
  std::optional<double> runqueue_ms;
};

// Hands one tracked frame to the viewer; `frame`'s images move into the view.
HandoverTime publishFrame(viewer::Viewer& viewer, io::FrameData& frame, const FrameResult& result,
                          const Pipeline& system);

// `--viewer-keep`: after the results are written, serve the final map until SIGINT / SIGTERM.
void keepServing(const viewer::Viewer& viewer, const StopOnSignal& stop);

// summary.json's "viewer": address, frames handed over and shown, tracking-thread cost
// (`handover_ms` wall, `handover_cpu_ms` thread CPU time, `handover_runqueue_ms` time waiting for
// a core: median / p99 / max).
nlohmann::json viewerSummary(const viewer::Viewer& viewer,
                             const std::vector<HandoverTime>& handovers);

}  // namespace lumaslam::cli
