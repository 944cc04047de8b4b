#include "run_pipeline.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <vector>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/eval/evaluation.h"
#include "lumaslam/eval/trajectory_plot.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/io/trajectory_io.h"
#include "lumaslam/loop/loop_closer.h"
#include "lumaslam/system.h"

namespace lumaslam::cli {
namespace {

std::filesystem::path datasetPath(const std::string& spec) {
  const auto colon = spec.find(':');
  return colon == std::string::npos ? spec : spec.substr(colon + 1);
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Every map of the atlas in summary.json; the main one is trajectory.txt, the others (never
// merged into it) trajectory_map<ID>.txt, each in its own world.
nlohmann::json writeMapTrajectories(const System& system, const std::filesystem::path& out) {
  nlohmann::json maps = nlohmann::json::array();
  const map::MapId main = system.mainMap();
  for (const auto& [id, frames] : system.mapTrajectories()) {
    const std::string file =
        id == main ? std::string("trajectory.txt") : fmt::format("trajectory_map{}.txt", id);
    if (id != main) io::writeTrajectory(out / file, frames);
    maps.push_back({{"id", id},
                    {"main", id == main},
                    {"frames", frames.size()},
                    {"first_timestamp", frames.front().timestamp},
                    {"last_timestamp", frames.back().timestamp},
                    {"trajectory", file}});
  }
  return maps;
}

}  // namespace

int runPipeline(const RunOptions& options) {
  auto settings_path = options.settings;
  if (settings_path.empty()) settings_path = datasetPath(options.dataset) / "settings.yaml";
  const auto settings = io::loadSettings(settings_path);
  io::ReaderOptions reader_options;
  reader_options.max_frames = options.max_frames;
  auto reader = io::openDataset(options.dataset, reader_options);
  if (settings.sensor == io::SensorType::Rgbd && !reader->hasDepth()) {
    fail("{}: the settings are RGB-D but dataset {} has no depth", settings_path.string(),
         options.dataset);
  }
  if (settings.sensor == io::SensorType::Stereo && !reader->isStereo()) {
    fail("{}: the settings are stereo but dataset {} has no right images", settings_path.string(),
         options.dataset);
  }
  std::filesystem::create_directories(options.out);

  SystemOptions system_options;
  system_options.enhance_preset = options.enhance_preset;
  system_options.detector = options.detector;
  if (options.sequential) system_options.sequential = true;
  system_options.vocabulary = options.vocabulary;
  if (options.no_loop_closing) system_options.loop_closing = false;
  System system(settings, system_options);

  std::ofstream timing(options.out / "timing.csv");
  timing << "frame,timestamp,state,inliers,enhance_ms,features_ms,tracking_ms,mapping_ms,total_ms,"
            "detection_wait_ms,detection_ms,boxes,dropped_features,map\n";
  const bool progress = isatty(STDERR_FILENO) != 0;
  std::vector<double> totals;
  std::size_t tracked = 0;
  std::size_t relocalized = 0;
  std::size_t frames = 0;
  double dropped_sum = 0.0;
  double wait_sum = 0.0;
  while (auto frame = reader->next()) {
    const auto result = system.track(toSensorFrame(*frame));
    const auto& t = result.timing;
    timing << frame->index << ',' << fmt::format("{:.6f}", frame->timestamp) << ','
           << track::toString(result.outcome.state) << ',' << result.outcome.inliers << ','
           << fmt::format("{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}", t.enhance, t.features, t.tracking,
                          t.mapping, t.total)
           << fmt::format(",{:.3f},{:.3f},{},{},", t.detection_wait, t.detection,
                          result.dynamic_boxes.size(), result.dropped_features.size())
           << (result.outcome.T_w_c ? std::to_string(result.outcome.map) : std::string()) << '\n';
    dropped_sum += static_cast<double>(result.dropped_features.size());
    wait_sum += t.detection_wait;
    totals.push_back(t.total);
    ++frames;
    if (result.outcome.state == track::TrackingState::Ok) ++tracked;
    if (result.outcome.relocalized) ++relocalized;
    if (progress) {
      std::fprintf(stderr, "\rframe %zu/%zu  %s  %.1f ms   ", frames, reader->size(),
                   track::toString(result.outcome.state), t.total);
    }
  }
  if (progress) std::fprintf(stderr, "\n");
  if (frames == 0) fail("{}: the dataset delivered no frames", options.dataset);
  system.shutdown();

  const auto trajectory = system.frameTrajectory();
  io::writeTrajectory(options.out / "trajectory.txt", trajectory);
  io::writeTrajectory(options.out / "keyframes.txt", system.keyFrameTrajectory());
  const nlohmann::json maps = writeMapTrajectories(system, options.out);

  double mean = 0.0;
  for (double v : totals) mean += v / static_cast<double>(totals.size());
  std::size_t loops = 0;
  std::size_t merges = 0;
  if (system.loopCloser()) {
    for (const auto& closed : system.loopCloser()->closedLoops())
      ++(closed.merged_map ? merges : loops);
  }
  nlohmann::json summary = {{"dataset", options.dataset},
                            {"settings", settings_path.string()},
                            {"frames", frames},
                            {"tracked", tracked},
                            {"lost", frames - tracked},
                            {"relocalized", relocalized},
                            {"keyframes", system.keyFrameCount()},
                            {"vocabulary", system.vocabularyDescription()},
                            {"loops", loops},
                            {"merges", merges},
                            {"maps", maps},
                            {"map_points", system.mapPointCount()},
                            {"ms_per_frame", {{"mean", mean}, {"median", median(totals)}}}};
  summary["detector"] = {{"name", system.detectorDescription()},
                         {"dropped_features_per_frame", dropped_sum / static_cast<double>(frames)},
                         {"wait_ms_per_frame", wait_sum / static_cast<double>(frames)}};
  std::printf("%s: %zu frames, %zu tracked, %zu lost, %zu keyframes, %.1f ms/frame median\n",
              options.dataset.c_str(), frames, tracked, frames - tracked, system.keyFrameCount(),
              median(totals));

  const auto ground_truth = reader->groundTruth();
  if (!ground_truth.empty() && trajectory.size() >= 3) {
    try {
      eval::EvaluationOptions eval_options;
      // Monocular scale is unobservable: align with a similarity (ORB-SLAM's evaluation).
      if (settings.sensor == io::SensorType::Monocular) eval_options.align = eval::AlignMode::Sim3;
      const auto report = eval::evaluate(trajectory, ground_truth, eval_options);
      summary["evaluation"] = eval::toJson(report);
      eval::writeEvaluationPlot(options.out / "evaluation.svg", report);
      std::printf("%s", eval::formatTable(report).c_str());
    } catch (const Error& e) {
      spdlog::warn("evaluation against ground truth skipped: {}", e.what());
    }
  }
  std::ofstream(options.out / "summary.json") << summary.dump(2) << '\n';
  std::printf("results in %s\n", options.out.string().c_str());
  return 0;
}

}  // namespace lumaslam::cli
