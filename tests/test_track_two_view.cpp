// Two-view initialisation on synthetic correspondences with known geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "lumaslam/track/two_view_initializer.h"

namespace {

using namespace lumaslam;
using track::TwoViewModel;

const cv::Matx33d kK(500, 0, 320, 0, 500, 240, 0, 0, 1);

struct Scene {
  SE3 T_c2_c1 = SE3::Identity();
  std::vector<Eigen::Vector3d> X_c1;  // ground truth, camera 1
  std::vector<cv::Point2f> p1, p2;
  std::vector<bool> outlier;
};

std::optional<cv::Point2f> project(const Eigen::Vector3d& X) {
  if (X.z() <= 0.1) return std::nullopt;
  const cv::Point2f p(static_cast<float>(kK(0, 0) * X.x() / X.z() + kK(0, 2)),
                      static_cast<float>(kK(1, 1) * X.y() / X.z() + kK(1, 2)));
  if (p.x < 0 || p.y < 0 || p.x >= 640 || p.y >= 480) return std::nullopt;
  return p;
}

SE3 motion(const Eigen::Vector3d& axis, double degrees, const Eigen::Vector3d& t) {
  SE3 T = SE3::Identity();
  T.linear() = Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

// `planar`: points on a tilted plane, otherwise spread through a deep volume. A tenth of the
// matches are random outliers; inliers get 0.5 px noise.
Scene makeScene(const SE3& T_c2_c1, bool planar, int count, std::uint32_t seed) {
  constexpr double kTiltX = 0.4;  // plane Z = 5 + kTiltX X + kTiltY Y
  constexpr double kTiltY = -0.3;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.5);
  Scene scene;
  scene.T_c2_c1 = T_c2_c1;
  int attempts = 0;
  while (static_cast<int>(scene.p1.size()) < count && ++attempts < 100000) {
    const double x = 2.5 * unit(rng);
    const double y = 1.8 * unit(rng);
    // Along the ray (x, y, 5): on the plane, or at a random depth.
    const double z = planar ? 5.0 / (1.0 - (kTiltX * x + kTiltY * y) / 5.0) : 5.0 + 2.5 * unit(rng);
    if (z <= 0.5 || z > 20.0) continue;
    const Eigen::Vector3d X(x * z / 5.0, y * z / 5.0, z);
    const auto a = project(X);
    const auto b = project(T_c2_c1 * X);
    if (!a || !b) continue;
    const bool outlier = scene.p1.size() % 10 == 9;
    scene.X_c1.push_back(X);
    scene.outlier.push_back(outlier);
    if (outlier) {
      scene.p1.emplace_back(*a);
      scene.p2.emplace_back(static_cast<float>(320 + 300 * unit(rng)),
                            static_cast<float>(240 + 220 * unit(rng)));
    } else {
      scene.p1.emplace_back(a->x + static_cast<float>(noise(rng)),
                            a->y + static_cast<float>(noise(rng)));
      scene.p2.emplace_back(b->x + static_cast<float>(noise(rng)),
                            b->y + static_cast<float>(noise(rng)));
    }
  }
  return scene;
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

double rotationErrorDeg(const SE3& a, const SE3& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

void expectRecovers(const Scene& scene, const track::TwoViewReconstruction& result) {
  ASSERT_TRUE(result.success) << result.failure << " (" << track::toString(result.model) << ", R_H "
                              << result.score_ratio << ", inliers " << result.inliers
                              << ", parallax " << result.parallax_deg << ")";
  EXPECT_LT(rotationErrorDeg(result.T_c2_c1, scene.T_c2_c1), 0.5);
  EXPECT_LT(angleDeg(result.T_c2_c1.translation(), scene.T_c2_c1.translation()), 3.0);
  // Points agree with the truth once the unknown scale is fixed by the translation.
  const double scale = scene.T_c2_c1.translation().norm() / result.T_c2_c1.translation().norm();
  int inliers = 0;
  int outliers_kept = 0;
  std::vector<double> relative_errors;
  for (std::size_t i = 0; i < scene.X_c1.size(); ++i) {
    if (!result.points[i]) continue;
    if (scene.outlier[i]) {
      ++outliers_kept;
      continue;
    }
    ++inliers;
    relative_errors.push_back((scale * *result.points[i] - scene.X_c1[i]).norm() /
                              scene.X_c1[i].norm());
  }
  EXPECT_LE(outliers_kept, 2);  // a random match may fall on its epipolar line
  EXPECT_GT(inliers, static_cast<int>(0.7 * scene.X_c1.size()));
  ASSERT_FALSE(relative_errors.empty());
  std::nth_element(relative_errors.begin(), relative_errors.begin() + relative_errors.size() / 2,
                   relative_errors.end());
  // 0.5 px noise at 3-5 degrees of parallax: a few percent of depth per point.
  EXPECT_LT(relative_errors[relative_errors.size() / 2], 0.05);
  EXPECT_EQ(result.triangulated, inliers + outliers_kept);
}

// The model ORB-SLAM's rule picks: H when R_H = S_H / (S_H + S_F) > 0.45.
void expectModel(const track::TwoViewReconstruction& result, TwoViewModel model) {
  EXPECT_EQ(result.model, model);
  EXPECT_EQ(result.score_ratio > 0.45, model == TwoViewModel::Homography) << result.score_ratio;
}

TEST(TwoViewInitializer, GeneralSceneChoosesFundamentalAndRecoversMotion) {
  const auto scene = makeScene(motion({0.2, 1.0, 0.1}, 4.0, {0.4, 0.05, 0.1}), false, 400, 1);
  const auto result = track::TwoViewInitializer(kK).reconstruct(scene.p1, scene.p2);
  expectModel(result, TwoViewModel::Fundamental);
  expectRecovers(scene, result);
}

TEST(TwoViewInitializer, PlanarSceneChoosesHomographyAndRecoversMotion) {
  const auto scene = makeScene(motion({0.1, 1.0, -0.2}, 3.0, {0.5, -0.1, 0.05}), true, 400, 2);
  const auto result = track::TwoViewInitializer(kK).reconstruct(scene.p1, scene.p2);
  expectModel(result, TwoViewModel::Homography);
  expectRecovers(scene, result);
}

TEST(TwoViewInitializer, ForwardMotionIsRecovered) {
  const auto scene = makeScene(motion({1.0, 0.0, 0.0}, 2.0, {0.05, 0.0, 0.6}), false, 400, 3);
  const auto result = track::TwoViewInitializer(kK).reconstruct(scene.p1, scene.p2);
  expectRecovers(scene, result);
}

TEST(TwoViewInitializer, PureRotationFailsCleanly) {
  const auto scene =
      makeScene(motion({0.3, 1.0, 0.0}, 5.0, Eigen::Vector3d::Zero()), false, 400, 4);
  const auto result = track::TwoViewInitializer(kK).reconstruct(scene.p1, scene.p2);
  EXPECT_FALSE(result.success);
  EXPECT_FALSE(result.failure.empty());
  EXPECT_EQ(result.points.size(), scene.p1.size());
}

TEST(TwoViewInitializer, TinyBaselineFailsOnParallax) {
  // 1 cm sideways at 5 m: about 0.1 degrees of parallax.
  const auto scene = makeScene(motion({0.0, 1.0, 0.0}, 1.0, {0.01, 0.0, 0.0}), false, 400, 5);
  const auto result = track::TwoViewInitializer(kK).reconstruct(scene.p1, scene.p2);
  EXPECT_FALSE(result.success);
}

TEST(TwoViewInitializer, TooFewOrInconsistentMatchesFailCleanly) {
  const auto scene = makeScene(motion({0.2, 1.0, 0.1}, 4.0, {0.4, 0.05, 0.1}), false, 30, 6);
  const track::TwoViewInitializer initializer(kK);
  EXPECT_FALSE(initializer.reconstruct(scene.p1, scene.p2).success);
  EXPECT_FALSE(initializer.reconstruct({}, {}).success);
  std::vector<cv::Point2f> shorter(scene.p2.begin(), scene.p2.end() - 1);
  EXPECT_FALSE(initializer.reconstruct(scene.p1, shorter).success);
  // Random matches: no geometry at all.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0F, 640.0F);
  std::uniform_real_distribution<float> v(0.0F, 480.0F);
  std::vector<cv::Point2f> a(300);
  std::vector<cv::Point2f> b(300);
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = {u(rng), v(rng)};
    b[i] = {u(rng), v(rng)};
  }
  EXPECT_FALSE(initializer.reconstruct(a, b).success);
  // Degenerate sets (all at one pixel, all on one line) fail without throwing.
  const std::vector<cv::Point2f> same(100, cv::Point2f(100.0F, 100.0F));
  EXPECT_FALSE(initializer.reconstruct(same, same).success);
  std::vector<cv::Point2f> line1;
  std::vector<cv::Point2f> line2;
  for (int i = 0; i < 100; ++i) {
    line1.emplace_back(static_cast<float>(5 * i), 200.0F);
    line2.emplace_back(static_cast<float>(5 * i + 3), 210.0F);
  }
  EXPECT_FALSE(initializer.reconstruct(line1, line2).success);
}

TEST(TwoViewScores, ExactModelsScoreEveryMatchAsInlier) {
  const auto T = motion({0.2, 1.0, 0.1}, 4.0, {0.4, 0.05, 0.1});
  auto scene = makeScene(T, false, 100, 8);
  // Noise-free, outlier-free copy.
  for (std::size_t i = 0; i < scene.X_c1.size(); ++i) {
    scene.p1[i] = *project(scene.X_c1[i]);
    scene.p2[i] = *project(T * scene.X_c1[i]);
  }
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Vector3d t = T.translation();
  Eigen::Matrix3d t_hat;
  t_hat << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  const Eigen::Matrix3d F = K.inverse().transpose() * t_hat * R * K.inverse();
  cv::Matx33d F_cv;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) F_cv(r, c) = F(r, c);
  }
  const auto f = track::scoreFundamental(F_cv, scene.p1, scene.p2, 1.0);
  EXPECT_EQ(f.inlierCount(), static_cast<int>(scene.p1.size()));
  EXPECT_NEAR(f.score, 2 * 5.991 * static_cast<double>(scene.p1.size()), 0.5);
  // The homography of the infinite plane (K R K^-1) does not explain a translating camera.
  const cv::Matx33d H_inf =
      kK *
      cv::Matx33d(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)) *
      kK.inv();
  const auto h = track::scoreHomography(H_inf, scene.p1, scene.p2, 1.0);
  EXPECT_LT(h.inlierCount(), static_cast<int>(scene.p1.size()) / 2);
}

}  // namespace
