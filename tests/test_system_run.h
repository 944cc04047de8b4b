#pragma once
// Runs the System on a synthetic preset (RGB-D or stereo, with the Settings the generator
// writes) and evaluates the trajectory against the ground truth: shared by test_system_*.
#include <functional>
#include <string>

#include <spdlog/spdlog.h>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/eval/evaluation.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/synth/dataset_writer.h"
#include "lumaslam/synth/sequence.h"
#include "lumaslam/system.h"

namespace lumaslam::test {

struct RunResult {
  std::size_t tracked = 0;
  std::size_t frames = 0;
  eval::EvaluationReport report;
  std::size_t keyframes = 0;
};

// The settings.yaml the generator writes for the sequence, optionally edited first.
using SettingsEdit = std::function<std::string(std::string)>;
inline io::Settings presetSettings(const synth::SequenceRenderer& sequence,
                                   const SettingsEdit& edit = {}) {
  const std::string name = sequence.preset().name;
  std::string yaml = synth::settingsYaml(sequence);
  if (edit) yaml = edit(std::move(yaml));
  auto file = std::make_shared<const core::SettingsFile>(
      core::SettingsFile::fromString(yaml, name + ".yaml"));
  return io::Settings::fromFile(file);
}

// The sensor input of a rendered frame: left + right for stereo, rgb + depth for RGB-D.
inline SensorFrame sensorFrame(const synth::Frame& frame) {
  SensorFrame input;
  input.index = static_cast<std::size_t>(frame.index);
  input.timestamp = frame.timestamp();
  input.image = frame.cam0.image;
  if (frame.cam1) input.right = frame.cam1->image;
  input.depth = frame.sensor_depth;
  return input;
}

inline RunResult runOnPreset(const std::string& preset, int frames, std::uint64_t seed,
                             const SettingsEdit& edit = {}, bool sequential = true) {
  const synth::SequenceRenderer sequence(synth::findPreset(preset), frames, seed);
  SystemOptions options;
  options.enhance_preset = "off";
  options.sequential = sequential;
  System system(presetSettings(sequence, edit), options);
  Trajectory ground_truth;
  RunResult run;
  for (int i = 0; i < frames; ++i) {
    const auto frame = sequence.render(i);
    const auto result = system.track(sensorFrame(frame));
    ground_truth.push_back({frame.timestamp(), frame.cam0.T_w_c});
    if (result.outcome.state == track::TrackingState::Ok) ++run.tracked;
  }
  system.shutdown();
  run.frames = static_cast<std::size_t>(frames);
  run.keyframes = system.keyFrameCount();
  eval::EvaluationOptions eval_options;
  run.report = eval::evaluate(system.frameTrajectory(), ground_truth, eval_options);
  spdlog::info("{}: tracked {}/{}, {} keyframes, {} points, ATE rmse {:.4f} m", preset, run.tracked,
               frames, run.keyframes, system.mapPointCount(), run.report.ate.stats.rmse);
  return run;
}

}  // namespace lumaslam::test
