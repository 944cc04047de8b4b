#include <gtest/gtest.h>

#include <spdlog/spdlog.h>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/eval/evaluation.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/synth/dataset_writer.h"
#include "lumaslam/synth/sequence.h"
#include "lumaslam/system.h"

namespace {

using namespace lumaslam;

struct RunResult {
  std::size_t tracked = 0;
  std::size_t frames = 0;
  eval::EvaluationReport report;
  std::size_t keyframes = 0;
};

RunResult runOnPreset(const std::string& preset, int frames, std::uint64_t seed) {
  const synth::SequenceRenderer sequence(synth::findPreset(preset), frames, seed);
  auto file = std::make_shared<const core::SettingsFile>(
      core::SettingsFile::fromString(synth::settingsYaml(sequence), preset + ".yaml"));
  const auto settings = io::Settings::fromFile(file);
  SystemOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  System system(settings, options);
  Trajectory ground_truth;
  RunResult run;
  for (int i = 0; i < frames; ++i) {
    const auto frame = sequence.render(i);
    const auto result = system.trackRgbd(static_cast<std::size_t>(i), frame.timestamp(),
                                         frame.cam0.image, frame.sensor_depth);
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

TEST(SystemRgbd, TracksStaticSceneWithXyzMotion) {
  const auto run = runOnPreset("xyz-rgbd", 150, 1);
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LT(run.report.ate.stats.rmse, 0.01);
  EXPECT_GT(run.keyframes, 1U);
}

}  // namespace
