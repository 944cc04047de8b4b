// RGB-D tracking on handheld-rgbd: a hand-held Kinect v1 like TUM fr1 desk/room (fast sweeps
// with a quick ~5-degree-per-frame turn every 2-3 s, blur at a 17 ms exposure, 30 ms rolling
// shutter, depth misregistered, up to 15 ms out of sync and with holes), so that what fails on
// real hand-held data fails here too (issue 15).
#include <gtest/gtest.h>

#include "test_system_run.h"

namespace {

using namespace lumaslam;

// Tracked frames and ATE of a sequential run over `frames` frames of `preset` as rendered
// with `options` (runOnPreset, for a preset changed by the options).
test::RunResult runWithOptions(const synth::Preset& preset, int frames, std::uint64_t seed,
                               const synth::SynthOptions& options) {
  const synth::SequenceRenderer sequence(preset, frames, seed, options);
  const auto settings = test::presetSettings(sequence);
  PipelineOptions system_options;
  system_options.enhance_preset = "off";
  system_options.sequential = true;
  Pipeline system(settings, system_options);
  const test::FedFrames fed = test::feedFrames(
      system, frames, [&](int i) { return sequence.render(i); }, settings.sensor);
  test::RunResult run;
  run.tracked = fed.tracked;
  run.frames = static_cast<std::size_t>(frames);
  run.report = eval::evaluate(system.frameTrajectory(), fed.ground_truth, {});
  spdlog::info("{} ({} frames): tracked {}, ATE rmse {:.4f} m", preset.name, frames, run.tracked,
               run.report.ate.stats.rmse);
  return run;
}

// Every sensor effect on. Before the tracker's reference-keyframe fallback (main 8e76fe9):
// tracked 54/150, lost at frame 54 (the first quick turn) and never back. Measured with it
// (7d39fc8, `build/tests/test_system_handheld --gtest_filter='*Kinect*'`): 148/150, ATE
// 0.068 m; the rolling shutter dominates the error (50 frames with it alone give 0.053 m, with
// every other effect but it 0.004-0.012 m). The bound is ~2x the 0.068 m.
TEST(SystemHandheld, TracksHandheldKinectSequence) {
  const auto run = test::runOnPreset("handheld-rgbd", 150, 1);
  EXPECT_GE(static_cast<double>(run.tracked), 0.95 * static_cast<double>(run.frames));
  EXPECT_LT(run.report.ate.stats.rmse, 0.14);
}

// The same motion through an ideal camera (global shutter, no blur, depth registered and in
// sync; noise and Kinect holes kept): what is left is the hand-held motion itself. On main
// 8e76fe9 also lost at frame 54 (54/150); with the reference-keyframe fallback (7d39fc8)
// 150/150, ATE 3.6 mm; the bound is ~2x.
TEST(SystemHandheld, TracksHandheldMotionThroughAnIdealCamera) {
  synth::SynthOptions ideal;
  ideal.motion_blur = false;
  ideal.rolling_shutter = false;
  ideal.depth_misalignment = false;
  const auto run = runWithOptions(synth::findPreset("handheld-rgbd"), 150, 1, ideal);
  EXPECT_GE(static_cast<double>(run.tracked), 0.95 * static_cast<double>(run.frames));
  EXPECT_LT(run.report.ate.stats.rmse, 0.0075);
}

}  // namespace
