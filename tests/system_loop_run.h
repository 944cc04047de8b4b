#pragma once
// The `loop-stereo` loop sequence of the Pipeline loop tests: one lap of the room, then part of
// a second lap rendered from other viewpoints (the same room and trajectory sampled with one
// frame more), so that the camera comes back to where the map started with several keyframes
// in a row. A run with loop closing on or off, as stereo or as monocular (left camera only),
// with the default vocabulary (trained on real images, none of the generator's): what users
// run.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "test_system_run.h"

#include "lumaslam/loop/loop_closer.h"

namespace lumaslam::test {

struct LoopInput {
  LoopInput(int lap_frames, int second_lap_frames, std::uint64_t seed,
            const std::string& preset = "loop-stereo")
      : lap_frames(lap_frames),
        second_lap_frames(second_lap_frames),
        lap(synth::findPreset(preset), lap_frames, seed),
        second_lap(synth::findPreset(preset), lap_frames + 1, seed) {}
  int lap_frames;
  int second_lap_frames;
  synth::SequenceRenderer lap;
  synth::SequenceRenderer second_lap;
  int frames() const { return lap_frames + second_lap_frames; }
  double fps() const { return lap.rig().fps; }
  synth::Frame render(int i) const {
    // Second lap: frame k of the (N+1)-frame lap sits between frames k-1 and k of the first.
    return i < lap_frames ? lap.render(i) : second_lap.render(i - lap_frames + 1);
  }
  // Frame i as the Pipeline gets it: the second lap numbered and timed on from the first.
  SensorFrame sensorInput(const synth::Frame& frame, int i,
                          std::optional<io::SensorType> sensor) const {
    SensorFrame input = sensorFrame(frame, sensor);
    input.index = static_cast<std::size_t>(i);
    input.timestamp = i / fps();
    return input;
  }
};

struct LoopRun {
  double ate = 0.0;
  double ate_sim3 = 0.0;
  std::size_t tracked = 0;
  std::vector<loop::ClosedLoop> loops;
  loop::GlobalBAStats global_ba;
};

inline LoopRun runLoop(const LoopInput& input, bool loop_closing,
                       std::optional<io::SensorType> sensor = std::nullopt,
                       const SettingsEdit& edit = {}) {
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  options.loop_closing = loop_closing;
  Pipeline system(presetSettings(input.lap, edit, sensor), options);
  const FedFrames fed = feedFrames(
      system, input.frames(), [&](int i) { return input.render(i); }, sensor,
      [&](const synth::Frame& frame, int i) { return input.sensorInput(frame, i, sensor); });
  const Trajectory& ground_truth = fed.ground_truth;
  LoopRun result;
  result.tracked = fed.tracked;
  if (system.loopCloser()) {
    result.loops = system.loopCloser()->closedLoops();
    result.global_ba = system.loopCloser()->globalBundleAdjustmentStats();
  }
  result.ate = eval::evaluate(system.frameTrajectory(), ground_truth, {}).ate.stats.rmse;
  eval::EvaluationOptions sim3;
  sim3.align = eval::AlignMode::Sim3;
  result.ate_sim3 = eval::evaluate(system.frameTrajectory(), ground_truth, sim3).ate.stats.rmse;
  const std::string sensor_name(sensor ? io::toString(*sensor) : "preset sensor");
  std::printf(
      "%s, loop closing %s: tracked %zu/%d, %zu keyframes, %zu loops, ATE %.1f mm (Sim3 %.1f "
      "mm)\n",
      sensor_name.c_str(), loop_closing ? "on" : "off", result.tracked, input.frames(),
      system.keyFrameCount(), result.loops.size(), 1000.0 * result.ate, 1000.0 * result.ate_sim3);
  for (const auto& loop : result.loops) {
    std::printf("  loop keyframe %llu -> %llu: %d inliers, moved %.1f mm %.2f deg, scale %.4f\n",
                static_cast<unsigned long long>(loop.current),
                static_cast<unsigned long long>(loop.loop), loop.inliers,
                1000.0 * loop.correction_m, loop.correction_deg, loop.correction_scale);
  }
  return result;
}

}  // namespace lumaslam::test
