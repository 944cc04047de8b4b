// Issue 7 acceptance, relocalization in the running System: a synthetic RGB-D sequence whose
// images go black (20 frames) or over-exposed (10 frames x5) in the middle. Frames without
// light are Lost with no pose; when the light returns the camera is far from where it was
// lost, the tracker relocalizes against the same map (BoW + PnP) within 5 frames (sequential
// runs; the threaded one: eventually, and stays tracked), and the poses after recovery are in
// the first map's world. The vocabulary is the default one (trained on real images, none of
// the generator's), as users get it; "none" for the run that shows what the tracker does
// without one.
// Enhancement `best` is on, as users run it: its online statistics see the dark frames too.
// Disturbed frames that are tracked must be true (<= 2 cm): no invented poses. A stereo run
// (xyz-stereo, both images over-exposed) checks the same for the over-exposure.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "test_system_run.h"
#include "threaded_run_checks.h"

namespace lumaslam {
namespace {

constexpr int kFrames = 120;
constexpr int kFirstDark = 50;
constexpr std::uint64_t kSeed = 3;
constexpr int kRecoveryWindow = 5;  // frames after the light returns (acceptance, sequential)
constexpr double kMaxErrorWhileDisturbed = 0.02;  // metres, for a disturbed frame not Lost

// RGB-D: the fast-turning rpy-rgbd sequence with enhancement `best`. Stereo: xyz-stereo played
// twice as fast, enhancement off, where x5 over-exposed pairs kept 100 local-map inliers with
// poses 2-3 cm off before the tracker compared them with the last tracked frame's.
enum class Sensor { Rgbd, Stereo };

const char* enhancementFor(Sensor sensor) {
  return sensor == Sensor::Rgbd ? "best" : "off";
}

synth::Preset presetFor(Sensor sensor) {
  if (sensor == Sensor::Rgbd) return synth::findPreset("rpy-rgbd");
  synth::Preset preset = synth::findPreset("xyz-stereo");
  preset.motion_speed = 2.0;
  return preset;
}

const synth::SequenceRenderer& sequence(Sensor sensor) {
  if (sensor == Sensor::Rgbd) {
    static const synth::SequenceRenderer rgbd(presetFor(Sensor::Rgbd), kFrames, kSeed);
    return rgbd;
  }
  static const synth::SequenceRenderer stereo(presetFor(Sensor::Stereo), kFrames, kSeed);
  return stereo;
}

using Disturbance = std::function<cv::Mat(const cv::Mat&)>;

struct DisturbedRun {
  Sensor sensor = Sensor::Rgbd;
  bool sequential = true;
  std::vector<track::TrackingOutcome> outcomes;  // per frame
  std::vector<double> timestamps;                // per frame
  std::vector<double> tracking_ms;               // per frame (printed, never asserted)
  Trajectory trajectory;                         // Pipeline::frameTrajectory()
  Trajectory keyframes;
  std::size_t keyframes_before = 0;  // when the light went
};

// Runs the sequence with images [kFirstDark, kFirstDark + dark_frames) disturbed.
DisturbedRun runDisturbed(int dark_frames, const Disturbance& disturb, bool with_vocabulary,
                          bool sequential = true, Sensor sensor = Sensor::Rgbd) {
  PipelineOptions options;
  options.enhance_preset = enhancementFor(sensor);
  options.sequential = sequential;
  if (!with_vocabulary) options.vocabulary = "none";
  Pipeline system(test::presetSettings(sequence(sensor)), options);
  DisturbedRun run;
  run.sensor = sensor;
  run.sequential = sequential;
  for (int i = 0; i < kFrames; ++i) {
    auto input = test::sensorFrame(sequence(sensor).render(i));
    if (i == kFirstDark) run.keyframes_before = system.keyFrameCount();
    if (i >= kFirstDark && i < kFirstDark + dark_frames) {
      input.image = disturb(input.image);
      if (!input.right.empty()) input.right = disturb(input.right);
    }
    const auto result = system.track(input);
    run.outcomes.push_back(result.outcome);
    run.timestamps.push_back(input.timestamp);
    run.tracking_ms.push_back(result.timing.tracking);
  }
  system.shutdown();
  run.trajectory = system.frameTrajectory();
  run.keyframes = system.keyFrameTrajectory();
  return run;
}

cv::Mat black(const cv::Mat& image) {
  return cv::Mat::zeros(image.size(), image.type());
}

cv::Mat overExposed(const cv::Mat& image) {
  cv::Mat bright;
  image.convertTo(bright, -1, 5.0);  // saturates
  return bright;
}

std::optional<int> firstTrackedFrom(const DisturbedRun& run, int from) {
  for (int i = from; i < kFrames; ++i) {
    if (run.outcomes[static_cast<std::size_t>(i)].state == track::TrackingState::Ok) return i;
  }
  return std::nullopt;
}

bool recoveredByRelocalizer(const DisturbedRun& run, int light_back) {
  const auto recovered = firstTrackedFrom(run, light_back);
  return recovered && run.outcomes[static_cast<std::size_t>(*recovered)].relocalized;
}

// Position errors (metres) of the tracked frames from `from` on, in the world of the map
// started before the disturbance: no alignment, the ground truth is expressed relative to
// the first keyframe's frame as the Pipeline's world is.
std::vector<double> positionErrorsFrom(const DisturbedRun& run, int from, int to = kFrames) {
  const auto& frames = sequence(run.sensor);
  const double t0 = run.keyframes.front().timestamp;
  int first_keyframe = 0;
  while (frames.render(first_keyframe).timestamp() < t0 - 1e-6) ++first_keyframe;
  const SE3 T_w0_w = frames.render(first_keyframe).cam0.T_w_c.inverse();
  const double t_from = frames.render(from).timestamp() - 1e-6;
  const double t_to = to < kFrames ? frames.render(to).timestamp() - 1e-6 : 1e300;
  std::vector<double> errors;
  for (const auto& pose : run.trajectory) {
    if (pose.timestamp < t_from || pose.timestamp >= t_to) continue;
    const SE3 truth = T_w0_w * frames.poseAt(pose.timestamp);
    errors.push_back((pose.T_w_c.translation() - truth.translation()).norm());
  }
  return errors;
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v * v;
  return values.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(values.size()));
}

// Checks the acceptance after `dark_frames` disturbed frames; returns how many were lost.
// `max_rms`: position RMSE from the disturbance on, ~2x the value measured on 2026-12-04
// (issue 22; the "position RMSE" the test prints; threaded: worst of 3 runs).
int expectRecoveredInTheSameMap(const DisturbedRun& run, int dark_frames, const char* what,
                                double max_rms) {
  const int light_back = kFirstDark + dark_frames;
  // Disturbed frames are Lost with no pose in the trajectory, or tracked (checked below with
  // the rest).
  int lost = 0;
  for (int i = kFirstDark; i < light_back; ++i) {
    const auto& outcome = run.outcomes[static_cast<std::size_t>(i)];
    if (outcome.state != track::TrackingState::Lost) continue;
    ++lost;
    EXPECT_FALSE(outcome.T_w_c) << what << ": frame " << i;
    const double t = sequence(run.sensor).render(i).timestamp();
    EXPECT_TRUE(std::none_of(run.trajectory.begin(), run.trajectory.end(),
                             [&](const auto& p) { return std::abs(p.timestamp - t) < 1e-6; }))
        << what << ": lost frame " << i << " has a pose in the trajectory";
  }
  // A disturbed frame that is tracked must have a true pose: no invented poses (issue 7).
  const auto disturbed_errors = positionErrorsFrom(run, kFirstDark, light_back);
  for (const double error : disturbed_errors) {
    EXPECT_LE(error, kMaxErrorWhileDisturbed)
        << what << ": a disturbed frame is tracked " << 1000.0 * error << " mm off";
  }
  const auto recovered = firstTrackedFrom(run, light_back);
  if (!recovered) {
    ADD_FAILURE() << what << ": never recovered";
    return lost;
  }
  // Same map: the first keyframe is still the origin, keyframes were only added to it, and
  // the frames after the recovery are tracked in it (the trajectory is the main map's).
  EXPECT_GE(run.keyframes.size(), run.keyframes_before) << what;
  EXPECT_NEAR(run.keyframes.front().timestamp, sequence(run.sensor).render(0).timestamp(), 0.5)
      << what;
  test::expectTrackedOrLost(run.outcomes);
  test::expectEachTrackedFrameOnce(run.trajectory,
                                   test::trackedTimestamps(run.outcomes, run.timestamps));
  if (run.sequential) {  // deterministic: the acceptance's window, then every frame
    EXPECT_LT(*recovered, light_back + kRecoveryWindow) << what;
    for (int i = *recovered; i < kFrames; ++i) {
      EXPECT_EQ(run.outcomes[static_cast<std::size_t>(i)].state, track::TrackingState::Ok)
          << what << ": frame " << i;
    }
  } else {  // which keyframes the map has depends on the scheduling: recovered and stays so
    test::expectMostlyTracked(
        test::trackedFlags(run.outcomes, static_cast<std::size_t>(*recovered)), what);
  }
  const auto errors = positionErrorsFrom(run, kFirstDark);
  EXPECT_GT(errors.size(), 40U) << what;
  if (errors.empty()) return lost;
  std::printf(
      "%s: lost %d of %d frames (tracked ones max %.1f mm off), tracking at frame %d (%d after "
      "the light)%s in %.1f ms (median frame %.1f ms), %zu frames tracked from the disturbance "
      "on, position RMSE %.1f mm, max %.1f mm (no alignment)\n",
      what, lost, dark_frames,
      disturbed_errors.empty()
          ? 0.0
          : 1000.0 * *std::max_element(disturbed_errors.begin(), disturbed_errors.end()),
      *recovered, *recovered - light_back,
      run.outcomes[static_cast<std::size_t>(*recovered)].relocalized ? " by relocalization" : "",
      run.tracking_ms[static_cast<std::size_t>(*recovered)], median(run.tracking_ms), errors.size(),
      1000.0 * rms(errors), 1000.0 * *std::max_element(errors.begin(), errors.end()));
  EXPECT_LT(rms(errors), 0.02) << what;  // issue 7's acceptance
  EXPECT_LE(rms(errors), max_rms) << what;
  return lost;
}

TEST(SystemRelocalization, RecoversAfterTwentyBlackFrames) {
  const auto run = runDisturbed(20, black, true);
  EXPECT_EQ(expectRecoveredInTheSameMap(run, 20, "blackout", 0.014), 20);  // measured 6.8 mm
  // The camera turned too far for the last-pose search (see the test without vocabulary):
  // the relocalizer is what found the map again.
  EXPECT_TRUE(recoveredByRelocalizer(run, kFirstDark + 20));
}

// Pixel values x5 saturate most of the image: tracking is lost, and the relocalizer finds
// the map again when the exposure returns. Local mapping in its own thread, as users run it:
// keyframes enter the database from the tracker while mapping culls them from its thread. The
// recovery is checked by properties (no window, no exact count): the keyframes to relocalize
// against depend on the scheduling.
TEST(SystemRelocalization, RecoversAfterTenOverExposedFramesThreaded) {
  const auto run = runDisturbed(10, overExposed, true, /*sequential=*/false);
  // Measured 7.2-8.5 mm in 3 runs.
  EXPECT_GT(expectRecoveredInTheSameMap(run, 10, "over-exposure x5", 0.0175), 0);
  EXPECT_TRUE(recoveredByRelocalizer(run, kFirstDark + 10));
}

// The same sequential (deterministic): the acceptance's window, then every frame tracked.
TEST(SystemRelocalization, RecoversAfterTenOverExposedFrames) {
  const auto run = runDisturbed(10, overExposed, true);
  // Measured 9.7 mm (2026-12-08, 2 runs identical).
  EXPECT_GT(expectRecoveredInTheSameMap(run, 10, "over-exposure x5, sequential", 0.0195), 0);
  EXPECT_TRUE(recoveredByRelocalizer(run, kFirstDark + 10));
}

// Stereo, x5 over-exposure: the few unsaturated features are matched at displaced places, and
// 100 of them passed the 30-inlier rule with poses 19-27 mm off. Every disturbed pair must be
// Lost or true (<= 2 cm); here the last-pose search finds the map again (slower motion).
TEST(SystemRelocalization, StereoOverExposedFramesAreLostOrTrue) {
  const auto run = runDisturbed(10, overExposed, true, /*sequential=*/true, Sensor::Stereo);
  expectRecoveredInTheSameMap(run, 10, "stereo over-exposure x5", 0.0055);  // measured 2.6 mm
}

// Without a vocabulary the camera has turned too far during the blackout for the search around
// the last pose (before the reference-keyframe fallback it stayed lost past the recovery
// window); matching the last reference keyframe by descriptors finds the map again, in the
// same map and with true poses, and nothing is reported as relocalized.
TEST(SystemRelocalization, WithoutVocabularyTheReferenceKeyFrameRecoversTheBlackout) {
  const auto run = runDisturbed(20, black, false);
  // Measured 6.6 mm.
  EXPECT_EQ(expectRecoveredInTheSameMap(run, 20, "blackout without vocabulary", 0.0135), 20);
  for (const auto& outcome : run.outcomes) EXPECT_FALSE(outcome.relocalized);
}

TEST(SystemRelocalization, MissingVocabularyIsAnErrorNamingTheFile) {
  PipelineOptions options;
  options.enhance_preset = "off";
  options.vocabulary = "/nonexistent/vocab.bin";
  // A missing vocabulary is an error.
  const std::string message = test::errorOf(
      [&] { Pipeline system(test::presetSettings(sequence(Sensor::Rgbd)), options); });
  EXPECT_NE(message.find("/nonexistent/vocab.bin"), std::string::npos) << message;
}

}  // namespace
}  // namespace lumaslam
