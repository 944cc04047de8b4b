#pragma once
// Runs Pipeline with a detector on a synthetic RGB-D sequence rendered in memory, reporting
// per frame what it dropped, and evaluates the trajectory: shared by the dynamic-removal tests.
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <spdlog/spdlog.h>

#include "test_system_run.h"

namespace lumaslam::test {

struct SyntheticRun {
  std::size_t frames = 0;
  std::size_t tracked = 0;
  std::size_t keyframes = 0;
  std::size_t map_points = 0;
  std::size_t dropped_features = 0;
  eval::EvaluationReport report;
  double ate() const { return report.ate.stats.rmse; }
};

// Collects the generator's boxes of the frames it is given, in the detections.txt format
// (`timestamp class x y w h`), for the box-file detector.
class GroundTruthBoxes {
 public:
  void add(const synth::Frame& frame) {
    for (const auto& b : frame.cam0.boxes) {
      text_ += fmt::format("{:.9f} {} {} {} {} {}\n", frame.timestamp(), b.class_name, b.box.x,
                           b.box.y, b.box.width, b.box.height);
    }
  }
  void write(const std::filesystem::path& path) const { std::ofstream(path) << text_; }

 private:
  std::string text_;
};

// Called after every tracked frame with what the generator rendered and what Pipeline made of it.
using FrameObserver = std::function<void(const synth::Frame&, const FrameResult&)>;

// Enhancement off and local mapping in the caller's thread (repeatable) unless `options` says
// otherwise. `extra_settings`: YAML lines appended to the generator's settings.yaml. `sensor`:
// e.g. the rgb stream alone as monocular (then Sim3 alignment); nullopt: the preset's sensor.
inline SyntheticRun runSynthetic(const synth::SequenceRenderer& sequence, PipelineOptions options,
                                 const FrameObserver& observe = {},
                                 const std::string& extra_settings = {},
                                 std::optional<io::SensorType> sensor = std::nullopt) {
  if (!options.enhance_preset) options.enhance_preset = "off";
  if (!options.sequential) options.sequential = true;
  const auto settings = presetSettings(
      sequence, [&](std::string yaml) { return yaml + extra_settings; }, sensor);
  Pipeline system(settings, options);
  Trajectory ground_truth;
  SyntheticRun run;
  for (int i = 0; i < sequence.frameCount(); ++i) {
    const auto frame = sequence.render(i);
    const auto result = system.track(sensorFrame(frame, settings.sensor));
    ground_truth.push_back({frame.timestamp(), frame.cam0.T_w_c});
    if (result.outcome.state == track::TrackingState::Ok) ++run.tracked;
    run.dropped_features += result.dropped_features.size();
    if (observe) observe(frame, result);
  }
  system.shutdown();
  run.frames = static_cast<std::size_t>(sequence.frameCount());
  run.keyframes = system.keyFrameCount();
  run.map_points = system.mapPointCount();
  eval::EvaluationOptions eval_options;
  if (settings.sensor == io::SensorType::Monocular) eval_options.align = eval::AlignMode::Sim3;
  run.report = eval::evaluate(system.frameTrajectory(), ground_truth, eval_options);
  spdlog::info(
      "{} (detector {}): tracked {}/{}, {} keyframes, {} points, {} features dropped, "
      "ATE rmse {:.4f} m",
      sequence.preset().name, system.detectorDescription(), run.tracked, run.frames, run.keyframes,
      run.map_points, run.dropped_features, run.ate());
  return run;
}

}  // namespace lumaslam::test
