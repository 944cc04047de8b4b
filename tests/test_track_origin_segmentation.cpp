// track::segmentAgainstOrigin on hand-built RGB-D frames: an origin keyframe at the identity
// that measured a far wall, near static boxes and a crate, and a current frame whose camera
// moved, matched to the origin's map points. The static motion is the one whose own points are
// spread over the image, also when a crate-following motion fits more points.
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/track/origin_segmentation.h"

namespace {

using namespace lumaslam;

const CameraIntrinsics kCamera{525.0, 525.0, 319.5, 239.5, 40.0};
constexpr int kWidth = 640;
constexpr int kHeight = 480;
constexpr double kDegree = M_PI / 180.0;

enum class Part { Wall, Box, Crate };

struct Scene {
  std::vector<Eigen::Vector3d> points;  // world = the origin camera
  std::vector<Part> parts;
};

void add(Scene& s, const Eigen::Vector3d& p, Part part) {
  s.points.push_back(p);
  s.parts.push_back(part);
}

// `wall` points on a plane 3.5 m away; `boxes` static points 1.5-2 m away in four clusters at
// the image's sides; `crate` points in a 0.3 x 0.3 m patch 1.8 m away, near the centre.
// With `textured_wall` the wall's points are instead one per 32 px of the origin image (inside a
// margin of 48 px), so that the wall alone covers nearly every cell of the
// coverage grid.
Scene scene(int wall, int boxes, int crate, bool textured_wall = false) {
  Scene s;
  if (textured_wall) {
    for (int v = 48; v <= kHeight - 48; v += 32) {
      for (int u = 48; u <= kWidth - 48; u += 32)
        add(s, {(u - kCamera.cx) * 3.5 / kCamera.fx, (v - kCamera.cy) * 3.5 / kCamera.fy, 3.5},
            Part::Wall);
    }
    wall = 0;
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < wall; ++i) add(s, {1.8 * unit(rng), 1.3 * unit(rng), 3.5}, Part::Wall);
  // Box centres (x, y, z): left and right of the image, above and below its centre line.
  const Eigen::Vector3d centres[] = {
      {-0.65, -0.45, 1.5}, {-0.8, 0.4, 1.9}, {0.75, -0.4, 1.7}, {0.85, 0.5, 2.0}};
  for (int i = 0; i < boxes; ++i) {
    const Eigen::Vector3d& c = centres[i % 4];
    add(s, c + Eigen::Vector3d(0.12 * unit(rng), 0.12 * unit(rng), 0.05 * unit(rng)), Part::Box);
  }
  for (int i = 0; i < crate; ++i)
    add(s, {0.1 + 0.15 * unit(rng), 0.15 * unit(rng), 1.8}, Part::Crate);
  return s;
}

// RGB-D features of `points` seen from `T_c_w`, with Kinect-like depth noise (1.4e-3 z^2 m,
// Khoshelham & Elberink 2012) and a third of a pixel of keypoint noise; feature `order[i]`
// sees point i.
std::shared_ptr<map::FeatureSet> observe(const std::vector<Eigen::Vector3d>& points,
                                         const SE3& T_c_w, const std::vector<std::size_t>& order,
                                         std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  auto features = std::make_shared<map::FeatureSet>();
  const std::size_t n = points.size();
  features->keypoints.resize(n);
  features->undistorted.resize(n);
  features->depth.resize(n);
  features->u_right.assign(n, -1.0F);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d X_c = T_c_w * points[i];
    const double z = X_c.z() + 1.4e-3 * X_c.z() * X_c.z() * gauss(rng);
    const cv::Point2f p(
        static_cast<float>(kCamera.fx * X_c.x() / X_c.z() + kCamera.cx + gauss(rng) / 3.0),
        static_cast<float>(kCamera.fy * X_c.y() / X_c.z() + kCamera.cy + gauss(rng) / 3.0));
    const std::size_t j = order[i];
    features->keypoints[j] = cv::KeyPoint(p, 31.0F, 0.0F, 0.0F, 0);
    features->undistorted[j] = p;
    features->depth[j] = static_cast<float>(z);
  }
  features->descriptors = cv::Mat::zeros(static_cast<int>(n), 32, CV_8U);
  return features;
}

// The origin keyframe, its map points and the current frame matched to them.
struct Views {
  std::shared_ptr<map::KeyFrame> origin;  // the map points hold it weakly
  std::vector<std::shared_ptr<map::MapPoint>> points;
  track::Frame current;
};

// The origin measured `s` from the identity; then the crate moved by `crate_shift` (world)
// and the camera moved to `T_current_origin`. The origin stores point i at feature n - 1 - i,
// the current frame at feature i: the pairs must be made through the observation index. The
// origin has no depth for the first `origin_without_depth` points.
Views build(const Scene& s, const SE3& T_current_origin, const Eigen::Vector3d& crate_shift,
            std::size_t origin_without_depth = 0) {
  const std::size_t n = s.points.size();
  std::mt19937 rng(5);
  std::vector<std::size_t> reversed(n);
  std::vector<std::size_t> same(n);
  for (std::size_t i = 0; i < n; ++i) {
    reversed[i] = n - 1 - i;
    same[i] = i;
  }
  auto seen = observe(s.points, SE3::Identity(), reversed, rng);
  for (std::size_t i = 0; i < origin_without_depth; ++i) seen->depth[reversed[i]] = -1.0F;
  Views views;
  views.origin = std::make_shared<map::KeyFrame>(
      0, 0, 0.0, SE3::Identity(), seen, std::make_shared<feature::ScaleLevels>(8, 1.2F), kCamera);
  for (std::size_t i = 0; i < n; ++i) {
    auto point = std::make_shared<map::MapPoint>(i, s.points[i], views.origin);
    point->addObservation(views.origin, static_cast<int>(reversed[i]));
    views.points.push_back(point);
  }
  std::vector<Eigen::Vector3d> now = s.points;
  for (std::size_t i = 0; i < n; ++i) {
    if (s.parts[i] == Part::Crate) now[i] += crate_shift;
  }
  views.current.index = 3;
  views.current.features = observe(now, T_current_origin, same, rng);
  views.current.clearMatches();
  for (std::size_t i = 0; i < n; ++i) views.current.points[i] = views.points[i];
  return views;
}

// The camera moved 3 cm sideways and turned 1 degree to the left.
SE3 movedCamera() {
  const SE3 T_w_c = Eigen::Translation3d(0.03, 0.0, 0.0) *
                    Eigen::AngleAxisd(1.0 * kDegree, Eigen::Vector3d::UnitY());
  return T_w_c.inverse();
}

struct Counts {
  int holds[3] = {0, 0, 0};   // by Part
  int broken[3] = {0, 0, 0};  // by Part
  int of[3] = {0, 0, 0};      // features of each part
};

Counts count(const track::RigidVerdict& verdict, const Scene& s) {
  Counts c;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const auto part = static_cast<int>(s.parts[i]);
    c.holds[part] += verdict.holdsAt(i);
    c.broken[part] += verdict.brokenAt(i);
    ++c.of[part];
  }
  return c;
}

constexpr int kWall = static_cast<int>(Part::Wall);
constexpr int kBox = static_cast<int>(Part::Box);
constexpr int kCrate = static_cast<int>(Part::Crate);

void expectNear(const SE3& estimate, const SE3& truth) {
  const SE3 error = estimate * truth.inverse();
  EXPECT_LT(error.translation().norm(), 0.01);
  EXPECT_LT(Eigen::AngleAxisd(error.rotation()).angle(), 0.3 * kDegree);
}

// Whether the origin's and the current measurement of point i agree under `motion` (origin
// camera -> current camera) within the tolerance the module documents (origin_segmentation.h).
bool fitsWithinTolerance(const Views& views, std::size_t i, const SE3& motion,
                         const track::OriginSegmentationParams& params) {
  const auto& seen = views.origin->features();
  const std::size_t j = seen.size() - 1 - i;
  const double z0 = seen.depth[j];
  const Eigen::Vector3d in_origin((seen.undistorted[j].x - kCamera.cx) * z0 / kCamera.fx,
                                  (seen.undistorted[j].y - kCamera.cy) * z0 / kCamera.fy, z0);
  const Eigen::Vector3d in_current = views.current.unprojectCamera(i, kCamera);
  const double s0 = params.depth_noise * in_origin.z() * in_origin.z();
  const double s1 = params.depth_noise * in_current.z() * in_current.z();
  const double along_tolerance =
      std::max(params.min_tolerance_m, params.tolerance_sigmas * std::hypot(s0, s1));
  const double across_tolerance = params.lateral_tolerance_px * in_current.z() / kCamera.fx;
  const Eigen::Vector3d error = motion * in_origin - in_current;
  const Eigen::Vector3d ray = in_current.normalized();
  const double along = error.dot(ray);
  return std::abs(along) < along_tolerance && (error - along * ray).norm() < across_tolerance;
}

// The map-start ambiguity's premise: the crate-following motion (the true one after a turn
// about a vertical axis through the wall's centre, by the angle that carries the crate's plane,
// 1.8 m, by the crate's `shift`) fits the crate and the whole wall, the true motion the wall and
// the boxes but not the crate; there are more crate points than box points, so that the
// follower fits more pairs and a max-inlier choice would take it.
void expectAFollowerFitsMore(const Scene& s, const Views& views, const SE3& truth, double shift,
                             const track::OriginSegmentationParams& params) {
  const Eigen::Vector3d axis_point(0.0, 0.0, 3.5);
  const SE3 turn = Eigen::Translation3d(axis_point) *
                   Eigen::AngleAxisd(-std::asin(shift / 1.7), Eigen::Vector3d::UnitY()) *
                   Eigen::Translation3d(-axis_point);
  const SE3 follower = truth * turn;
  Counts fit_truth;
  Counts fit_follower;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const auto part = static_cast<int>(s.parts[i]);
    fit_truth.holds[part] += fitsWithinTolerance(views, i, truth, params);
    fit_follower.holds[part] += fitsWithinTolerance(views, i, follower, params);
    ++fit_truth.of[part];
  }
  const int wall = fit_truth.of[kWall];
  const int boxes = fit_truth.of[kBox];
  const int crate = fit_truth.of[kCrate];
  EXPECT_GT(crate, boxes);
  EXPECT_EQ(fit_follower.holds[kCrate], crate);
  EXPECT_GE(fit_follower.holds[kWall], wall * 19 / 20);
  EXPECT_LE(fit_follower.holds[kBox], boxes / 8);
  EXPECT_EQ(fit_truth.holds[kCrate], 0);
  EXPECT_GE(fit_truth.holds[kWall] + fit_truth.holds[kBox], wall + boxes - 2);
  const auto total = [](const Counts& c) {
    return c.holds[kWall] + c.holds[kBox] + c.holds[kCrate];
  };
  EXPECT_GT(total(fit_follower), total(fit_truth));
}

TEST(OriginSegmentation, FindsTheCameraMotionAndBreaksTheMovedCrate) {
  const Scene s = scene(300, 80, 60);
  const SE3 truth = movedCamera();
  const Views views = build(s, truth, {0.06, 0.0, 0.0});
  const auto result =
      track::segmentAgainstOrigin(views.current, *views.origin, kCamera, kWidth, kHeight);
  EXPECT_EQ(result.pairs, 440);
  ASSERT_TRUE(result.T_current_origin.has_value());
  expectNear(*result.T_current_origin, truth);
  const Counts c = count(result.verdict, s);
  EXPECT_GE(c.broken[kCrate], 54);  // 90 %
  EXPECT_GE(c.holds[kWall] + c.holds[kBox], 342);
  EXPECT_GE(c.holds[kBox], 72);
  EXPECT_LE(c.broken[kWall] + c.broken[kBox], 3);
  EXPECT_EQ(c.holds[kCrate], 0);
  // The static matches are the points that hold, and only those.
  ASSERT_EQ(result.static_matches.size(), views.current.size());
  for (std::size_t i = 0; i < views.current.size(); ++i) {
    if (result.verdict.holdsAt(i))
      EXPECT_EQ(result.static_matches[i], views.points[i]) << i;
    else
      EXPECT_EQ(result.static_matches[i], nullptr) << i;
  }
}

// The map-start ambiguity: a camera that slid with the crate and turned back so that the far
// wall stays in place explains the crate and the wall, more points than the true motion (the
// wall and the few near boxes) explains. Only the boxes tell the two apart: they are spread
// over the image, the crate is one compact patch.
TEST(OriginSegmentation, PrefersTheSpreadStaticSceneOverACrateFollowingMotionWithMorePoints) {
  const Scene s = scene(300, 40, 60);
  const SE3 truth = movedCamera();
  const double shift = 0.03;
  const Views views = build(s, truth, {shift, 0.0, 0.0});
  const track::OriginSegmentationParams params;
  expectAFollowerFitsMore(s, views, truth, shift, params);

  const auto result =
      track::segmentAgainstOrigin(views.current, *views.origin, kCamera, kWidth, kHeight, params);
  EXPECT_EQ(result.pairs, 400);
  ASSERT_TRUE(result.T_current_origin.has_value());
  expectNear(*result.T_current_origin, truth);
  const Counts c = count(result.verdict, s);
  EXPECT_GE(c.broken[kCrate], 54);  // 90 %
  EXPECT_EQ(c.holds[kCrate], 0);
  EXPECT_GE(c.holds[kBox], 36);
  EXPECT_GE(c.holds[kWall], 270);
  EXPECT_LE(c.broken[kWall] + c.broken[kBox], 3);
}

// As above, on a wall textured all over the image: both motions' points then cover every cell,
// and only the points each motion alone explains (the boxes, the crate) tell them apart.
TEST(OriginSegmentation, TellsTheMotionsApartByThePointsOnlyEachExplains) {
  const Scene s = scene(0, 40, 60, /*textured_wall=*/true);
  const SE3 truth = movedCamera();
  const double shift = 0.03;
  const Views views = build(s, truth, {shift, 0.0, 0.0});
  const track::OriginSegmentationParams params;
  expectAFollowerFitsMore(s, views, truth, shift, params);
  const auto result =
      track::segmentAgainstOrigin(views.current, *views.origin, kCamera, kWidth, kHeight, params);
  EXPECT_EQ(result.pairs, static_cast<int>(s.points.size()));
  ASSERT_TRUE(result.T_current_origin.has_value());
  expectNear(*result.T_current_origin, truth);
  const Counts c = count(result.verdict, s);
  EXPECT_GE(c.broken[kCrate], 54);  // 90 %
  EXPECT_GE(c.holds[kBox], 36);
  EXPECT_GE(c.holds[kWall], c.of[kWall] * 9 / 10);
  EXPECT_LE(c.broken[kWall] + c.broken[kBox], 3);
}

TEST(OriginSegmentation, BreaksNothingWhenNothingMoved) {
  const Scene s = scene(300, 80, 60);
  const SE3 truth = movedCamera();
  const Views views = build(s, truth, Eigen::Vector3d::Zero());
  const auto result =
      track::segmentAgainstOrigin(views.current, *views.origin, kCamera, kWidth, kHeight);
  EXPECT_EQ(result.pairs, 440);
  ASSERT_TRUE(result.T_current_origin.has_value());
  expectNear(*result.T_current_origin, truth);
  EXPECT_EQ(result.verdict.broken, 0);
  EXPECT_GE(result.verdict.holds, 418);  // 95 %
  EXPECT_FALSE(result.verdict.informative());
}

// Too few pairs: no motion and no verdict, but the pairs are counted; features without depth
// (in either frame) or without a match make no pair. The 13 wall and 13 crate pairs left would
// each be enough for a motion.
TEST(OriginSegmentation, GivesNoMotionOnTooFewPairs) {
  const Scene s = scene(18, 0, 13);
  const Views built = build(s, movedCamera(), {0.25, 0.0, -0.3}, /*origin_without_depth=*/2);
  track::Frame current = built.current;
  auto features = std::make_shared<map::FeatureSet>(*current.features);
  features->depth[2] = -1.0F;
  features->depth[3] = 0.0F;
  current.features = features;
  current.points[4] = nullptr;
  const auto result = track::segmentAgainstOrigin(current, *built.origin, kCamera, kWidth, kHeight);
  EXPECT_EQ(result.pairs, 26);
  EXPECT_FALSE(result.T_current_origin.has_value());
  EXPECT_TRUE(result.verdict.per_feature.empty());
  EXPECT_EQ(result.verdict.holds + result.verdict.broken, 0);
  EXPECT_TRUE(result.static_matches.empty());
}

// The same scene, unmoved and with all its pairs, gives a motion once the minimum allows it.
TEST(OriginSegmentation, GivesAMotionOnceThereAreEnoughPairs) {
  const Scene s = scene(18, 0, 13);
  const Views views = build(s, movedCamera(), Eigen::Vector3d::Zero());
  track::OriginSegmentationParams params;
  params.min_points = 20;
  const auto result =
      track::segmentAgainstOrigin(views.current, *views.origin, kCamera, kWidth, kHeight, params);
  EXPECT_EQ(result.pairs, 31);
  EXPECT_TRUE(result.T_current_origin.has_value());
  EXPECT_EQ(result.verdict.holds, 31);
  EXPECT_EQ(result.verdict.broken, 0);
}

}  // namespace
