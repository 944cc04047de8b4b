// YOLO in the loop (issue 6): on walking-xyz-rgbd with walkers cut from real person photos
// (SynthOptions::people), YOLOv5n-320 finds the walkers and removal brings the ATE to the
// box-file level. The sequence has no moving crate: YOLO knows no "box".
#include <gtest/gtest.h>

#include "test_paths.h"
#include "test_people.h"
#include "test_system_dynamic.h"

namespace {

using namespace lumaslam;

TEST(SystemDynamicPeople, YoloRemovalOnPhotoWalkersMeetsTheIssueTarget) {
  const auto model = test::modelsDir() / "yolov5n-320.onnx";
  synth::SynthOptions photo_walkers;
  photo_walkers.moving_boxes = 0;
  photo_walkers.people = test::labelledPeople();
  const synth::SequenceRenderer sequence(synth::findPreset("walking-xyz-rgbd"), 100, 1,
                                         photo_walkers);
  PipelineOptions without_options;
  without_options.detector = "none";
  without_options.motion_evidence = false;  // box removal alone (issue 6)
  const auto without = test::runSynthetic(sequence, without_options, {});
  PipelineOptions yolo_options;
  yolo_options.detector = "yolo:" + model.string();
  yolo_options.motion_evidence = false;  // box removal alone (issue 6)
  std::size_t frames_with_drops = 0;
  const auto yolo =
      test::runSynthetic(sequence, yolo_options, [&](const synth::Frame&, const FrameResult& r) {
        if (!r.dropped_features.empty()) ++frames_with_drops;
      });
  EXPECT_EQ(yolo.tracked, yolo.frames);
  EXPECT_GT(frames_with_drops, 50U);  // the walkers are in view most of the time
  // Issue 6: with YoloDetector <= 2 cm; and removal must matter (<= 1/3 of the error without).
  EXPECT_LE(yolo.ate(), 0.02) << "without " << without.ate();
  EXPECT_LE(yolo.ate(), without.ate() / 3.0);
  // ~2x the measured ATE (issue 22): 5.3 mm on 2026-12-04 (sequential, deterministic; the
  // "detector yolo" line the test logs).
  EXPECT_LE(yolo.ate(), 0.011);
}

// The generator's boxes are tight: features on the background just beside a walker's
// silhouette survive the depth refinement (their depth is the wall's) but their descriptor
// patches show the walker. Without the band that Detector.depthEdge keeps masked around the
// silhouette, this sequence had a 4.8 cm error spike (ATE 7.6 mm); with it every frame stays
// within 1.2 cm (ATE 4.4 mm).
TEST(SystemDynamicPeople, GroundTruthBoxRemovalKeepsEveryFrameNearTheTruth) {
  synth::SynthOptions photo_walkers;
  photo_walkers.moving_boxes = 0;
  photo_walkers.people = test::labelledPeople();
  const synth::SequenceRenderer sequence(synth::findPreset("walking-xyz-rgbd"), 100, 1,
                                         photo_walkers);
  test::GroundTruthBoxes boxes;
  for (int i = 0; i < sequence.frameCount(); ++i) boxes.add(sequence.render(i));
  const test::TempDir dir("people_gt_boxes");
  const auto box_file = dir.path() / "detections.txt";
  boxes.write(box_file);
  PipelineOptions options;
  options.detector = "boxes:" + box_file.string();
  options.motion_evidence = false;  // box removal alone (issue 6)
  const auto run = test::runSynthetic(sequence, options);
  spdlog::info("ground-truth boxes: ATE rmse {:.2f} mm, max {:.2f} mm", 1000.0 * run.ate(),
               1000.0 * run.report.ate.stats.max);
  EXPECT_EQ(run.tracked, run.frames);
  EXPECT_LE(run.ate(), 0.01);  // issue 6's box-file target
  // ~2x the measured errors (issue 22): ATE 4.38 mm on 2026-12-04 (sequential, deterministic;
  // logged above); max 11.93 mm, the 2 cm bound was already within 2x.
  EXPECT_LE(run.ate(), 0.009);
  EXPECT_LE(run.report.ate.stats.max, 0.02);
}

}  // namespace
