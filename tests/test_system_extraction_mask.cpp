// The feature budget goes to what is likely static (issue 16): a frame's features are taken
// outside the last frame's dynamic mask (the detector's boxes of the frame itself arrive after
// its features), then the features in its own boxes are dropped as before.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include "lumaslam/feature/orb_extractor.h"
#include "test_paths.h"
#include "test_people.h"
#include "test_system_dynamic.h"

namespace {

using namespace lumaslam;

using PointSet = std::set<std::pair<float, float>>;

PointSet pointsOf(const std::vector<cv::Point2f>& points) {
  PointSet set;
  for (const auto& p : points) set.emplace(p.x, p.y);
  return set;
}

struct BoxRun {
  std::vector<FrameResult> results;
  feature::OrbSettings orb;
};

// The people-only walking sequence with the generator's boxes as the detector.
BoxRun runWithTrueBoxes(const synth::SequenceRenderer& sequence, const std::filesystem::path& dir) {
  test::GroundTruthBoxes truth;
  for (int i = 0; i < sequence.frameCount(); ++i) truth.add(sequence.render(i));
  truth.write(dir / "boxes.txt");
  PipelineOptions options;
  options.detector = "boxes:" + (dir / "boxes.txt").string();
  options.motion_evidence = false;  // box removal alone
  BoxRun run;
  run.orb = feature::OrbSettings::fromSettings(*test::presetSettings(sequence).file);
  test::runSynthetic(sequence, options, [&](const synth::Frame&, const FrameResult& result) {
    run.results.push_back(result);
  });
  return run;
}

synth::SequenceRenderer walkers(int frames) {
  synth::SynthOptions people_only;
  people_only.moving_boxes = 0;
  return synth::SequenceRenderer(synth::findPreset("walking-xyz-rgbd"), frames, 1, people_only);
}

// Oracle: the extractor run by the test on the frame's image with the previous frame's mask
// gives exactly the features the frame had before its own boxes dropped some.
TEST(SystemExtractionMask, FeaturesAreTakenOutsideTheLastFramesMask) {
  test::TempDir dir("extraction_mask");
  const auto sequence = walkers(30);
  const auto run = runWithTrueBoxes(sequence, dir.path());
  const feature::OrbExtractor extractor(run.orb);
  int frames_checked = 0;
  for (std::size_t k = 1; k < run.results.size(); ++k) {
    const auto& previous_mask = run.results[k - 1].dynamic_mask;
    if (previous_mask.empty()) continue;
    const auto& result = run.results[k];
    PointSet expected;
    for (const auto& kp : extractor.extract(result.feature_image, previous_mask).keypoints)
      expected.emplace(kp.pt.x, kp.pt.y);
    PointSet got = pointsOf(result.kept_features);
    const auto dropped = pointsOf(result.dropped_features);
    got.insert(dropped.begin(), dropped.end());
    EXPECT_EQ(got, expected) << "frame " << k;
    for (const auto& p : result.kept_features) {
      EXPECT_EQ(previous_mask.at<uchar>(cvRound(p.y), cvRound(p.x)), 0) << "frame " << k;
    }
    ++frames_checked;
  }
  EXPECT_GT(frames_checked, 20);
}

// What it buys: with people in view, the features kept after removal come close to the
// extractor's budget, where taking them everywhere and dropping those in the boxes kept only
// the features outside the people.
TEST(SystemExtractionMask, KeptFeaturesStayNearTheBudgetWithPeopleInView) {
  test::TempDir dir("extraction_mask_budget");
  const auto sequence = walkers(40);
  const auto run = runWithTrueBoxes(sequence, dir.path());
  const feature::OrbExtractor extractor(run.orb);
  double kept = 0.0;
  double kept_without_mask = 0.0;
  int frames = 0;
  for (std::size_t k = 1; k < run.results.size(); ++k) {
    const auto& result = run.results[k];
    if (run.results[k - 1].dynamic_mask.empty() || result.dynamic_mask.empty()) continue;
    kept += static_cast<double>(result.kept_features.size());
    // The old way, computed here: every feature of the image, minus those in this frame's mask.
    const auto all = extractor.extract(result.feature_image).keypoints;
    kept_without_mask +=
        static_cast<double>(std::count_if(all.begin(), all.end(), [&](const cv::KeyPoint& kp) {
          return result.dynamic_mask.at<uchar>(cvRound(kp.pt.y), cvRound(kp.pt.x)) == 0;
        }));
    ++frames;
  }
  ASSERT_GT(frames, 20);
  const double budget = run.orb.nFeatures;
  spdlog::info(
      "kept features per frame with people in view: {:.0f} (without the mask {:.0f}) of {}",
      kept / frames, kept_without_mask / frames, budget);
  // Of the features the boxes took from the old way, at least half come back elsewhere
  // (measured 2026-12-04: 974 kept against 908 of 1000, i.e. 72 %).
  const double taken_by_boxes = budget - kept_without_mask / frames;
  EXPECT_GE(kept / frames - kept_without_mask / frames, 0.5 * taken_by_boxes);
}

// Two people sitting close to the camera carry 60-70 % of the image's features. Taking
// features everywhere and dropping those in the boxes left ~300, under the 500 an RGB-D map
// needs to start: 0 of 150 frames tracked. Outside the last frame's mask the map starts at
// frame 1 (frame 0 has no last mask).
TEST(SystemExtractionMask, PeopleSittingCloseToTheCameraLeaveEnoughFeaturesToStartAMap) {
  test::TempDir dir("extraction_mask_sitting");
  synth::SynthOptions photo_people;
  photo_people.people = test::labelledPeople();
  const synth::SequenceRenderer sequence(synth::findPreset("sitting-xyz-rgbd"), 100, 1,
                                         photo_people);
  test::GroundTruthBoxes truth;
  for (int i = 0; i < sequence.frameCount(); ++i) truth.add(sequence.render(i));
  truth.write(dir.path() / "boxes.txt");
  PipelineOptions options;
  options.detector = "boxes:" + (dir.path() / "boxes.txt").string();
  options.motion_evidence = false;  // box removal alone
  const auto run = test::runSynthetic(sequence, options);
  EXPECT_GE(run.tracked, run.frames - 1);
  // ~2x the measured ATE (issue 22): 4.9 mm, 99/100 tracked (sequential; 2026-12-08,
  // `build/tests/test_system_extraction_mask --gtest_filter=*PeopleSitting*`, "ATE rmse").
  EXPECT_LE(run.ate(), 0.01);
}

}  // namespace
