// Relocalization against a map built from ground truth on one synthetic lap of a room: every
// other frame is a keyframe whose depth-measured features are map points; the frames in
// between are relocalized with no pose prior at all.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "loop_test_map.h"

#include "lumaslam/core/error.h"
#include "lumaslam/loop/relocalizer.h"
#include "lumaslam/loop/vocabulary_training.h"

namespace {

using namespace lumaslam;

constexpr int kFrames = 24;  // 15 degrees apart

struct LapMap {
  synth::SequenceRenderer sequence{synth::findPreset("loop-rgbd"), kFrames, 1};
  track::FrameBuilder builder{test::rgbdCameraOf(sequence.rig()), feature::OrbSettings{}};
  map::Map map;
  loop::Vocabulary vocabulary;
  loop::KeyFrameDatabase database;

  track::Frame buildFrame(const synth::SequenceRenderer& from, int index) const {
    return test::buildRgbdFrame(builder, from, index);
  }

  loop::RelocalizationFrame relocalizationFrame(const track::Frame& frame) const {
    return {frame.features.get(), builder.camera().intrinsics(), builder.pyramid().get(),
            builder.camera().pinhole.undistortedBounds()};
  }

  LapMap() {
    std::vector<track::Frame> keyframes;
    for (int i = 0; i < kFrames; i += 2) keyframes.push_back(buildFrame(sequence, i));
    std::vector<cv::Mat> descriptors;
    for (const auto& f : keyframes) descriptors.push_back(f.features->descriptors);
    loop::TrainingParams params;
    params.depth = 4;
    vocabulary = loop::trainVocabulary(descriptors, params);

    for (const auto& frame : keyframes) {
      const SE3 T_w_c = sequence.render(static_cast<int>(frame.index)).cam0.T_w_c;
      const auto keyframe = test::addKeyFrameWithPoints(map, builder, frame, T_w_c);
      loop::KeyFrameBow entry;
      vocabulary.transform(frame.features->descriptors, 4, entry.bow, entry.features);
      database.add(keyframe->id(), std::move(entry));
    }
  }
};

const LapMap& lapMap() {
  static const LapMap instance;
  return instance;
}

TEST(LoopRelocalizer, RelocalizesFramesBetweenKeyframesWithoutAPosePrior) {
  const LapMap& lap = lapMap();
  const loop::Relocalizer relocalizer(lap.vocabulary, lap.database, lap.map);
  std::vector<double> position_errors;
  std::vector<double> angle_errors;
  for (int index = 1; index < kFrames; index += 2) {
    const track::Frame frame = lap.buildFrame(lap.sequence, index);
    const auto result = relocalizer.relocalize(lap.relocalizationFrame(frame));
    ASSERT_TRUE(result.success) << "frame " << index << ": " << result.candidates << " candidates, "
                                << result.tried << " tried";
    EXPECT_GE(result.inliers, 50);
    int matched = 0;
    for (const auto& p : result.points) matched += p != nullptr;
    EXPECT_EQ(matched, result.inliers);
    // The keyframe used is one of the two neighbours on the lap (frames index -+ 1).
    const auto keyframe = lap.map.keyFrame(result.keyframe);
    ASSERT_TRUE(keyframe);
    const int gap = std::abs(static_cast<int>(keyframe->frameIndex()) - index);
    EXPECT_TRUE(gap == 1 || gap == kFrames - 1)
        << "frame " << index << " used keyframe of frame " << keyframe->frameIndex();
    const SE3 truth = lap.sequence.render(index).cam0.T_w_c.inverse();
    const SE3 error = result.T_c_w * truth.inverse();
    const double angle_deg = Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI;
    // Every pose close enough for tracking's projection search to take over (it then refines
    // against the whole local map, not one keyframe's ~60-110 points with ~1.5 px noise).
    EXPECT_LT(error.translation().norm(), 0.15) << "frame " << index;
    EXPECT_LT(angle_deg, 5.0) << "frame " << index;
    position_errors.push_back(error.translation().norm());
    angle_errors.push_back(angle_deg);
    std::printf("frame %d: %d candidates, %d tried, %d inliers, error %.1f mm %.2f deg\n", index,
                result.candidates, result.tried, result.inliers,
                1000.0 * error.translation().norm(), angle_deg);
  }
  // Typical accuracy.
  std::sort(position_errors.begin(), position_errors.end());
  std::sort(angle_errors.begin(), angle_errors.end());
  EXPECT_LT(position_errors[position_errors.size() / 2], 0.03);
  EXPECT_LT(angle_errors[angle_errors.size() / 2], 1.0);
}

TEST(LoopRelocalizer, FailsCleanlyInAnotherRoomOrInTheDark) {
  const LapMap& lap = lapMap();
  const loop::Relocalizer relocalizer(lap.vocabulary, lap.database, lap.map);
  const synth::SequenceRenderer other_room(synth::findPreset("loop-rgbd"), kFrames, 9);
  const track::Frame elsewhere = lap.buildFrame(other_room, 5);
  const auto result = relocalizer.relocalize(lap.relocalizationFrame(elsewhere));
  EXPECT_FALSE(result.success) << result.inliers << " inliers";
  EXPECT_EQ(result.points.size(), elsewhere.size());

  const cv::Mat black(lap.builder.camera().size(), CV_8UC1, cv::Scalar(0));
  const track::Frame dark = lap.builder.build(0, 0.0, black, cv::Mat());
  EXPECT_FALSE(relocalizer.relocalize(lap.relocalizationFrame(dark)).success);

  EXPECT_THROW(relocalizer.relocalize(loop::RelocalizationFrame{}), Error);
}

}  // namespace
