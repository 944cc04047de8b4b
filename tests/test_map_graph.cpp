#include <gtest/gtest.h>

#include <random>
#include <thread>

#include "lumaslam/map/map.h"

namespace lm = lumaslam::map;
using lumaslam::SE3;

namespace {

// Keyframes on a line along x looking along +z; point j lies at x = 0.1 j and is seen by every
// keyframe whose x is within `reach` of it. Each keyframe has one feature per point it sees.
struct LineScene {
  lm::Map map;
  std::vector<std::shared_ptr<lm::KeyFrame>> keyframes;
  std::vector<std::shared_ptr<lm::MapPoint>> points;

  LineScene(int keyframe_count, int point_count, double reach, bool stereo = false) {
    auto pyramid = std::make_shared<const lumaslam::feature::ScaleLevels>(8, 1.2F);
    std::mt19937 rng(7);
    std::vector<std::vector<int>> seen_by(keyframe_count);
    for (int k = 0; k < keyframe_count; ++k) {
      for (int j = 0; j < point_count; ++j) {
        if (std::abs(0.1 * j - 0.5 * k) <= reach) seen_by[k].push_back(j);
      }
    }
    for (int j = 0; j < point_count; ++j) {
      points.push_back(nullptr);  // created when first seen, with that keyframe as reference
    }
    for (int k = 0; k < keyframe_count; ++k) {
      auto features = std::make_shared<lm::FeatureSet>();
      features->descriptors = cv::Mat(static_cast<int>(seen_by[k].size()), 32, CV_8U);
      cv::randu(features->descriptors, 0, 256);
      for (std::size_t i = 0; i < seen_by[k].size(); ++i) {
        cv::KeyPoint kp(320.0F, 240.0F, 31.0F);
        kp.octave = static_cast<int>(i % 3);
        features->keypoints.push_back(kp);
        features->undistorted.emplace_back(kp.pt);
        features->u_right.push_back(stereo ? 300.0F : -1.0F);
        features->depth.push_back(stereo ? 2.0F : -1.0F);
      }
      SE3 T_w_c = SE3::Identity();
      T_w_c.translation() = Eigen::Vector3d(0.5 * k, 0, 0);
      auto kf = std::make_shared<lm::KeyFrame>(map.nextKeyFrameId(), static_cast<std::size_t>(k),
                                               0.1 * k, T_w_c.inverse(), features, pyramid,
                                               lumaslam::CameraIntrinsics{500, 500, 320, 240, 0});
      map.addKeyFrame(kf);
      for (std::size_t i = 0; i < seen_by[k].size(); ++i) {
        const int j = seen_by[k][i];
        if (!points[j]) {
          points[j] = std::make_shared<lm::MapPoint>(map.nextMapPointId(),
                                                     Eigen::Vector3d(0.1 * j, 0, 2), kf);
          map.addMapPoint(points[j]);
        }
        kf->setMapPoint(i, points[j]);
        points[j]->addObservation(kf, static_cast<int>(i));
      }
      kf->updateConnections();
      keyframes.push_back(kf);
    }
  }

  int shared(int a, int b) const {
    int n = 0;
    for (const auto& p : keyframes[a]->mapPoints()) {
      if (p && p->featureIndexIn(keyframes[b]->id()) >= 0) ++n;
    }
    return n;
  }
};

TEST(MapGraph, CovisibilityWeightsAreSharedPointCounts) {
  LineScene scene(6, 60, 1.6);
  for (int a = 0; a < 6; ++a) {
    for (int b = 0; b < 6; ++b) {
      if (a == b) continue;
      const int shared = scene.shared(a, b);
      const int weight = scene.keyframes[a]->weight(scene.keyframes[b]->id());
      if (shared >= lm::KeyFrame::kMinCovisibilityWeight) {
        EXPECT_EQ(weight, shared) << a << "-" << b;
      } else {
        EXPECT_EQ(weight, 0) << a << "-" << b;
      }
    }
  }
  // Sorted by weight: the nearest neighbours first.
  const auto best = scene.keyframes[2]->covisibles(2);
  ASSERT_EQ(best.size(), 2U);
  EXPECT_GE(scene.keyframes[2]->weight(best[0]->id()), scene.keyframes[2]->weight(best[1]->id()));
  EXPECT_TRUE(best[0]->id() == 1 || best[0]->id() == 3);
}

TEST(MapGraph, SpanningTreeParentIsStrongestOlderNeighbour) {
  LineScene scene(6, 60, 1.6);
  EXPECT_EQ(scene.keyframes[0]->parent(), nullptr);
  for (int k = 1; k < 6; ++k) {
    const auto parent = scene.keyframes[k]->parent();
    ASSERT_NE(parent, nullptr) << k;
    EXPECT_EQ(parent->id(), scene.keyframes[k - 1]->id());
    const auto children = parent->children();
    EXPECT_TRUE(std::any_of(children.begin(), children.end(),
                            [&](const auto& c) { return c == scene.keyframes[k]; }));
  }
}

TEST(MapGraph, RetiringAKeyFrameDetachesItAndReparentsChildren) {
  LineScene scene(6, 60, 1.6);
  const auto victim = scene.keyframes[2];
  EXPECT_FALSE(scene.map.retireKeyFrame(scene.keyframes[0])) << "origin must never be retired";
  ASSERT_TRUE(scene.map.retireKeyFrame(victim));
  EXPECT_TRUE(victim->isBad());
  EXPECT_EQ(scene.map.keyFrame(victim->id()), nullptr);
  EXPECT_EQ(scene.map.keyFrameCount(), 5U);
  for (const auto& kf : scene.map.keyFrames()) {
    EXPECT_EQ(kf->weight(victim->id()), 0);
    for (const auto& p : kf->mapPoints()) {
      if (p) {
        EXPECT_EQ(p->featureIndexIn(victim->id()), -1);
      }
    }
  }
  // Its child (keyframe 3) now hangs from keyframe 1, the remaining neighbour it shares most with.
  ASSERT_NE(scene.keyframes[3]->parent(), nullptr);
  EXPECT_EQ(scene.keyframes[3]->parent()->id(), scene.keyframes[1]->id());
  // The retired keyframe keeps its pose relative to the parent for trajectory export.
  const SE3 T_w_victim = scene.keyframes[1]->T_w_c() * victim->T_c_parent().inverse();
  EXPECT_NEAR((T_w_victim.translation() - victim->center()).norm(), 0.0, 1e-12);
}

TEST(MapGraph, PointsLeftWithTooFewObservationsAreRetired) {
  LineScene scene(4, 40, 0.3);  // each point seen by at most 2 keyframes
  const auto victim = scene.keyframes[1];
  std::vector<std::shared_ptr<lm::MapPoint>> seen;
  for (const auto& p : victim->mapPoints()) {
    if (p) seen.push_back(p);
  }
  ASSERT_FALSE(seen.empty());
  ASSERT_TRUE(scene.map.retireKeyFrame(victim));
  for (const auto& p : seen) {
    // Mono observations: one keyframe left (count 1 <= 2) -> retired and unlinked everywhere.
    EXPECT_TRUE(p->isBad());
    EXPECT_EQ(scene.map.mapPoint(p->id()), nullptr);
    for (const auto& [kf, index] : p->observations()) {
      EXPECT_NE(kf->mapPoint(static_cast<std::size_t>(index)), p);
    }
  }
}

TEST(MapGraph, ReplaceMovesObservationsToTheSurvivor) {
  LineScene scene(4, 40, 1.1);
  const auto survivor = scene.points[10];
  const auto duplicate = scene.points[11];
  const auto before = survivor->observationCount();
  scene.map.replaceMapPoint(duplicate, survivor);
  EXPECT_TRUE(duplicate->isBad());
  EXPECT_EQ(duplicate->replacement(), survivor);
  EXPECT_EQ(scene.map.mapPoint(duplicate->id()), nullptr);
  EXPECT_GE(survivor->observationCount(), before);
  for (const auto& kf : scene.map.keyFrames()) {
    for (const auto& p : kf->mapPoints()) EXPECT_NE(p, duplicate);
  }
}

TEST(MapPoint, NormalDistanceRangeAndScalePrediction) {
  LineScene scene(3, 30, 3.0);
  const auto point = scene.points[5];  // at (0.5, 0, 2), reference keyframe 0 at the origin
  point->updateNormalAndDepth();
  const Eigen::Vector3d normal = point->normal();
  EXPECT_NEAR(normal.norm(), 1.0, 1e-9);
  EXPECT_GT(normal.z(), 0.8);  // the keyframes look at it from below (+z direction)
  const auto& pyramid = scene.keyframes[0]->pyramid();
  const double distance = std::sqrt(0.5 * 0.5 + 4.0);
  const int octave =
      scene.keyframes[0]
          ->features()
          .keypoints[static_cast<std::size_t>(point->featureIndexIn(scene.keyframes[0]->id()))]
          .octave;
  const double max_distance = distance * pyramid.scale(octave);
  EXPECT_NEAR(point->maxDistance(), 1.2 * max_distance, 1e-9);
  EXPECT_NEAR(point->minDistance(), 0.8 * max_distance / pyramid.scale(pyramid.count() - 1), 1e-9);
  EXPECT_EQ(point->predictScale(max_distance, pyramid), 0);
  EXPECT_EQ(point->predictScale(1.01 * max_distance / (1.2 * 1.2), pyramid), 2);
  EXPECT_EQ(point->predictScale(max_distance / 100.0, pyramid), 7);
}

TEST(MapPoint, DistinctiveDescriptorIsTheMedianOne) {
  LineScene scene(5, 30, 3.0);
  const auto point = scene.points[0];  // seen by all five keyframes
  // Nested bit masks: distance between masks with a and b low bits set is 32 * |a - b|.
  // Bit counts {0, 2, 3, 4, 8}: the one with 3 bits (0x07) has the least median distance.
  const auto observations = point->observations();
  ASSERT_EQ(observations.size(), 5U);
  const std::uint8_t values[5] = {0x00, 0x03, 0x07, 0x0F, 0xFF};
  for (std::size_t i = 0; i < 5; ++i) {
    auto& kf = observations[i].first;
    auto& features = const_cast<lm::FeatureSet&>(kf->features());
    features.descriptors.row(observations[i].second).setTo(values[i]);
  }
  point->computeDistinctiveDescriptor();
  EXPECT_EQ(point->descriptor()[0], 0x07);
  EXPECT_EQ(lm::hammingDistance(point->descriptor(), lm::Descriptor{}), 96);
}

TEST(MapGraph, ConcurrentReadersAndWritersDoNotRace) {
  LineScene scene(8, 80, 1.6);
  std::atomic<bool> stop{false};
  std::thread reader([&] {
    while (!stop) {
      for (const auto& kf : scene.map.keyFrames()) {
        (void)kf->covisibles(5);
        (void)kf->center();
        for (const auto& p : kf->mapPoints()) {
          if (p) (void)p->position();
        }
      }
    }
  });
  for (int round = 0; round < 50; ++round) {
    for (const auto& kf : scene.keyframes) {
      SE3 pose = kf->T_c_w();
      pose.translation().y() += 1e-3;
      kf->setPose(pose);
      kf->updateConnections();
    }
    for (const auto& p : scene.points) {
      if (p) p->updateNormalAndDepth();
    }
  }
  scene.map.retireKeyFrame(scene.keyframes[4]);
  stop = true;
  reader.join();
  EXPECT_EQ(scene.map.keyFrameCount(), 7U);
}

}  // namespace
