// loop::PlaceRecognition as the Map's KeyFrameIndex: keyframes enter the database with their
// BoW when they join the map, leave it when retired, and the database answers queries with
// them; a missing or empty vocabulary file is an Error naming it.
#include <fstream>

#include <gtest/gtest.h>

#include "error_of.h"
#include "loop_test_frames.h"
#include "lumaslam/core/error.h"
#include "lumaslam/loop/place_recognition.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "lumaslam/loop/vocabulary_training.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map.h"
#include "test_paths.h"

namespace lumaslam {
namespace {

std::shared_ptr<map::KeyFrame> keyFrameOf(map::Map& map, const cv::Mat& descriptors) {
  auto features = std::make_shared<map::FeatureSet>();
  features->descriptors = descriptors;
  features->keypoints.resize(static_cast<std::size_t>(descriptors.rows));
  return std::make_shared<map::KeyFrame>(
      map.nextKeyFrameId(), 0, 0.0, SE3::Identity(), std::move(features),
      std::make_shared<feature::ScaleLevels>(8, 1.2F), CameraIntrinsics{});
}

TEST(LoopPlaceRecognition, FollowsTheMapsKeyFrames) {
  const auto lap = test::renderLoopLap(8, 3, 500);
  loop::TrainingParams params;
  params.branching = 6;
  params.depth = 3;
  auto places =
      std::make_shared<loop::PlaceRecognition>(loop::trainVocabulary(lap.descriptors, params));
  map::Map map;
  const auto first = keyFrameOf(map, lap.descriptors[0]);
  map.addKeyFrame(first);
  map.setKeyFrameIndex(places);  // keyframes already in the map are indexed at once
  EXPECT_EQ(places->database().size(), 1U);
  std::vector<std::shared_ptr<map::KeyFrame>> keyframes = {first};
  for (std::size_t i = 1; i < lap.descriptors.size(); ++i) {
    keyframes.push_back(keyFrameOf(map, lap.descriptors[i]));
    map.addKeyFrame(keyframes.back());
  }
  ASSERT_EQ(places->database().size(), lap.descriptors.size());
  const auto entry = places->database().entry(keyframes[3]->id());
  ASSERT_TRUE(entry);
  EXPECT_FALSE(entry->features.empty());  // direct index filled

  // A keyframe's own image finds it first.
  const auto bow = places->vocabulary().transform(lap.descriptors[3]);
  auto candidates = places->database().query(bow);
  ASSERT_FALSE(candidates.empty());
  EXPECT_EQ(candidates.front().id, keyframes[3]->id());

  // Retired: gone from the database, no longer a candidate.
  ASSERT_TRUE(map.retireKeyFrame(keyframes[3]));
  EXPECT_FALSE(places->database().contains(keyframes[3]->id()));
  EXPECT_EQ(places->database().size(), lap.descriptors.size() - 1);
  candidates = places->database().query(bow);
  for (const auto& c : candidates) EXPECT_NE(c.id, keyframes[3]->id());

  map.clear();
  EXPECT_EQ(places->database().size(), 0U);
}

TEST(LoopPlaceRecognition, BadVocabularyFilesAreErrorsNamingThem) {
  const test::TempDir dir("place_recognition");
  const auto missing = dir.path() / "missing.bin";
  // A missing file is an error.
  const std::string message = test::errorOf([&] { loop::PlaceRecognition::fromFile(missing); });
  EXPECT_NE(message.find("missing.bin"), std::string::npos) << message;
  const auto garbage = dir.path() / "garbage.txt";
  std::ofstream(garbage) << "not a vocabulary\n";
  EXPECT_THROW(loop::PlaceRecognition::fromFile(garbage), Error);
}

}  // namespace
}  // namespace lumaslam
