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
  std::vector<track::TrackingOutcome> outcomes;  // per frame
  std::vector<double> timestamps;                // per frame
  Trajectory trajectory;                         // Pipeline::frameTrajectory()
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

// Called after every frame with what the generator rendered and what Pipeline made of it.
using FrameObserver = std::function<void(const synth::Frame&, const FrameResult&)>;
// Renders frame i of a run.
using FrameRenderer = std::function<synth::Frame(int)>;
// The Pipeline's input for rendered frame i; unset: sensorFrame(frame, sensor).
using FrameInput = std::function<SensorFrame(const synth::Frame&, int)>;

// What feeding the frames gave, before evaluation.
struct FedFrames {
  Trajectory ground_truth;  // at the input's timestamps
  std::size_t tracked = 0;
  std::optional<std::size_t> first_tracked;  // frame index of the first tracked frame
  std::size_t moving_features = 0;           // summed over the frames
  std::size_t dropped_features = 0;          // summed over the frames (detector boxes)
};

// The one loop of the system tests that feeds rendered frames to a Pipeline: frames 0 to
// frames - 1, each handed over as `input` makes it, then shutdown().
inline FedFrames feedFrames(Pipeline& system, int frames, const FrameRenderer& render,
                            std::optional<io::SensorType> sensor, const FrameInput& input = {},
                            const FrameObserver& observe = {}) {
  FedFrames fed;
  for (int i = 0; i < frames; ++i) {
    const synth::Frame frame = render(i);
    const SensorFrame sensor_frame = input ? input(frame, i) : sensorFrame(frame, sensor);
    const FrameResult result = system.track(sensor_frame);
    fed.ground_truth.push_back({sensor_frame.timestamp, frame.cam0.T_w_c});
    fed.moving_features += static_cast<std::size_t>(result.outcome.moving_features);
    fed.dropped_features += result.dropped_features.size();
    if (result.outcome.state == track::TrackingState::Ok) {
      ++fed.tracked;
      if (!fed.first_tracked) fed.first_tracked = static_cast<std::size_t>(i);
    }
    if (observe) observe(frame, result);
  }
  system.shutdown();
  return fed;
}

// ATE/RPE of the run's frame trajectory: SE3-aligned, Sim3 for monocular (scale unknown).
inline eval::EvaluationReport evaluateRun(const Pipeline& system, const Trajectory& ground_truth,
                                          io::SensorType sensor) {
  eval::EvaluationOptions options;
  if (sensor == io::SensorType::Monocular) options.align = eval::AlignMode::Sim3;
  return eval::evaluate(system.frameTrajectory(), ground_truth, options);
}

inline RunResult runOnPreset(const std::string& preset, int frames, std::uint64_t seed,
                             const RunConfig& config = {}) {
  const synth::SequenceRenderer sequence(synth::findPreset(preset), frames, seed);
  const auto settings = presetSettings(sequence, config.edit, config.sensor);
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = config.sequential;
  Pipeline system(settings, options);
  RunResult run;
  const FedFrames fed = feedFrames(
      system, frames, [&](int i) { return sequence.render(i); }, settings.sensor, {},
      [&](const synth::Frame& frame, const FrameResult& result) {
        run.outcomes.push_back(result.outcome);
        run.timestamps.push_back(frame.timestamp());
      });
  run.frames = static_cast<std::size_t>(frames);
  run.tracked = fed.tracked;
  run.first_tracked = fed.first_tracked;
  run.moving_features = fed.moving_features;
  run.ground_truth_length = pathLength(fed.ground_truth);
  run.keyframes = system.keyFrameCount();
  run.report = evaluateRun(system, fed.ground_truth, settings.sensor);
  run.trajectory = system.frameTrajectory();
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
