// track::MotionEvidence on hand-built frames: a static scene seen by a moving RGB-D camera
// with one group of points that moves (a person), with and without map points.
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "lumaslam/track/motion_evidence.h"

namespace {

using namespace lumaslam;

constexpr double kBf = 40.0;  // Kinect-like virtual baseline x fx

track::FrameCamera camera() {
  return {camera::PinholeCamera(500, 500, 320, 240, camera::ImageSize{640, 480}), kBf, 3.0};
}

struct Scene {
  std::vector<Eigen::Vector3d> points;  // world, at frame 0
  std::vector<bool> moves;
  cv::Mat descriptors;  // one per point, the same in every frame
};

// 300 static points on a wall 3 m away and 60 on a "person" 1.5 m away.
Scene scene() {
  Scene s;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(-1.5, 1.5);
  std::uniform_real_distribution<double> y(-1.0, 1.0);
  for (int i = 0; i < 360; ++i) {
    const bool person = i >= 300;
    s.points.emplace_back(person ? x(rng) * 0.15 : x(rng), person ? y(rng) * 0.4 : y(rng),
                          person ? 1.5 : 3.0);
    s.moves.push_back(person);
  }
  s.descriptors = cv::Mat(360, 32, CV_8U);
  cv::randu(s.descriptors, 0, 256);
  return s;
}

// Frame `index`: the camera has moved 1 cm along x per frame, the person 4 cm per frame.
track::Frame render(const Scene& s, std::size_t index, const track::FrameCamera& c) {
  const double t = static_cast<double>(index);
  track::Frame frame;
  frame.index = index;
  frame.timestamp = t / 30.0;
  frame.T_c_w = SE3(Eigen::Translation3d(-0.01 * t, 0, 0));
  auto features = std::make_shared<map::FeatureSet>();
  features->descriptors = s.descriptors.clone();
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    Eigen::Vector3d X = s.points[i];
    if (s.moves[i]) X.x() += 0.04 * t;
    const Eigen::Vector3d X_c = *frame.T_c_w * X;
    const Eigen::Vector2d uv = c.pinhole.project(X_c);
    const cv::Point2f p(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
    features->keypoints.emplace_back(p, 31.0F, 0.0F, 0.0F, 0);
    features->undistorted.push_back(p);
    features->depth.push_back(static_cast<float>(X_c.z()));
    features->u_right.push_back(static_cast<float>(uv.x() - kBf / X_c.z()));
  }
  features->grid =
      std::make_shared<const feature::FeatureGrid>(features->keypoints, cv::Rect2f(0, 0, 640, 480));
  frame.features = features;
  frame.clearMatches();
  return frame;
}

const feature::ScaleLevels& pyramid() {
  static const feature::ScaleLevels levels(8, 1.2F);
  return levels;
}

std::size_t movingFlagged(const track::Frame& frame, const Scene& s, bool moves) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.features->moving[i] && s.moves[i] == moves) ++n;
  }
  return n;
}

// A keyframe at `first` and a map point per scene point, at its frame-0 position.
std::vector<std::shared_ptr<map::MapPoint>> mapPoints(const Scene& s, const track::Frame& first,
                                                      const track::FrameCamera& c) {
  auto keyframe = std::make_shared<map::KeyFrame>(0, 0, 0.0, *first.T_c_w, first.features,
                                                  std::make_shared<feature::ScaleLevels>(8, 1.2F),
                                                  c.intrinsics());
  std::vector<std::shared_ptr<map::MapPoint>> points;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    auto point = std::make_shared<map::MapPoint>(i, s.points[i], keyframe);
    point->addObservation(keyframe, static_cast<int>(i));
    points.push_back(point);
  }
  return points;
}

TEST(MotionEvidence, StaticEvidenceIsPositiveInsideTheThresholdAndNegativeFarOutside) {
  EXPECT_DOUBLE_EQ(track::staticEvidence(0.0, 5.991), 0.5);
  EXPECT_DOUBLE_EQ(track::staticEvidence(5.991, 5.991), 0.0);
  EXPECT_LT(track::staticEvidence(3 * 5.991, 5.991), -0.9);
  EXPECT_DOUBLE_EQ(track::staticEvidence(1e6, 5.991), -1.5);
}

TEST(MotionEvidence, FeaturesOnAMovingPersonTurnMovingAndTheWallStaysStatic) {
  const auto s = scene();
  const auto c = camera();
  track::MotionEvidence evidence;
  track::Frame previous = render(s, 0, c);
  for (std::size_t index = 1; index <= 3; ++index) {
    track::Frame current = render(s, index, c);
    const auto verdict = evidence.update(current, previous, c, pyramid());
    EXPECT_TRUE(verdict.evidence_used);
    previous = std::move(current);
  }
  EXPECT_EQ(movingFlagged(previous, s, false), 0U);
  EXPECT_GE(movingFlagged(previous, s, true), 55U);  // of 60 (a few lose their flow match)
}

TEST(MotionEvidence, MapPointsOnThePersonTurnDynamicAndWallPointsDoNot) {
  const auto s = scene();
  const auto c = camera();
  const track::Frame first = render(s, 0, c);
  const auto points = mapPoints(s, first, c);
  track::MotionEvidence evidence;
  track::Frame previous = first;
  std::set<std::size_t> dynamic_person;
  std::set<std::size_t> dynamic_wall;
  for (std::size_t index = 1; index <= 4; ++index) {
    track::Frame current = render(s, index, c);
    current.points = points;  // every feature matched to its map point
    // Pose optimisation rejected the person's points (their residual is tens of pixels).
    for (std::size_t i = 0; i < s.points.size(); ++i) current.outliers[i] = s.moves[i];
    const auto verdict = evidence.update(current, previous, c, pyramid());
    for (const auto i : verdict.dynamic_points)
      (s.moves[i] ? dynamic_person : dynamic_wall).insert(i);
    previous = std::move(current);
  }
  EXPECT_EQ(dynamic_wall.size(), 0U);
  EXPECT_EQ(dynamic_person.size(), 60U);
  EXPECT_EQ(evidence.dynamicCount(4), 60U);
  EXPECT_TRUE(evidence.isDynamic(points[300]->id(), 4));
  EXPECT_FALSE(evidence.isDynamic(points[0]->id(), 4));
}

// Evidence is forgotten: a person who stops moving (their map points fit again) is static
// again after a while, and their points rejoin the pose.
TEST(MotionEvidence, APointThatStopsMovingBecomesStaticAgain) {
  const auto s = scene();
  const auto c = camera();
  const track::Frame first = render(s, 0, c);
  const std::size_t person = 300;
  const auto point = mapPoints(s, first, c)[person];
  track::MotionEvidence evidence;
  track::Frame previous = first;
  for (std::size_t index = 1; index <= 40; ++index) {
    track::Frame current = render(s, std::min<std::size_t>(index, 4), c);  // stops at frame 4
    current.index = index;
    current.points[person] = point;
    if (index == 4) {
      EXPECT_TRUE(evidence.isDynamic(point->id(), index)) << "while it moved";
      point->setPosition(s.points[person] + Eigen::Vector3d(0.16, 0, 0));  // where it stopped
    }
    evidence.update(current, previous, c, pyramid());
    previous = std::move(current);
  }
  EXPECT_FALSE(evidence.isDynamic(point->id(), 40));
  EXPECT_TRUE(evidence.isConfirmedStatic(point->id(), 40));
}

TEST(MotionEvidence, ADoubtfulPoseGivesNoMovingEvidence) {
  const auto s = scene();
  const auto c = camera();
  track::MotionEvidence evidence;
  track::Frame previous = render(s, 0, c);
  track::Frame current = render(s, 1, c);
  // The pose is 10 cm off: everything looks as if it moved.
  current.T_c_w = SE3(Eigen::Translation3d(0.1, 0, 0)) * *current.T_c_w;
  current.points = mapPoints(s, previous, c);
  current.outliers.assign(current.size(), true);  // pose optimisation kept none of them
  const auto verdict = evidence.update(current, previous, c, pyramid());
  EXPECT_FALSE(verdict.evidence_used);
  EXPECT_TRUE(verdict.dynamic_points.empty());
  EXPECT_EQ(verdict.moving_features, 0U);
}

TEST(MotionEvidence, DisabledDoesNothing) {
  const auto s = scene();
  const auto c = camera();
  track::MotionEvidenceParams params;
  params.enabled = false;
  track::MotionEvidence evidence(params);
  const track::Frame previous = render(s, 0, c);
  track::Frame current = render(s, 1, c);
  const auto verdict = evidence.update(current, previous, c, pyramid());
  EXPECT_FALSE(verdict.evidence_used);
  EXPECT_TRUE(current.features->moving.empty());
}

}  // namespace
