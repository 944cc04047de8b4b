// Pipeline::prepareAhead (what `lumaslam run` does to overlap detection with tracking): the
// frames are enhanced and pushed to the detector before the frame ahead of them is tracked,
// and the result is the same as tracking without it, bit for bit in sequential mode; a frame
// prepared and then not tracked leaves nothing pending; frames out of order are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "test_paths.h"
#include "test_system_dynamic.h"
#include "threaded_run_checks.h"

namespace lumaslam {
namespace {

constexpr int kFrames = 40;

struct Tracked {
  std::vector<FrameResult> results;
  Trajectory trajectory;
};

// A walking-people RGB-D sequence with the generator's true boxes as the detector's, with
// enhancement on (its statistics depend on the order in which it sees the images).
class PrepareAhead : public ::testing::Test {
 protected:
  PrepareAhead() : sequence_(synth::findPreset("walking-xyz-rgbd"), kFrames, 2) {
    test::GroundTruthBoxes truth;
    for (int i = 0; i < kFrames; ++i) truth.add(sequence_.render(i));
    truth.write(dir_.path() / "boxes.txt");
    settings_ = test::presetSettings(sequence_, [](std::string yaml) { return yaml; });
  }

  PipelineOptions options(bool sequential) const {
    PipelineOptions options;
    options.detector = "boxes:" + (dir_.path() / "boxes.txt").string();
    options.enhance_preset = "best";
    options.sequential = sequential;
    return options;
  }

  SensorFrame frame(int index) const {
    return test::sensorFrame(sequence_.render(index), settings_.sensor);
  }

  // Tracks every frame; with `ahead`, each frame is prepared when "read", one frame before it
  // is tracked, as run_pipeline.cpp's loop does.
  Tracked track(bool ahead, bool sequential) const {
    Pipeline system(settings_, options(sequential));
    Tracked tracked;
    if (ahead) system.prepareAhead(frame(0));
    for (int i = 0; i < kFrames; ++i) {
      if (ahead && i + 1 < kFrames) system.prepareAhead(frame(i + 1));
      tracked.results.push_back(system.track(frame(i)));
    }
    system.shutdown();
    tracked.trajectory = system.frameTrajectory();
    return tracked;
  }

  synth::SequenceRenderer sequence_;
  test::TempDir dir_{"prepare_ahead"};
  io::Settings settings_;
};

TEST_F(PrepareAhead, SequentialRunIsTheSameBitForBit) {
  const Tracked plain = track(false, true);
  const Tracked ahead = track(true, true);
  ASSERT_EQ(plain.trajectory.size(), ahead.trajectory.size());
  ASSERT_EQ(plain.trajectory.size(), static_cast<std::size_t>(kFrames));
  for (std::size_t i = 0; i < plain.trajectory.size(); ++i) {
    EXPECT_EQ(plain.trajectory[i].T_w_c.matrix(), ahead.trajectory[i].T_w_c.matrix()) << i;
  }
  std::size_t dropped = 0;
  std::size_t enhanced_ahead = 0;
  for (int i = 0; i < kFrames; ++i) {
    const auto& a = ahead.results[i];
    EXPECT_EQ(plain.results[i].dynamic_boxes, a.dynamic_boxes) << i;
    EXPECT_EQ(plain.results[i].dropped_features, a.dropped_features) << i;
    dropped += a.dropped_features.size();
    // The enhancement was done ahead and is counted in this frame's time.
    if (a.timing.enhance_ahead > 0.0 && a.timing.enhance_ahead == a.timing.enhance) {
      ++enhanced_ahead;
    }
    EXPECT_EQ(plain.results[i].timing.enhance_ahead, 0.0);
  }
  EXPECT_GT(dropped, 0U) << "the walkers' boxes must drop features for the test to mean anything";
  EXPECT_EQ(enhanced_ahead, static_cast<std::size_t>(kFrames));
}

// Threaded, which frames are tracked depends on the scheduling: properties, not a count.
TEST_F(PrepareAhead, ThreadedRunTracksWithTheSameBoxes) {
  const Tracked ahead = track(true, false);
  std::vector<track::TrackingOutcome> outcomes;
  std::vector<double> timestamps;
  for (int i = 0; i < kFrames; ++i) {
    outcomes.push_back(ahead.results[i].outcome);
    timestamps.push_back(frame(i).timestamp);
  }
  test::expectThreadedRun(outcomes, timestamps, ahead.trajectory);
  const Tracked plain = track(false, true);
  for (int i = 0; i < kFrames; ++i) {
    EXPECT_EQ(plain.results[i].dynamic_boxes, ahead.results[i].dynamic_boxes) << i;
  }
}

// Frame 1 is prepared and then skipped. Threaded (the detector in its own thread, as users run
// it) the frames tracked after it depend on the scheduling: properties; sequential
// (deterministic) every frame but the skipped one is tracked.
TEST_F(PrepareAhead, APreparedFrameThatIsNotTrackedLeavesNothingPending) {
  for (const bool sequential : {false, true}) {
    SCOPED_TRACE(sequential ? "sequential" : "threaded");
    Pipeline system(settings_, options(sequential));
    system.prepareAhead(frame(0));
    system.prepareAhead(frame(1));
    system.prepareAhead(frame(2));  // a third is not taken: two ahead at most
    std::vector<track::TrackingOutcome> outcomes;
    std::vector<double> timestamps;
    outcomes.push_back(system.track(frame(0)).outcome);
    EXPECT_EQ(outcomes.back().state, track::TrackingState::Ok);
    // Frame 1 was prepared but is skipped: its detection is taken and dropped.
    const FrameResult two = system.track(frame(2));
    outcomes.push_back(two.outcome);
    EXPECT_NE(two.outcome.state, track::TrackingState::Lost);
    EXPECT_FALSE(two.dynamic_boxes.empty());
    for (int i = 3; i < 6; ++i) outcomes.push_back(system.track(frame(i)).outcome);
    system.shutdown();
    for (const int i : {0, 2, 3, 4, 5}) timestamps.push_back(frame(i).timestamp);
    // Each tracked frame once in the trajectory, nothing for frame 1.
    test::expectTrackedOrLost(outcomes);
    test::expectEachTrackedFrameOnce(system.frameTrajectory(),
                                     test::trackedTimestamps(outcomes, timestamps));
    if (sequential) {
      EXPECT_EQ(system.frameTrajectory().size(), 5U);
    }
  }
}

TEST_F(PrepareAhead, FramesOutOfOrderAreRefused) {
  Pipeline system(settings_, options(true));
  system.prepareAhead(frame(3));
  const std::string message = test::errorOf([&] { system.track(frame(1)); });
  EXPECT_NE(message.find("frame 1 tracked after frame 3 was prepared ahead"), std::string::npos)
      << message;
}

TEST_F(PrepareAhead, ABadFramePreparedAheadIsRefusedByItsOwnTrack) {
  Pipeline system(settings_, options(true));
  SensorFrame bad = frame(0);
  bad.depth = cv::Mat();  // RGB-D without depth
  system.prepareAhead(bad);
  EXPECT_THROW(system.track(bad), Error);
  EXPECT_EQ(system.track(frame(1)).outcome.state, track::TrackingState::Ok);
}

}  // namespace
}  // namespace lumaslam
