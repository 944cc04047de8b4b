#include "run_pipeline.h"

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
#include "lumaslam/io/output_file.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/io/trajectory_io.h"
#include "lumaslam/loop/loop_closer.h"
#include "lumaslam/pipeline.h"
#include "lumaslam/pipeline_params.h"
#include "moving_features_file.h"
#include "progress_line.h"
#include "run_manifest.h"
#include "run_viewer.h"
#include "stop_signal.h"

namespace lumaslam::cli {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Every map of the atlas in summary.json; the main one is trajectory.txt, the others (never
// merged into it) trajectory_map<ID>.txt, each in its own world.
nlohmann::json writeMapTrajectories(const Pipeline& system, const std::filesystem::path& out) {
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

struct SkippedFrame {
  std::string what;  // the file and the problem
};

struct FrameLoop {
  std::size_t frames = 0;  // tracked or lost (skipped frames not counted)
  std::size_t tracked = 0;
  std::size_t relocalized = 0;
  std::vector<SkippedFrame> skipped;
  std::vector<double> totals;
  double dropped_sum = 0.0;
  double moving_sum = 0.0;
  double wait_sum = 0.0;
  std::vector<HandoverTime> viewer_handovers;  // tracking-thread time handing frames over
  std::string status = "complete";  // "partial" (stopped by a signal), "stopped at a bad frame"
  int exit_code = 0;
};

void writeTimingRow(std::ostream& timing, const io::FrameData& frame, const FrameResult& result) {
  const auto& t = result.timing;
  timing << frame.index << ',' << fmt::format("{:.6f}", frame.timestamp) << ','
         << track::toString(result.outcome.state) << ',' << result.outcome.inliers << ','
         << fmt::format("{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}", t.enhance, t.features, t.tracking,
                        t.mapping, t.total)
         << fmt::format(",{:.3f},{:.3f},{},{},", t.detection_wait, t.detection,
                        result.dynamic_boxes.size(), result.dropped_features.size())
         << (result.outcome.T_w_c ? std::to_string(result.outcome.map) : std::string()) << ','
         << track::toString(result.outcome.step) << ',' << result.outcome.moving_features << ','
         << fmt::format("{:.3f}", result.outcome.motion_evidence_ms) << '\n';
}

// The files written a line per frame as the frames are tracked, committed with the results.
struct FrameFiles {
  io::OutputFile timing;
  MovingFeaturesWriter moving;

  void add(const io::FrameData& frame, const FrameResult& result) {
    writeTimingRow(timing.stream(), frame, result);
    timing.flush();
    moving.add({frame.index, result.kept_features.size() + result.dropped_features.size(),
                result.dynamic_boxes, result.dropped_features, result.outcome.moving_points});
  }
  void commit() {
    timing.commit();
    moving.commit();
  }
};

// Returns false when the loop must stop here (a bad frame with --on-bad-frame stop).
bool recordBadFrame(FrameLoop& loop, std::string what, const RunOptions& options) {
  if (options.on_bad_frame == RunOptions::BadFrame::Stop) {
    spdlog::error("{}: stopping (--on-bad-frame stop); the frames tracked so far are written",
                  what);
    loop.skipped.push_back({std::move(what)});
    loop.status = "stopped at a bad frame";
    loop.exit_code = 1;
    return false;
  }
  spdlog::warn("skipping a frame: {}", what);
  loop.skipped.push_back({std::move(what)});
  return true;
}

// Reads and tracks every frame, one timing.csv row each, until the dataset ends, a signal
// asks to stop, or a bad frame stops it.
// With a viewer, each frame is handed to it and the loop waits while the page has paused.
// run --save-map-every N: a failed save is logged and the run goes on (the last good file
// stays, the save at the end reports its own error).
void saveMapPeriodically(Pipeline& system, const RunOptions& options, std::size_t frames) {
  if (!options.save_map || options.save_map_every == 0 || frames % options.save_map_every != 0) {
    return;
  }
  try {
    system.saveMap(*options.save_map);
    spdlog::info("map saved at frame {}: {} keyframes in {}", frames, system.keyFrameCount(),
                 options.save_map->string());
  } catch (const Error& e) {
    spdlog::error("saving the map at frame {} failed: {}", frames, e.what());
  }
}

// The next frame that can be read; nullopt at the end of the dataset, on a signal, or when a bad
// frame stops the run (loop.status says so).
std::optional<io::FrameData> readGoodFrame(io::DatasetReader& reader, FrameLoop& loop,
                                           const RunOptions& options, const StopOnSignal& stop) {
  constexpr std::size_t kMaxUnreadableInARow = 100;  // a reader that cannot go on
  for (std::size_t unreadable_in_a_row = 0; !stop.requested();) {
    try {
      return reader.next();
    } catch (const Error& e) {
      if (!recordBadFrame(loop, e.what(), options)) return std::nullopt;
      if (++unreadable_in_a_row >= kMaxUnreadableInARow) {
        spdlog::error("{} unreadable frames in a row: stopping", unreadable_in_a_row);
        loop.status = "stopped at a bad frame";
        loop.exit_code = 1;
        return std::nullopt;
      }
    }
  }
  return std::nullopt;
}

// Reads one frame ahead: each frame goes to Pipeline::prepareAhead when it is read, before the
// frame before it is tracked, so that its detection overlaps that frame's tracking.
FrameLoop trackFrames(io::DatasetReader& reader, Pipeline& system, FrameFiles& files,
                      const RunOptions& options, const StopOnSignal& stop, viewer::Viewer* viewer) {
  ProgressLine progress("frame", reader.size());
  FrameLoop loop;
  std::optional<io::FrameData> next = readGoodFrame(reader, loop, options, stop);
  if (next) system.prepareAhead(toSensorFrame(*next));
  while (next && !stop.requested()) {
    if (viewer) viewer->waitWhilePaused([&stop] { return stop.requested(); });
    if (stop.requested()) break;
    std::optional<io::FrameData> frame = std::move(next);
    next = readGoodFrame(reader, loop, options, stop);
    if (next) system.prepareAhead(toSensorFrame(*next));
    FrameResult result;
    try {
      result = system.track(toSensorFrame(*frame));
    } catch (const Error& e) {
      if (!recordBadFrame(loop, fmt::format("{}: {}", frame->image_path.string(), e.what()),
                          options)) {
        break;
      }
      continue;
    }
    files.add(*frame, result);
    loop.dropped_sum += static_cast<double>(result.dropped_features.size());
    loop.moving_sum += result.outcome.moving_features;
    loop.wait_sum += result.timing.detection_wait;
    loop.totals.push_back(result.timing.total);
    ++loop.frames;
    saveMapPeriodically(system, options, loop.frames);
    if (result.outcome.state == track::TrackingState::Ok) ++loop.tracked;
    if (result.outcome.relocalized) ++loop.relocalized;
    if (viewer) loop.viewer_handovers.push_back(publishFrame(*viewer, *frame, result, system));
    progress.update(loop.frames, track::toString(result.outcome.state));
  }
  if (stop.requested()) {
    spdlog::warn("{}: stopped after {} frames; writing what was tracked (partial)", stop.name(),
                 loop.frames);
    loop.status = "partial";
    loop.exit_code = stop.exitCode();
  }
  return loop;
}

nlohmann::json summaryOf(const RunOptions& options, const std::filesystem::path& settings_path,
                         const Pipeline& system, const FrameLoop& loop, nlohmann::json maps) {
  double mean = 0.0;
  for (double v : loop.totals) mean += v / static_cast<double>(loop.totals.size());
  std::size_t loops = 0;
  std::size_t merges = 0;
  if (system.loopCloser()) {
    for (const auto& closed : system.loopCloser()->closedLoops()) {
      ++(closed.merged_map ? merges : loops);
    }
  }
  nlohmann::json skipped = nlohmann::json::array();
  for (const auto& frame : loop.skipped) skipped.push_back(frame.what);
  const double frames = static_cast<double>(std::max<std::size_t>(loop.frames, 1));
  nlohmann::json summary = {{"dataset", options.dataset},
                            {"settings", settings_path.string()},
                            {"status", loop.status},
                            {"frames", loop.frames},
                            {"tracked", loop.tracked},
                            {"lost", loop.frames - loop.tracked},
                            {"relocalized", loop.relocalized},
                            {"skipped_frames", loop.skipped.size()},
                            {"skipped", skipped},
                            {"keyframes", system.keyFrameCount()},
                            {"vocabulary", system.vocabularyDescription()},
                            {"loops", loops},
                            {"merges", merges},
                            {"maps", std::move(maps)},
                            {"map_points", system.mapPointCount()},
                            {"ms_per_frame", {{"mean", mean}, {"median", median(loop.totals)}}}};
  // The --enhance override, null when Enhancement.preset of the settings applies.
  summary["enhance_preset"] =
      options.enhance_preset ? nlohmann::json(*options.enhance_preset) : nlohmann::json(nullptr);
  summary["detector"] = {{"name", system.detectorDescription()},
                         {"dropped_features_per_frame", loop.dropped_sum / frames},
                         {"wait_ms_per_frame", loop.wait_sum / frames}};
  summary["motion_evidence"] = {{"on", system.tracker().motionEvidenceOn()},
                                {"moving_features_per_frame", loop.moving_sum / frames},
                                {"moving_map_points", system.tracker().movingPointCount()}};
  return summary;
}

// The error message, empty when saved or not asked to.
std::string saveMapIfAsked(Pipeline& system, const RunOptions& options) {
  if (!options.save_map) return {};
  try {
    system.saveMap(*options.save_map);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

nlohmann::json mapFileSummary(const RunOptions& options, const Pipeline& system,
                              std::size_t loaded_keyframes, const std::string& save_error) {
  const auto path_or_null = [](const std::optional<std::filesystem::path>& path) {
    // Absolute: `lumaslam report` reads the file again from wherever it runs.
    return path ? nlohmann::json(std::filesystem::absolute(*path).string())
                : nlohmann::json(nullptr);
  };
  nlohmann::json result = {
      {"loaded", path_or_null(options.load_map)},
      {"loaded_keyframes", loaded_keyframes},
      {"localization", options.localization},
      {"keyframes_added",
       static_cast<long long>(system.keyFrameCount()) - static_cast<long long>(loaded_keyframes)},
      {"saved", save_error.empty() ? path_or_null(options.save_map) : nlohmann::json(nullptr)}};
  if (!save_error.empty()) result["save_error"] = save_error;
  return result;
}

// Evaluation against the dataset's ground truth, when it has one, into the summary.
void evaluateAgainstGroundTruth(io::DatasetReader& reader, const io::Settings& settings,
                                const Trajectory& trajectory, const std::filesystem::path& out,
                                nlohmann::json& summary) {
  const auto ground_truth = reader.groundTruth();
  if (ground_truth.empty() || trajectory.size() < 3) return;
  try {
    eval::EvaluationOptions eval_options;
    // Monocular scale is unobservable: align with a similarity (ORB-SLAM's evaluation).
    if (settings.sensor == io::SensorType::Monocular) eval_options.align = eval::AlignMode::Sim3;
    const auto report = eval::evaluate(trajectory, ground_truth, eval_options);
    summary["evaluation"] = eval::toJson(report);
    eval::writeEvaluationPlot(out / "evaluation.svg", report);
    std::printf("%s", eval::formatTable(report).c_str());
  } catch (const Error& e) {
    spdlog::warn("evaluation against ground truth skipped: {}", e.what());
  }
}

}  // namespace

// docs/results.md
void removeEarlierOutputs(const std::filesystem::path& out) {
  std::error_code ec;
  for (const char* name :
       {"trajectory.txt", "keyframes.txt", "timing.csv", kMovingFeaturesFile, "summary.json",
        "evaluation.svg", "repeatability.json", "manifest.json", "report.html"}) {
    if (std::filesystem::is_regular_file(out / name, ec)) std::filesystem::remove(out / name, ec);
  }
  for (const auto& entry : std::filesystem::directory_iterator(out, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file(ec) && name.starts_with("trajectory_map")) {
      std::filesystem::remove(entry.path(), ec);
    }
  }
}

namespace {

// The images' size as tracking sees them, the pixels of moving_features.txt.
cv::Size workingSize(const io::Settings& settings) {
  const camera::ImageSize size = settings.camera.resizeTo.value_or(settings.camera.size);
  return {size.width, size.height};
}

std::filesystem::path settingsPathOf(const RunOptions& options) {
  // An unknown dataset KIND is reported before the settings file it would point to.
  if (!options.settings.empty()) return options.settings;
  return io::datasetPathOf(options.dataset) / "settings.yaml";
}

PipelineOptions pipelineOptionsOf(const RunOptions& options) {
  PipelineOptions pipeline;
  pipeline.enhance_preset = options.enhance_preset;
  pipeline.detector = options.detector;
  if (options.sequential) pipeline.sequential = true;
  pipeline.vocabulary = options.vocabulary;
  if (options.no_loop_closing) pipeline.loop_closing = false;
  if (options.no_motion_evidence) pipeline.motion_evidence = false;
  pipeline.strict_settings = options.strict_settings;
  return pipeline;
}

// Camera.RGB is for callers of the System API, whose arrays may be RGB; this command decodes
// image files with OpenCV, which always gives BGR. ORB-SLAM3's TUM files say 1, so say why it
// changes nothing here instead of swapping the colours.
void noteColourOrder(const io::Settings& settings, const std::filesystem::path& settings_path) {
  if (!settings.camera.rgb) return;
  spdlog::info(
      "{}: Camera.RGB: 1 describes colour images handed to the System API; lumaslam run decodes "
      "image files itself, in BGR order, so it does not apply (docs/settings.md)",
      settings_path.string());
}

// Last: its presence says every result above was written.
void writeManifest(const RunOptions& options, const std::string& status,
                   const std::string& save_error) {
  std::vector<std::filesystem::path> map_file;
  if (options.save_map && save_error.empty()) map_file.push_back(*options.save_map);
  std::vector<std::string> errors;
  if (!save_error.empty()) errors.push_back(save_error);
  writeRunManifest(options.out, status, map_file, errors);
}

}  // namespace

int printEffectiveSettings(const RunOptions& options) {
  const auto settings_path = settingsPathOf(options);
  const auto settings = io::loadSettings(settings_path);
  std::printf("%%YAML:1.0\n# effective values of %s (lumaslam run --print-settings)\n%s",
              settings_path.string().c_str(),
              effectiveSettings(settings, pipelineOptionsOf(options)).c_str());
  return 0;
}

int runPipeline(const RunOptions& options) {
  const auto settings_path = settingsPathOf(options);
  const auto settings = io::loadSettings(settings_path);
  noteColourOrder(settings, settings_path);
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
  io::requireWritableFolder(options.out);
  removeEarlierOutputs(options.out);

  Pipeline system(settings, pipelineOptionsOf(options));
  if (options.load_map) system.loadMap(*options.load_map);
  if (options.localization) system.setLocalizationMode(true);
  const std::size_t loaded_keyframes = system.keyFrameCount();

  FrameFiles files{io::OutputFile(options.out / "timing.csv"),
                   MovingFeaturesWriter(options.out / kMovingFeaturesFile, workingSize(settings))};
  files.timing.stream()
      << "frame,timestamp,state,inliers,enhance_ms,features_ms,tracking_ms,mapping_ms,total_ms,"
         "detection_wait_ms,detection_ms,boxes,dropped_features,map,step,moving_features,"
         "motion_ms\n";
  const StopOnSignal stop;
  const auto viewer = startViewer(options, system);
  const FrameLoop loop = trackFrames(*reader, system, files, options, stop, viewer.get());
  if (loop.frames == 0 && loop.exit_code == 0) {
    fail("{}: the dataset delivered no frames", options.dataset);
  }
  system.shutdown();
  if (viewer) viewer->finish(loop.status);

  // Results, each file complete or not written (io::OutputFile): trajectories first.
  const auto trajectory = system.frameTrajectory();
  io::writeTrajectory(options.out / "trajectory.txt", trajectory);
  io::writeTrajectory(options.out / "keyframes.txt", system.keyFrameTrajectory());
  auto summary =
      summaryOf(options, settings_path, system, loop, writeMapTrajectories(system, options.out));
  // After the trajectories, so that a map that cannot be written costs no results.
  const std::string save_error = saveMapIfAsked(system, options);
  summary["map_file"] = mapFileSummary(options, system, loaded_keyframes, save_error);
  if (viewer) summary["viewer"] = viewerSummary(*viewer, loop.viewer_handovers);
  files.commit();
  std::printf(
      "%s: %zu frames, %zu tracked, %zu lost, %zu skipped, %zu keyframes, %.1f ms/frame "
      "median%s\n",
      options.dataset.c_str(), loop.frames, loop.tracked, loop.frames - loop.tracked,
      loop.skipped.size(), system.keyFrameCount(), median(loop.totals),
      loop.status == "complete" ? "" : (" (" + loop.status + ")").c_str());
  evaluateAgainstGroundTruth(*reader, settings, trajectory, options.out, summary);
  io::OutputFile summary_file(options.out / "summary.json");
  summary_file.stream() << summary.dump(2) << '\n';
  summary_file.commit();
  writeManifest(options, loop.status, save_error);
  std::printf("results in %s\n", options.out.string().c_str());
  if (viewer && options.viewer_keep) keepServing(*viewer, stop);
  if (!save_error.empty()) fail("{}", save_error);
  return loop.exit_code;
}

}  // namespace lumaslam::cli
