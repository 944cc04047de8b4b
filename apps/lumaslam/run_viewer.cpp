#include "run_viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include "lumaslam/track/tracker.h"

namespace lumaslam::cli {
namespace {

bool isLoopback(const std::string& address) {
  return address == "127.0.0.1" || address == "localhost" || address == "::1";
}

viewer::FrameView frameViewOf(io::FrameData& frame, const FrameResult& result,
                              const Pipeline& system) {
  viewer::FrameView view;
  view.index = frame.index;
  view.timestamp = frame.timestamp;
  view.state = track::toString(result.outcome.state);
  view.step = track::toString(result.outcome.step);
  view.inliers = result.outcome.inliers;
  view.keyframe = result.outcome.new_keyframe;
  view.relocalized = result.outcome.relocalized;
  view.map = static_cast<int>(result.outcome.map);
  view.camera_centre = result.centre_in_map;
  view.raw = std::move(frame.image);  // the reader's next frame is a new image
  view.right = std::move(frame.right);
  // The enhancer may reuse its buffers for the next frame: the view keeps its own copy.
  view.features_image = result.feature_image.clone();
  view.overlays_fit_raw = !system.rectifiesStereo();
  view.kept = result.kept_features;
  view.dropped = result.dropped_features;
  view.boxes = result.dynamic_boxes;
  view.dynamic_mask = result.dynamic_mask;
  view.moving_features = result.outcome.moving_features;
  const auto& t = result.timing;
  view.timing = {t.enhance, t.features, t.tracking, t.mapping, t.detection_wait, t.total};
  return view;
}

// CPU time of the calling thread (ms).
double threadCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

// Time the calling thread has spent runnable but waiting for a core (ms): the second field of
// the kernel's /proc/thread-self/schedstat (run_delay, ns). Nullopt where the kernel has none.
// The file stays open per thread (a pread costs microseconds, an open tens of them).
std::optional<double> threadRunqueueWaitMs() {
  struct SchedstatFile {
    int fd = ::open("/proc/thread-self/schedstat", O_RDONLY | O_CLOEXEC);
    ~SchedstatFile() {
      if (fd >= 0) ::close(fd);
    }
  };
  thread_local const SchedstatFile file;
  if (file.fd < 0) return std::nullopt;
  char text[128];
  const ssize_t size = ::pread(file.fd, text, sizeof text - 1, 0);
  if (size <= 0) return std::nullopt;
  text[size] = '\0';
  unsigned long long on_cpu_ns = 0;
  unsigned long long run_delay_ns = 0;
  if (std::sscanf(text, "%llu %llu", &on_cpu_ns, &run_delay_ns) != 2) return std::nullopt;
  return static_cast<double>(run_delay_ns) * 1e-6;
}

// Median / p99 / max of `values`.
nlohmann::json quantiles(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const auto at = [&](double q) {
    return values.empty() ? 0.0 : values[static_cast<std::size_t>(q * (values.size() - 1))];
  };
  return {{"median", at(0.5)}, {"p99", at(0.99)}, {"max", at(1.0)}};
}

}  // namespace

std::unique_ptr<viewer::Viewer> startViewer(const RunOptions& options, const Pipeline& system) {
  if (!options.viewer_port) return nullptr;
  viewer::ViewerOptions viewer_options;
  viewer_options.address = options.viewer_address;
  viewer_options.port = *options.viewer_port;
  viewer_options.start_paused = options.viewer_paused;
  auto viewer = std::make_unique<viewer::Viewer>(viewer_options, system.map());
  if (!isLoopback(options.viewer_address)) {
    spdlog::warn(
        "viewer: listening on {}: anyone who can reach this machine sees the run and "
        "can pause it",
        options.viewer_address);
  }
  std::printf("viewer: %s%s\n", viewer->url().c_str(),
              options.viewer_paused ? " (paused: press Step or Resume)" : "");
  std::fflush(stdout);
  return viewer;
}

HandoverTime publishFrame(viewer::Viewer& viewer, io::FrameData& frame, const FrameResult& result,
                          const Pipeline& system) {
  // The schedstat reads lie inside the wall window, so wall >= CPU + run-queue wait.
  const auto start = std::chrono::steady_clock::now();
  const std::optional<double> waited_before = threadRunqueueWaitMs();
  const double cpu_start = threadCpuMs();
  viewer.publish(frameViewOf(frame, result, system));
  const double cpu_ms = threadCpuMs() - cpu_start;
  const std::optional<double> waited_after = threadRunqueueWaitMs();
  const auto end = std::chrono::steady_clock::now();
  HandoverTime time{std::chrono::duration<double, std::milli>(end - start).count(), cpu_ms,
                    std::nullopt};
  if (waited_before && waited_after) time.runqueue_ms = *waited_after - *waited_before;
  return time;
}

void keepServing(const viewer::Viewer& viewer, const StopOnSignal& stop) {
  if (stop.requested()) return;
  std::printf("viewer: the run has ended; still serving %s until Ctrl-C\n", viewer.url().c_str());
  std::fflush(stdout);
  while (!stop.requested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

nlohmann::json viewerSummary(const viewer::Viewer& viewer,
                             const std::vector<HandoverTime>& handovers) {
  std::vector<double> wall, cpu, runqueue, other;
  for (const HandoverTime& handover : handovers) {
    wall.push_back(handover.wall_ms);
    cpu.push_back(handover.cpu_ms);
    if (!handover.runqueue_ms) continue;
    runqueue.push_back(*handover.runqueue_ms);
    other.push_back(handover.wall_ms - handover.cpu_ms - *handover.runqueue_ms);
  }
  nlohmann::json summary = {{"url", viewer.url()},
                            {"frames_published", viewer.framesPublished()},
                            {"frames_dropped", viewer.framesDropped()},
                            {"handover_ms", quantiles(wall)},
                            {"handover_cpu_ms", quantiles(cpu)}};
  if (runqueue.size() == handovers.size()) {
    summary["handover_runqueue_ms"] = quantiles(runqueue);
    // Neither on a core nor waiting for one: blocked (a lock, a page fault's I/O), or time the
    // virtual CPU itself did not run, which the guest kernel cannot see.
    summary["handover_other_ms"] = quantiles(other);
  }
  return summary;
}

}  // namespace lumaslam::cli
