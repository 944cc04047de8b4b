// track::rigidConsensus on hand-built RGB-D frames: a wall of static map points and a crate
// that moved since it was mapped. The test is pose-free, so it must find the crate whatever the
// camera did, also when a pose estimate would have followed the crate.
#include <random>

#include <gtest/gtest.h>

#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/track/rigid_consensus.h"

namespace {

using namespace lumaslam;

const CameraIntrinsics kCamera{500.0, 500.0, 320.0, 240.0, 40.0};

struct Scene {
  std::vector<Eigen::Vector3d> points;  // world, where the map has them
  std::vector<bool> on_crate;
};

// `wall` static points 3 m away and `crate` points on a box 1.5 m away.
Scene scene(int wall, int crate) {
  Scene s;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-1.5, 1.5);
  std::uniform_real_distribution<double> y(-1.0, 1.0);
  for (int i = 0; i < wall + crate; ++i) {
    const bool on_crate = i >= wall;
    s.points.emplace_back(on_crate ? 0.2 * x(rng) : x(rng), on_crate ? 0.3 * y(rng) : y(rng),
                          on_crate ? 1.5 : 3.0);
    s.on_crate.push_back(on_crate);
  }
  return s;
}

// The frame seen from `T_c_w` after the crate moved by `crate_shift` (world), with Kinect-like
// depth noise (1.4e-3 z^2 m, Khoshelham & Elberink 2012) when `noisy`; every feature matched to
// its map point.
track::Frame observe(const Scene& s, const SE3& T_c_w, const Eigen::Vector3d& crate_shift,
                     bool noisy) {
  std::mt19937 rng(5);
  std::normal_distribution<double> unit(0.0, 1.0);
  const auto keyframe_features = std::make_shared<map::FeatureSet>();
  auto keyframe =
      std::make_shared<map::KeyFrame>(0, 0, 0.0, SE3::Identity(), keyframe_features,
                                      std::make_shared<feature::ScaleLevels>(8, 1.2F), kCamera);
  auto features = std::make_shared<map::FeatureSet>();
  std::vector<std::shared_ptr<map::MapPoint>> points;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const Eigen::Vector3d X = s.points[i] + (s.on_crate[i] ? crate_shift : Eigen::Vector3d::Zero());
    const Eigen::Vector3d X_c = T_c_w * X;
    const double z = X_c.z() + (noisy ? 1.4e-3 * X_c.z() * X_c.z() * unit(rng) : 0.0);
    const cv::Point2f p(static_cast<float>(kCamera.fx * X_c.x() / X_c.z() + kCamera.cx),
                        static_cast<float>(kCamera.fy * X_c.y() / X_c.z() + kCamera.cy));
    features->keypoints.emplace_back(p, 31.0F, 0.0F, 0.0F, 0);
    features->undistorted.push_back(p);
    features->depth.push_back(static_cast<float>(z));
    features->u_right.push_back(-1.0F);
    auto point = std::make_shared<map::MapPoint>(i, s.points[i], keyframe);
    point->addObservation(keyframe, static_cast<int>(i));
    points.push_back(point);
  }
  features->descriptors = cv::Mat::zeros(static_cast<int>(s.points.size()), 32, CV_8U);
  track::Frame frame;
  frame.T_c_w = T_c_w;
  frame.features = features;
  frame.clearMatches();
  for (std::size_t i = 0; i < points.size(); ++i) frame.points[i] = points[i];
  return frame;
}

struct Counts {
  int wall_holds = 0, wall_broken = 0, crate_holds = 0, crate_broken = 0;
};

Counts count(const track::RigidVerdict& verdict, const Scene& s) {
  Counts c;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    if (s.on_crate[i]) {
      c.crate_holds += verdict.holdsAt(i);
      c.crate_broken += verdict.brokenAt(i);
    } else {
      c.wall_holds += verdict.holdsAt(i);
      c.wall_broken += verdict.brokenAt(i);
    }
  }
  return c;
}

// The camera turned and moved; whatever the pose says, the crate's distances to the wall
// changed and the wall's among themselves did not. A sideways move changes the distance to a
// point straight behind only to second order (12 cm at 1.5 m: 0.5 cm), so under Kinect noise
// at 3 m the moves here have a part along the viewing ray.
SE3 turnedCamera() {
  return SE3(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY())) *
         SE3(Eigen::Translation3d(0.05, -0.02, 0.1));
}

TEST(RigidConsensus, FindsTheMovedCrateAndKeepsTheWallWhateverTheCameraDid) {
  const Scene s = scene(300, 60);
  const auto frame = observe(s, turnedCamera(), {0.12, 0.0, -0.12}, /*noisy=*/true);
  const auto verdict = track::rigidConsensus(frame, kCamera);
  const Counts c = count(verdict, s);
  EXPECT_TRUE(verdict.informative());
  EXPECT_EQ(c.crate_broken, 60);
  EXPECT_GE(c.wall_holds, 297);  // depth noise may break a far point's pairs
  EXPECT_EQ(verdict.holds + verdict.broken, 360);
}

TEST(RigidConsensus, BreaksNothingWhenNothingMoved) {
  const Scene s = scene(300, 60);
  const auto verdict =
      track::rigidConsensus(observe(s, turnedCamera(), Eigen::Vector3d::Zero(), true), kCamera);
  EXPECT_EQ(verdict.broken, 0);
  EXPECT_EQ(verdict.holds, 360);
  EXPECT_FALSE(verdict.informative());  // nothing to leave out of the pose
}

// A crate that moved toward the camera (its depth changed, not its pixels) is found too.
TEST(RigidConsensus, FindsAMoveAlongTheViewingRay) {
  const Scene s = scene(300, 60);
  const auto frame = observe(s, SE3::Identity(), {0.0, 0.0, -0.1}, /*noisy=*/false);
  const Counts c = count(track::rigidConsensus(frame, kCamera), s);
  EXPECT_EQ(c.crate_broken, 60);
  EXPECT_EQ(c.wall_broken, 0);
}

// Motion under the depth noise's tolerance (1 cm at least) is not evidence.
TEST(RigidConsensus, ToleratesShiftsWithinTheDepthNoise) {
  const Scene s = scene(300, 60);
  const Counts c = count(
      track::rigidConsensus(observe(s, SE3::Identity(), {0.004, 0.0, 0.0}, false), kCamera), s);
  EXPECT_EQ(c.crate_broken + c.wall_broken, 0);
}

TEST(RigidConsensus, GivesNoVerdictOnTooFewPoints) {
  const Scene s = scene(20, 5);
  const auto verdict =
      track::rigidConsensus(observe(s, SE3::Identity(), {0.2, 0.0, 0.0}, false), kCamera);
  EXPECT_TRUE(verdict.per_feature.empty());
  EXPECT_FALSE(verdict.brokenAt(0));
  EXPECT_FALSE(verdict.informative());
}

// Features without a depth reading, or unmatched, are not tested.
TEST(RigidConsensus, LeavesFeaturesWithoutDepthOrMatchUntested) {
  const Scene s = scene(300, 60);
  auto frame = observe(s, SE3::Identity(), {0.12, 0.0, 0.0}, false);
  auto features = std::make_shared<map::FeatureSet>(*frame.features);
  features->depth[0] = 0.0F;
  frame.features = features;
  frame.points[1] = nullptr;
  const auto verdict = track::rigidConsensus(frame, kCamera);
  EXPECT_EQ(verdict.per_feature[0], track::Rigidity::Untested);
  EXPECT_EQ(verdict.per_feature[1], track::Rigidity::Untested);
  EXPECT_EQ(verdict.holds + verdict.broken, 358);
}

}  // namespace
