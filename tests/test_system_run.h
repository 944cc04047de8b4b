#pragma once
// Runs the Pipeline over a synthetic preset (with the Settings the generator writes, optionally
// edited, optionally as another sensor: e.g. the rgb stream of an RGB-D preset as monocular)
// and evaluates the trajectory against the ground truth: shared by the test_system_* tests.
#include <functional>
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/eval/evaluation.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/pipeline.h"
#include "lumaslam/synth/dataset_writer.h"
#include "lumaslam/synth/sequence.h"
#include "test_trajectory_length.h"

namespace lumaslam::test {

struct RunResult {
  std::size_t frames = 0;
  std::size_t tracked = 0;
  std::optional<std::size_t> first_tracked;  // frame index of the first tracked frame
  std::size_t keyframes = 0;
  std::size_t moving_features = 0;   // summed over the frames (TrackingOutcome::moving_features)
  double ground_truth_length = 0.0;  // metres travelled by the camera over the sequence
  eval::EvaluationReport report;
};

// Edits the settings.yaml text the generator writes before it is parsed.
using SettingsEdit = std::function<std::string(std::string)>;

struct RunConfig {
  SettingsEdit edit = {};
  std::optional<io::SensorType> sensor = std::nullopt;  // nullopt: the preset's own sensor
  bool sequential = true;                               // false: local mapping in its own thread
};

inline io::Settings presetSettings(const synth::SequenceRenderer& sequence,
                                   const SettingsEdit& edit = {},
                                   std::optional<io::SensorType> sensor = std::nullopt) {
  const std::string name = sequence.preset().name;
  std::string yaml = synth::settingsYaml(sequence);
  if (edit) yaml = edit(std::move(yaml));
  auto file = std::make_shared<const core::SettingsFile>(
      core::SettingsFile::fromString(yaml, name + ".yaml"));
  return io::Settings::fromFile(file, sensor);
}

// The sensor input of a rendered frame: the left image plus, for `sensor` (nullopt: all the
// frame has), the right image (stereo) and the depth (RGB-D).
inline SensorFrame sensorFrame(const synth::Frame& frame,
                               std::optional<io::SensorType> sensor = std::nullopt) {
  SensorFrame input;
  input.index = static_cast<std::size_t>(frame.index);
  input.timestamp = frame.timestamp();
  input.image = frame.cam0.image;
  if (frame.cam1 && sensor.value_or(io::SensorType::Stereo) == io::SensorType::Stereo) {
    input.right = frame.cam1->image;
  }
  if (sensor.value_or(io::SensorType::Rgbd) == io::SensorType::Rgbd) {
    input.depth = frame.sensor_depth;
  }
  return input;
}

inline RunResult runOnPreset(const std::string& preset, int frames, std::uint64_t seed,
                             const RunConfig& config = {}) {
  const synth::SequenceRenderer sequence(synth::findPreset(preset), frames, seed);
  const auto settings = presetSettings(sequence, config.edit, config.sensor);
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = config.sequential;
  Pipeline system(settings, options);
  Trajectory ground_truth;
  RunResult run;
  for (int i = 0; i < frames; ++i) {
    const auto frame = sequence.render(i);
    const auto result = system.track(sensorFrame(frame, settings.sensor));
    ground_truth.push_back({frame.timestamp(), frame.cam0.T_w_c});
    run.moving_features += static_cast<std::size_t>(result.outcome.moving_features);
    if (result.outcome.state == track::TrackingState::Ok) {
      ++run.tracked;
      if (!run.first_tracked) run.first_tracked = static_cast<std::size_t>(i);
    }
  }
  system.shutdown();
  run.frames = static_cast<std::size_t>(frames);
  run.ground_truth_length = pathLength(ground_truth);
  run.keyframes = system.keyFrameCount();
  eval::EvaluationOptions eval_options;
  if (settings.sensor == io::SensorType::Monocular) eval_options.align = eval::AlignMode::Sim3;
  run.report = eval::evaluate(system.frameTrajectory(), ground_truth, eval_options);
  spdlog::info(
      "{} ({}): tracked {}/{} from frame {}, {} keyframes, {} points, ATE rmse {:.2f} mm "
      "over {:.2f} m ({:.3f} % of the path)",
      preset, io::toString(settings.sensor), run.tracked, frames,
      run.first_tracked ? static_cast<long>(*run.first_tracked) : -1L, run.keyframes,
      system.mapPointCount(), 1000.0 * run.report.ate.stats.rmse, run.ground_truth_length,
      100.0 * run.report.ate.stats.rmse / run.ground_truth_length);
  return run;
}

// Issue 7's monocular acceptance: initialised within 30 frames, >= 95% of all frames tracked
// (those before initialisation count as lost), Sim3 ATE <= 2% of the distance travelled (a
// target, not a measurement). Each test also passes `max_ate_fraction`, its own bound at ~2x
// the ATE measured on its input (issue 22), which is much tighter than the target.
inline void expectMonocularAcceptance(const RunResult& run, double max_ate_fraction) {
  ASSERT_TRUE(run.first_tracked.has_value()) << "never initialised";
  EXPECT_LT(*run.first_tracked, 30U);
  EXPECT_GE(static_cast<double>(run.tracked), 0.95 * static_cast<double>(run.frames));
  EXPECT_EQ(run.report.alignment.mode, eval::AlignMode::Sim3);
  EXPECT_LE(run.report.ate.stats.rmse, 0.02 * run.ground_truth_length);  // issue 7's target
  EXPECT_LE(run.report.ate.stats.rmse, max_ate_fraction * run.ground_truth_length)
      << "ATE " << 1000.0 * run.report.ate.stats.rmse << " mm over " << run.ground_truth_length
      << " m";
  EXPECT_GT(run.keyframes, 2U);
}

}  // namespace lumaslam::test
