// Class-free motion evidence (issue 16): with no detector at all, the tracker's own residual
// and flow tests keep people and objects it was never told about out of the pose. Synthetic
// RGB-D walking sequences, sequential mapping; `motion_evidence = false` is the code before.
#include <gtest/gtest.h>

#include "test_people.h"
#include "test_system_dynamic.h"

namespace {

using namespace lumaslam;

PipelineOptions withoutDetector(bool motion_evidence) {
  PipelineOptions options;
  options.detector = "none";
  options.motion_evidence = motion_evidence;
  return options;
}

synth::SequenceRenderer photoWalkers(const std::string& preset, int frames, int seed) {
  synth::SynthOptions people;
  people.moving_boxes = 0;
  people.people = test::labelledPeople();
  return synth::SequenceRenderer(synth::findPreset(preset), frames, seed, people);
}

// Runs `sequence` without a detector, with and without the motion test: with it, every frame
// tracked, ATE <= 3 cm (issue 16's target: geometry only) and <= `max_ate`, and at most `ratio`
// of the error without. `max_ate`: ~2x the ATE measured on 2026-12-04 (issue 22; sequential,
// deterministic; re-measure: the second "ATE rmse" line each test logs).
void expectRemovedWithoutADetector(const synth::SequenceRenderer& sequence, double ratio,
                                   double max_ate) {
  const auto before = test::runSynthetic(sequence, withoutDetector(false));
  const auto run = test::runSynthetic(sequence, withoutDetector(true));
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LE(run.ate(), 0.03);  // issue 16's target
  EXPECT_LE(run.ate(), max_ate);
  EXPECT_LE(run.ate(), ratio * before.ate()) << "before " << before.ate();
}

// Walkers cut from real person photos pass close to the camera (one covers a quarter of the
// view): without the test the tracker follows them by over a metre (1.23 m -> 4.4 mm).
TEST(SystemMotionEvidence, KeepsPhotoWalkersOutOfThePoseWithoutADetector) {
  expectRemovedWithoutADetector(photoWalkers("walking-xyz-rgbd", 100, 1), 0.1,
                                /*max_ate=*/0.009);  // measured 4.4 mm
}

// The moving crate has no COCO class: no detector could remove it (0.30 m -> 4.5 mm).
TEST(SystemMotionEvidence, KeepsTheCrateAndProceduralWalkersOutWithoutADetector) {
  expectRemovedWithoutADetector(
      synth::SequenceRenderer(synth::findPreset("walking-xyz-rgbd"), 100, 1), 1.0 / 3.0,
      /*max_ate=*/0.0095);  // measured 4.5 mm
}

// A still camera and people walking through the whole view, TUM walking_static (0.59 m ->
// 3.5 mm).
TEST(SystemMotionEvidence, KeepsAStillCameraStillWhilePeopleWalkBy) {
  expectRemovedWithoutADetector(photoWalkers("walking-static-rgbd", 100, 1), 1.0 / 3.0,
                                /*max_ate=*/0.0075);  // measured 3.5 mm
}

// Two people sitting side by side close to the camera, shifting 4.5-6.5 cm at 3-4 cm/s (TUM
// sitting_xyz): about a millimetre per frame, too slow to show as motion from one frame to the
// next. The test must do no harm (issue 16: no more than 10 % above the run without it).
TEST(SystemMotionEvidence, DoesNoHarmWithPeopleSittingInView) {
  const auto sequence = photoWalkers("sitting-xyz-rgbd", 100, 1);
  const auto before = test::runSynthetic(sequence, withoutDetector(false));
  const auto run = test::runSynthetic(sequence, withoutDetector(true));
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LE(run.ate(), 1.1 * before.ate() + 0.0005) << "before " << before.ate();
}

// Nothing moves: the test must not cost accuracy, nor take many static points for moving.
TEST(SystemMotionEvidence, CostsNothingOnAStaticScene) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 100, 1);
  const auto before = test::runSynthetic(sequence, withoutDetector(false));
  PipelineOptions options = withoutDetector(true);
  options.enhance_preset = "off";
  options.sequential = true;
  Pipeline system(test::presetSettings(sequence), options);
  const test::FedFrames fed = test::feedFrames(
      system, sequence.frameCount(), [&](int i) { return sequence.render(i); }, std::nullopt);
  const auto report =
      eval::evaluate(system.frameTrajectory(), fed.ground_truth, eval::EvaluationOptions{});
  EXPECT_EQ(report.matched_poses, 100U);
  // Issue 16: no more than 10 % above the run without the test (+ 0.5 mm for a few-mm ATE).
  EXPECT_LE(report.ate.stats.rmse, 1.1 * before.ate() + 0.0005) << "before " << before.ate();
  // Measured 5 %: points that fail the chi-square test in most frames (a depth from the wrong
  // side of an edge), outliers of pose optimisation with or without the motion test.
  const double moving = static_cast<double>(system.tracker().movingPointCount());
  spdlog::info("static scene: ATE {:.4f} m (without the test {:.4f} m), {} of {} points moving",
               report.ate.stats.rmse, before.ate(), moving, system.mapPointCount());
  EXPECT_LE(moving, 0.1 * static_cast<double>(system.mapPointCount()));
}

}  // namespace
