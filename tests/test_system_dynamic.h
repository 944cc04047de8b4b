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
  const FedFrames fed = feedFrames(
      system, sequence.frameCount(), [&](int i) { return sequence.render(i); }, settings.sensor, {},
      observe);
  SyntheticRun run;
  run.frames = static_cast<std::size_t>(sequence.frameCount());
  run.tracked = fed.tracked;
  run.dropped_features = fed.dropped_features;
  run.keyframes = system.keyFrameCount();
  run.map_points = system.mapPointCount();
  run.report = evaluateRun(system, fed.ground_truth, settings.sensor);
  spdlog::info(
      "{} (detector {}): tracked {}/{}, {} keyframes, {} points, {} features dropped, "
      "ATE rmse {:.4f} m",
      sequence.preset().name, system.detectorDescription(), run.tracked, run.frames, run.keyframes,
      run.map_points, run.dropped_features, run.ate());
  return run;
}

// runSynthetic with no detector, `extra_settings` appended to the settings.
inline SyntheticRun runWithoutDetector(const synth::SequenceRenderer& sequence,
                                       const std::string& extra_settings = {}) {
  PipelineOptions options;
  options.detector = "none";
  return runSynthetic(sequence, options, {}, extra_settings);
}

}  // namespace lumaslam::test
