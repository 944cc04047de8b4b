// Map merging (loop/map_merge.h): keyframes of a second map built in another world (rotated,
// shifted and, for the monocular case, scaled) join the first map's world and id, from the
// pose of one keyframe measured in the other map, whichever of the two keyframes is the
// current one. Rendered loop-rgbd frames with their true poses give the ground truth.
#include <gtest/gtest.h>

#include "loop_test_map.h"
#include "lumaslam/loop/map_merge.h"

namespace lumaslam {
namespace {

using optimize::Sim3;

struct TwoMaps {
  synth::SequenceRenderer room{synth::findPreset("loop-rgbd"), 40, 3};
  track::FrameBuilder builder{test::rgbdCameraOf(room.rig()), feature::OrbSettings{}};
  map::Map map;
  std::shared_ptr<map::KeyFrame> first;                // map 0, true world
  std::vector<std::shared_ptr<map::KeyFrame>> second;  // map 1, world X_1 = S_1_0 * X_0
  Sim3 S_1_0;
  std::vector<std::pair<std::shared_ptr<map::MapPoint>, Eigen::Vector3d>> truth;  // map 1 points

  explicit TwoMaps(double scale) {
    SE3 T = SE3::Identity();
    T.linear() = Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.3, 1.0, 0.2).normalized()).matrix();
    T.translation() = Eigen::Vector3d(1.5, -0.4, 3.0);
    S_1_0 = Sim3::fromSE3(T, scale);
    first = test::addKeyFrameWithPoints(map, builder, test::buildRgbdFrame(builder, room, 0),
                                        room.render(0).cam0.T_w_c);
    const map::MapId second_map = map.newMapId();
    for (const int index : {6, 12}) {
      const SE3 T_w0_c = room.render(index).cam0.T_w_c;
      auto kf = test::addKeyFrameWithPoints(
          map, builder, test::buildRgbdFrame(builder, room, index), T_w0_c, second_map);
      // Re-express the keyframe and its points in the second world (as its own map saw them).
      kf->setPose((Sim3::fromSE3(kf->T_c_w()) * S_1_0.inverse()).toSE3());
      for (const auto& point : kf->mapPoints()) {
        if (!point) continue;
        truth.emplace_back(point, point->position());
        point->setPosition(S_1_0 * point->position());
      }
      second.push_back(kf);
    }
  }

  void expectInTheFirstWorld() const {
    for (const auto& kf : second) {
      EXPECT_EQ(kf->mapId(), 0U);
      const SE3 expected = room.render(static_cast<int>(kf->frameIndex())).cam0.T_w_c;
      EXPECT_LT((kf->T_w_c().translation() - expected.translation()).norm(), 1e-6);
      EXPECT_LT((kf->T_w_c().linear() - expected.linear()).norm(), 1e-6);
    }
    for (const auto& [point, X_0] : truth) EXPECT_LT((point->position() - X_0).norm(), 1e-6);
    EXPECT_TRUE(map.keyFramesOf(1).empty());
    EXPECT_EQ(map.keyFramesOf(0).size(), 3U);
    // The second map's first keyframe is not a gauge any more, but is still never culled.
    EXPECT_FALSE(map.isMapOrigin(*second.front()));
    EXPECT_TRUE(map.isOrigin(*second.front()));
    EXPECT_TRUE(map.isMapOrigin(*first));
  }
};

// The current keyframe is in the newer map: the match gives its pose in the first map's world
// (with the scale of its own map: S_c_w0 = S_c_w1 * S_1_0).
TEST(MapMerge, TheNewerMapOfTheCurrentKeyFrameMovesIntoTheFirstWorld) {
  for (const double scale : {1.0, 2.5}) {
    TwoMaps maps(scale);
    loop::LoopMatch match;
    match.current = maps.second.back();
    match.loop = maps.first;
    match.S_c_w = Sim3::fromSE3(match.current->T_c_w()) * maps.S_1_0;
    const auto merge = loop::mergeFor(match);
    EXPECT_EQ(merge.moved, 1U);
    EXPECT_EQ(merge.into, 0U);
    loop::moveMapInto(maps.map, merge);
    maps.expectInTheFirstWorld();
  }
}

// The current keyframe is in the older map and recognises a keyframe of the newer one: the
// match gives its pose in the newer map's world; the newer map still moves.
TEST(MapMerge, TheNewerMapOfTheLoopKeyFrameMovesIntoTheFirstWorld) {
  for (const double scale : {1.0, 0.4}) {
    TwoMaps maps(scale);
    loop::LoopMatch match;
    match.current = maps.first;
    match.loop = maps.second.front();
    match.S_c_w = Sim3::fromSE3(maps.first->T_c_w()) * maps.S_1_0.inverse();
    const auto merge = loop::mergeFor(match);
    EXPECT_EQ(merge.moved, 1U);
    EXPECT_EQ(merge.into, 0U);
    loop::moveMapInto(maps.map, merge);
    maps.expectInTheFirstWorld();
  }
}

}  // namespace
}  // namespace lumaslam
