// FeatureGrid area queries against a brute-force scan, the quadtree distribution and the
// per-level feature budget, on synthetic keypoints with known answers.
#include <algorithm>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "lumaslam/core/error.h"
#include "lumaslam/feature/feature_grid.h"
#include "lumaslam/feature/grid_coverage.h"
#include "lumaslam/feature/quadtree_distribution.h"
#include "lumaslam/feature/scale_levels.h"

namespace lumaslam::feature {
namespace {

std::vector<cv::KeyPoint> randomKeypoints(int count, cv::Size size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> x(0.0f, static_cast<float>(size.width));
  std::uniform_real_distribution<float> y(0.0f, static_cast<float>(size.height));
  std::uniform_int_distribution<int> octave(0, 7);
  std::uniform_real_distribution<float> response(0.0f, 100.0f);
  std::vector<cv::KeyPoint> keypoints;
  for (int i = 0; i < count; ++i) {
    keypoints.emplace_back(cv::Point2f(x(rng), y(rng)), 31.0f, 0.0f, response(rng), octave(rng));
  }
  return keypoints;
}

std::vector<std::size_t> bruteForceArea(const std::vector<cv::KeyPoint>& keypoints,
                                        cv::Point2f center, float radius, int minLevel,
                                        int maxLevel) {
  std::vector<std::size_t> found;
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& k = keypoints[i];
    if (minLevel >= 0 && k.octave < minLevel) continue;
    if (maxLevel >= 0 && k.octave > maxLevel) continue;
    if (std::abs(k.pt.x - center.x) < radius && std::abs(k.pt.y - center.y) < radius) {
      found.push_back(i);
    }
  }
  return found;
}

TEST(FeatureGrid, AreaQueriesEqualABruteForceScan) {
  const cv::Size size(752, 480);
  const auto keypoints = randomKeypoints(3000, size, 1);
  const FeatureGrid grid(keypoints, size);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> x(-50.0f, size.width + 50.0f);
  std::uniform_real_distribution<float> y(-50.0f, size.height + 50.0f);
  std::uniform_real_distribution<float> radius(0.5f, 60.0f);
  std::uniform_int_distribution<int> level(-1, 7);
  for (int query = 0; query < 500; ++query) {
    const cv::Point2f center(x(rng), y(rng));
    const float r = radius(rng);
    const int minLevel = level(rng);
    const int maxLevel = minLevel < 0 ? -1 : std::max(minLevel, level(rng));
    auto found = grid.featuresInArea(center, r, minLevel, maxLevel);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, bruteForceArea(keypoints, center, r, minLevel, maxLevel))
        << "query " << query << " at " << center << " r " << r;
  }
}

TEST(FeatureGrid, IgnoresKeypointsOutsideItsBoundsAndRejectsBadShapes) {
  std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(10, 10, 31), cv::KeyPoint(-5, 10, 31),
                                         cv::KeyPoint(10, 200, 31)};
  const FeatureGrid grid(keypoints, cv::Rect2f(0, 0, 100, 100), 10, 10);
  EXPECT_EQ(grid.keypoints().size(), 3u);
  EXPECT_EQ(grid.featuresInArea({0, 50}, 500.0f), std::vector<std::size_t>{0});
  EXPECT_THROW(FeatureGrid(keypoints, cv::Rect2f(0, 0, 0, 100)), Error);
  EXPECT_THROW(FeatureGrid(keypoints, cv::Rect2f(0, 0, 100, 100), 0, 10), Error);
}

TEST(QuadtreeDistribution, SpreadsADenseClusterAndASparseBackground) {
  // 2000 strong candidates crowd the top-left corner; 100 weak ones are spread everywhere.
  std::vector<cv::KeyPoint> candidates = randomKeypoints(2000, cv::Size(60, 60), 5);
  for (auto& k : candidates) k.response += 1000.0f;
  const auto background = randomKeypoints(100, cv::Size(640, 480), 6);
  candidates.insert(candidates.end(), background.begin(), background.end());
  const cv::Rect2f area(0, 0, 640, 480);

  const auto chosen = distributeByQuadtree(candidates, area, 300);
  EXPECT_LE(chosen.size(), 300u);
  EXPECT_GE(chosen.size(), 290u);
  const auto inCluster = std::count_if(chosen.begin(), chosen.end(), [](const cv::KeyPoint& k) {
    return k.pt.x < 60 && k.pt.y < 60;
  });
  // Most background points survive although every cluster point is stronger.
  EXPECT_GE(static_cast<long>(chosen.size()) - inCluster, 80);
  // Taking the strongest 300 instead would keep only the cluster.
  EXPECT_GT(gridCoverage(chosen, area.size()), 0.7);

  // No keypoint is invented or duplicated.
  for (const cv::KeyPoint& k : chosen) {
    EXPECT_EQ(std::count_if(candidates.begin(), candidates.end(),
                            [&](const cv::KeyPoint& c) { return c.pt == k.pt; }),
              1);
  }
}

TEST(QuadtreeDistribution, KeepsTheStrongestOfNeighbouringCandidates) {
  // Pairs of candidates one pixel apart on a coarse lattice: with a target equal to the number
  // of pairs, every pair ends up in its own node and its stronger member wins.
  std::vector<cv::KeyPoint> candidates;
  for (int row = 0; row < 8; ++row) {
    for (int column = 0; column < 8; ++column) {
      const float x = 20.0f + column * 40.0f;
      const float y = 20.0f + row * 40.0f;
      candidates.emplace_back(cv::Point2f(x, y), 31.0f, 0.0f, 10.0f);
      candidates.emplace_back(cv::Point2f(x + 1, y), 31.0f, 0.0f, 20.0f);
    }
  }
  const auto chosen = distributeByQuadtree(candidates, cv::Rect2f(0, 0, 320, 320), 64);
  ASSERT_EQ(chosen.size(), 64u);
  for (const cv::KeyPoint& k : chosen) EXPECT_EQ(k.response, 20.0f);
}

TEST(QuadtreeDistribution, HandlesFewOrNoCandidates) {
  const cv::Rect2f area(0, 0, 100, 100);
  EXPECT_TRUE(distributeByQuadtree({}, area, 10).empty());
  const auto few = randomKeypoints(5, cv::Size(100, 100), 9);
  EXPECT_EQ(distributeByQuadtree(few, area, 10).size(), 5u);
  EXPECT_TRUE(distributeByQuadtree(few, area, 0).empty());
}

TEST(ScaleLevels, BudgetIsAGeometricSeriesSummingToTheTotal) {
  const ScaleLevels levels(8, 1.2f);
  const auto budget = levels.featureBudget(1000);
  ASSERT_EQ(budget.size(), 8u);
  EXPECT_EQ(std::accumulate(budget.begin(), budget.end(), 0), 1000);
  for (int level = 1; level + 1 < 8; ++level) {
    EXPECT_NEAR(static_cast<double>(budget[level]) / budget[level - 1], 1.0 / 1.2, 0.02);
  }
  EXPECT_FLOAT_EQ(levels.scale(7), std::pow(1.2f, 7.0f));
  EXPECT_FLOAT_EQ(levels.inverseSigma2(2), 1.0f / (1.44f * 1.44f));
  EXPECT_EQ(ScaleLevels(1, 1.2f).featureBudget(500), std::vector<int>{500});
}

TEST(GridCoverage, CountsOccupiedCells) {
  const std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(1, 1, 1), cv::KeyPoint(2, 2, 1),
                                               cv::KeyPoint(99, 99, 1)};
  EXPECT_DOUBLE_EQ(gridCoverage(keypoints, cv::Size(100, 100), 2, 2), 0.5);
  EXPECT_DOUBLE_EQ(gridCoverage({}, cv::Size(100, 100)), 0.0);
  EXPECT_THROW(gridCoverage(keypoints, cv::Size(0, 100)), Error);
}

}  // namespace
}  // namespace lumaslam::feature
