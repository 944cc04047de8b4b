// Sim3 between two cameras from matched points (sim3_ransac.h, optimize::refineSim3):
// a known similarity, pixel noise on the observations and 30 % wrong matches.
#include <random>

#include <gtest/gtest.h>

#include "lumaslam/loop/sim3_ransac.h"
#include "lumaslam/optimize/sim3_alignment.h"

namespace {

using namespace lumaslam;

const CameraIntrinsics kCamera{450.0, 450.0, 320.0, 240.0, 0.0};

struct Scene {
  optimize::Sim3 S_12;
  std::vector<optimize::Sim3Pair> pairs;
  std::vector<bool> wrong;
};

Eigen::Vector2d project(const Eigen::Vector3d& X) {
  return {kCamera.fx * X.x() / X.z() + kCamera.cx, kCamera.fy * X.y() / X.z() + kCamera.cy};
}

Scene makeScene(double scale, int count, double outlier_ratio, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> lateral(-1.5, 1.5);
  std::uniform_real_distribution<double> depth(2.0, 6.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> pixel(0.0, 0.7);
  Scene scene;
  scene.S_12 = {
      scale,
      Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.2, 1.0, 0.1).normalized())),
      Eigen::Vector3d(0.3, -0.05, 0.1) * scale};
  const optimize::Sim3 S_21 = scene.S_12.inverse();
  while (static_cast<int>(scene.pairs.size()) < count) {
    // A point in camera 1, seen in front of both cameras.
    const Eigen::Vector3d X1(lateral(random), lateral(random), depth(random));
    const Eigen::Vector3d X2 = S_21 * X1;
    if (X2.z() <= 0.5) continue;
    optimize::Sim3Pair pair;
    pair.X1 = X1;
    pair.X2 = X2;
    pair.uv1 = project(X1) + Eigen::Vector2d(pixel(random), pixel(random));
    pair.uv2 = project(X2) + Eigen::Vector2d(pixel(random), pixel(random));
    const bool wrong = unit(random) < outlier_ratio;
    if (wrong) pair.X2 = S_21 * Eigen::Vector3d(lateral(random), lateral(random), depth(random));
    scene.pairs.push_back(pair);
    scene.wrong.push_back(wrong);
  }
  return scene;
}

TEST(Sim3Ransac, FindsTheSimilarityAndTheWrongMatches) {
  for (const double scale : {0.6, 1.0, 1.7}) {
    const Scene scene = makeScene(scale, 120, 0.3, 7);
    const auto found = loop::estimateSim3Ransac(scene.pairs, kCamera);
    ASSERT_TRUE(found.has_value()) << "scale " << scale;
    EXPECT_NEAR(found->S_12.scale, scale, 0.02 * scale);
    EXPECT_LT(found->S_12.rotation.angularDistance(scene.S_12.rotation), 0.01);
    int wrong_accepted = 0;
    for (std::size_t p = 0; p < scene.pairs.size(); ++p) {
      if (found->inlier[p] && scene.wrong[p]) ++wrong_accepted;
    }
    EXPECT_EQ(wrong_accepted, 0);
    EXPECT_GE(found->inliers, 70);

    // The Ceres refinement from a perturbed start returns to the truth.
    optimize::Sim3 start = found->S_12;
    start.scale *= 1.05;
    const auto refined = optimize::refineSim3(scene.pairs, start, kCamera);
    EXPECT_NEAR(refined.S_12.scale, scale, 0.02 * scale);
    EXPECT_LT((refined.S_12.translation - scene.S_12.translation).norm(), 0.02 * scale);
    EXPECT_GE(refined.inliers, 70);
  }
}

TEST(Sim3Ransac, RejectsMatchesWithoutACommonSimilarity) {
  Scene scene = makeScene(1.0, 60, 1.0, 3);  // every match wrong
  EXPECT_FALSE(loop::estimateSim3Ransac(scene.pairs, kCamera).has_value());
  scene.pairs.resize(2);
  EXPECT_FALSE(loop::estimateSim3Ransac(scene.pairs, kCamera).has_value());
}

}  // namespace
