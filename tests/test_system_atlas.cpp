// Issue 15 item 4 (ORB-SLAM3's Atlas) in the running System: the loop sequences of
// system_loop_run.h (a lap of the room, then part of a second lap) with a 3 s blackout while
// the camera turns to a part of the room the map has not seen. When the light returns the
// tracker cannot relocalize (nothing mapped there) and starts a second map at once; when the
// second lap comes back to where the first map began, the loop closer recognises the place
// and merges the maps. In the end >= 95 % of the lit frames are in one trajectory, in one
// world, ATE <= 2 cm (the acceptance), for RGB-D and for stereo, and for monocular (Sim3). Default
// vocabulary, as users run it; local mapping inline (sequential) so that the run is the same every
// time.
#include <algorithm>
#include <cstdio>
#include <optional>

#include <gtest/gtest.h>

#include "system_loop_run.h"

namespace lumaslam {
namespace {

constexpr int kLapFrames = 400;
constexpr int kSecondLapFrames = 200;  // 180 degrees past the start
constexpr int kFirstDark = 150;
constexpr int kDarkFrames = 90;   // 3 s at 30 Hz: the camera turns 81 degrees meanwhile
constexpr int kNewMapWindow = 5;  // frames after the light returns

struct AtlasRun {
  std::vector<track::TrackingOutcome> outcomes;
  std::vector<loop::ClosedLoop> merges;
  std::map<map::MapId, Trajectory> maps;
  Trajectory trajectory;  // the main map's frames
  double ate = 0.0;
};

AtlasRun runWithBlackout(const test::LoopInput& input, const test::SettingsEdit& edit = {},
                         std::optional<io::SensorType> sensor = std::nullopt) {
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  Pipeline system(test::presetSettings(input.lap, edit, sensor), options);
  const auto dark_in_blackout = [&](const synth::Frame& frame, int i) {
    SensorFrame sensor_frame = input.sensorInput(frame, i, sensor);
    if (i >= kFirstDark && i < kFirstDark + kDarkFrames) {
      sensor_frame.image = cv::Mat::zeros(sensor_frame.image.size(), sensor_frame.image.type());
      if (!sensor_frame.right.empty()) sensor_frame.right = sensor_frame.image.clone();
    }
    return sensor_frame;
  };
  AtlasRun run;
  const test::FedFrames fed = test::feedFrames(
      system, input.frames(), [&](int i) { return input.render(i); }, sensor, dark_in_blackout,
      [&](const synth::Frame&, const FrameResult& result) {
        run.outcomes.push_back(result.outcome);
      });
  const Trajectory& ground_truth = fed.ground_truth;
  if (system.loopCloser()) {
    for (const auto& closed : system.loopCloser()->closedLoops()) {
      if (closed.merged_map) run.merges.push_back(closed);
    }
  }
  run.maps = system.mapTrajectories();
  run.trajectory = system.frameTrajectory();
  if (run.trajectory.size() >= 3) {
    eval::EvaluationOptions alignment;  // monocular: Sim3 (scale unobservable)
    if (sensor == io::SensorType::Monocular) alignment.align = eval::AlignMode::Sim3;
    run.ate = eval::evaluate(run.trajectory, ground_truth, alignment).ate.stats.rmse;
  }
  std::printf("%s: %zu maps at the end, %zu merges, main map %zu frames, ATE %.1f mm\n",
              input.lap.preset().name.c_str(), run.maps.size(), run.merges.size(),
              run.trajectory.size(), 1000.0 * run.ate);
  for (const auto& merge : run.merges) {
    std::printf(
        "  map %u into map %u at keyframe %llu -> %llu, %d inliers, moved %.3f m %.1f deg\n",
        *merge.merged_map, merge.into_map, static_cast<unsigned long long>(merge.current),
        static_cast<unsigned long long>(merge.loop), merge.inliers, merge.correction_m,
        merge.correction_deg);
  }
  return run;
}

std::optional<int> firstNewMap(const AtlasRun& run) {
  for (std::size_t i = 0; i < run.outcomes.size(); ++i) {
    if (run.outcomes[i].new_map) return static_cast<int>(i);
  }
  return std::nullopt;
}

// `max_ate`: ~2x the ATE measured on 2026-12-04 (issue 22; sequential, deterministic; the
// "ATE ... mm" line runWithBlackout prints), much tighter than the 2 cm acceptance.
void expectMergedAtlas(const std::string& preset, double max_ate,
                       std::optional<io::SensorType> sensor = std::nullopt,
                       int new_map_window = kNewMapWindow) {
  const test::LoopInput input(kLapFrames, kSecondLapFrames, 1, preset);
  const AtlasRun run = runWithBlackout(input, {}, sensor);
  const int light_back = kFirstDark + kDarkFrames;
  // A second map, started at once when the light returns (not while it is dark).
  const auto new_map = firstNewMap(run);
  ASSERT_TRUE(new_map) << preset << ": no new map after the blackout";
  EXPECT_GE(*new_map, light_back) << preset;
  EXPECT_LT(*new_map, light_back + new_map_window) << preset;
  // ... merged into the first one when its area is seen again (the second lap).
  ASSERT_GE(run.merges.size(), 1U) << preset << ": the maps were never merged";
  EXPECT_EQ(run.merges.front().into_map, 0U) << preset;
  EXPECT_GE(run.merges.front().current, run.merges.front().loop) << preset;
  EXPECT_EQ(run.maps.size(), 1U) << preset << ": frames left in an unmerged map";
  const int lit_frames = input.frames() - kDarkFrames;
  EXPECT_GE(run.trajectory.size(), static_cast<std::size_t>(lit_frames * 95 / 100)) << preset;
  EXPECT_LE(run.ate, 0.02) << preset;  // the acceptance
  EXPECT_LE(run.ate, max_ate) << preset;
}

TEST(SystemAtlas, RgbdStartsANewMapAfterABlackoutAndMergesItOnTheSecondLap) {
  expectMergedAtlas("loop-rgbd", /*max_ate=*/0.0095);  // measured 4.6 mm
}

TEST(SystemAtlas, StereoStartsANewMapAfterABlackoutAndMergesItOnTheSecondLap) {
  expectMergedAtlas("loop-stereo", /*max_ate=*/0.0125);  // measured 6.1 mm
}

// Monocular (the left camera of loop-stereo): the new map needs a two-view initialisation
// (4 frames here) and is merged by a Sim3, which also corrects its scale (0.86 measured).
TEST(SystemAtlas, MonocularStartsANewMapAfterABlackoutAndMergesItOnTheSecondLap) {
  // Measured 5.9 mm (Sim3).
  expectMergedAtlas("loop-stereo", /*max_ate=*/0.012, io::SensorType::Monocular, 10);
}

// The same RGB-D run with new maps off (System.newMapAfter < 0): the tracker stays lost from
// the blackout until the relocalizer finds the first map on the second lap, so the frames in
// between have no pose (what the code did before new maps).
TEST(SystemAtlas, WithNewMapsOffTheFramesAfterTheBlackoutAreLost) {
  const test::LoopInput input(kLapFrames, kSecondLapFrames, 1, "loop-rgbd");
  const AtlasRun run = runWithBlackout(
      input, [](std::string yaml) { return yaml + "\nSystem.newMapAfter: -1.0\n"; });
  EXPECT_FALSE(firstNewMap(run));
  EXPECT_TRUE(run.merges.empty());
  EXPECT_EQ(run.maps.size(), 1U);
  const int lit_frames = input.frames() - kDarkFrames;
  EXPECT_LT(run.trajectory.size(), static_cast<std::size_t>(lit_frames * 80 / 100));
}

}  // namespace
}  // namespace lumaslam
