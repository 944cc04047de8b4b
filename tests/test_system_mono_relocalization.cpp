// Issue 7, monocular blackout: the rgb stream of a synthetic RGB-D sequence (xyz-rgbd played
// twice as fast), run without depth, goes black for 20 frames after the map is built, and the
// camera moves on meanwhile: the stream resumes 40 frames further on, too far for the search
// around the last pose. Black frames are Lost with no pose; when the light returns the
// relocalizer (BoW + EPnP) finds the map within 5 frames, and tracking goes on in the same map
// (same first keyframe; one Sim3 fits the poses before and after the blackout). The default
// vocabulary (trained on real images only) is what turns relocalization on, as for users.
#include <algorithm>
#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "test_system_run.h"

namespace lumaslam {
namespace {

constexpr int kFrames = 200;
constexpr int kFirstDark = 100;
constexpr int kDarkFrames = 20;
constexpr int kSkipped = 40;        // frames of motion not shown while dark
constexpr int kRecoveryWindow = 5;  // frames after the light returns (acceptance)
constexpr auto kMonocular = io::SensorType::Monocular;

const synth::SequenceRenderer& sequence() {
  static const synth::SequenceRenderer instance(
      [] {
        auto preset = synth::findPreset("xyz-rgbd");
        preset.motion_speed = 2.0;
        return preset;
      }(),
      kFrames + kSkipped, 1);
  return instance;
}

struct BlackoutRun {
  std::vector<track::TrackingOutcome> outcomes;  // per frame
  Trajectory trajectory;
  Trajectory ground_truth;
  Trajectory keyframes;
  std::size_t keyframes_before = 0;  // when the light went
  double first_keyframe_before = 0.0;
};

BlackoutRun runWithBlackout() {
  const auto settings = test::presetSettings(sequence(), {}, kMonocular);
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  Pipeline system(settings, options);
  BlackoutRun run;
  for (int i = 0; i < kFrames; ++i) {
    const auto frame = sequence().render(i < kFirstDark + kDarkFrames ? i : i + kSkipped);
    auto input = test::sensorFrame(frame, kMonocular);
    if (i == kFirstDark) {
      run.keyframes_before = system.keyFrameCount();
      run.first_keyframe_before = system.keyFrameTrajectory().front().timestamp;
    }
    if (i >= kFirstDark && i < kFirstDark + kDarkFrames) {
      input.image = cv::Mat::zeros(input.image.size(), input.image.type());
    }
    run.outcomes.push_back(system.track(input).outcome);
    run.ground_truth.push_back({frame.timestamp(), frame.cam0.T_w_c});
  }
  system.shutdown();
  run.trajectory = system.frameTrajectory();
  run.keyframes = system.keyFrameTrajectory();
  return run;
}

TEST(SystemMonoRelocalization, ResumesInTheSameMapAfterTwentyBlackFrames) {
  const auto run = runWithBlackout();
  const auto tracked = [&](int i) {
    return run.outcomes[static_cast<std::size_t>(i)].state == track::TrackingState::Ok;
  };
  ASSERT_GT(run.keyframes_before, 2U) << "no monocular map before the blackout";
  ASSERT_TRUE(tracked(kFirstDark - 1)) << "not tracking when the light went";

  for (int i = kFirstDark; i < kFirstDark + kDarkFrames; ++i) {
    const auto& outcome = run.outcomes[static_cast<std::size_t>(i)];
    EXPECT_EQ(outcome.state, track::TrackingState::Lost) << "black frame " << i;
    EXPECT_FALSE(outcome.T_w_c) << "black frame " << i;
    const double t = sequence().render(i).timestamp();
    EXPECT_TRUE(std::none_of(run.trajectory.begin(), run.trajectory.end(),
                             [&](const auto& p) { return std::abs(p.timestamp - t) < 1e-6; }))
        << "black frame " << i << " has a pose in the trajectory";
  }

  const int light_back = kFirstDark + kDarkFrames;
  std::optional<int> recovered;
  for (int i = light_back; i < kFrames && !recovered; ++i) {
    if (tracked(i)) recovered = i;
  }
  ASSERT_TRUE(recovered.has_value()) << "never tracking again after the blackout";
  EXPECT_LT(*recovered, light_back + kRecoveryWindow);
  EXPECT_TRUE(run.outcomes[static_cast<std::size_t>(*recovered)].relocalized)
      << "recovered by the last-pose search: the test no longer exercises the relocalizer";
  int tracked_after = 0;
  for (int i = *recovered; i < kFrames; ++i) tracked_after += tracked(i) ? 1 : 0;
  EXPECT_GE(tracked_after, static_cast<int>(0.95 * (kFrames - *recovered)));

  // Same map: the first keyframe is still the origin and keyframes were only added; one Sim3
  // (one scale) fits the poses before and after the blackout, which a new map would not.
  EXPECT_GE(run.keyframes.size(), run.keyframes_before);
  EXPECT_NEAR(run.keyframes.front().timestamp, run.first_keyframe_before, 1e-6);
  eval::EvaluationOptions eval_options;
  eval_options.align = eval::AlignMode::Sim3;
  const auto report = eval::evaluate(run.trajectory, run.ground_truth, eval_options);
  const double length = test::pathLength(run.ground_truth);
  std::printf(
      "mono blackout: tracking again at frame %d (%d after the light)%s, %d of %d frames tracked "
      "after it, %zu keyframes (%zu before), ATE (Sim3, whole run) %.2f mm over %.2f m\n",
      *recovered, *recovered - light_back,
      run.outcomes[static_cast<std::size_t>(*recovered)].relocalized ? " by relocalization" : "",
      tracked_after, kFrames - *recovered, run.keyframes.size(), run.keyframes_before,
      1000.0 * report.ate.stats.rmse, length);
  // Issue 7's target is 2 % of the path; the bound is ~2x the measured ATE (issue 22): 3.69 mm
  // over 4.17 m = 0.089 % (sequential, deterministic; printed above).
  EXPECT_LE(report.ate.stats.rmse, 0.0018 * length);
}

}  // namespace
}  // namespace lumaslam
