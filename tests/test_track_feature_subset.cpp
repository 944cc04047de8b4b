#include <gtest/gtest.h>

#include "lumaslam/core/error.h"
#include "lumaslam/track/feature_subset.h"

namespace {

using namespace lumaslam;

track::Frame frameWithFeatures(int n) {
  auto features = std::make_shared<map::FeatureSet>();
  features->descriptors = cv::Mat(n, 32, CV_8U);
  for (int i = 0; i < n; ++i) {
    const auto x = static_cast<float>(10 * i + 5);
    features->keypoints.emplace_back(cv::Point2f(x, 20.0F), 31.0F, 0.0F, 0.0F, i % 3);
    features->undistorted.emplace_back(x + 0.5F, 20.5F);
    features->depth.push_back(1.0F + static_cast<float>(i));
    features->u_right.push_back(x - 4.0F);
    features->descriptors.row(i).setTo(i);
  }
  std::vector<cv::KeyPoint> undistorted = features->keypoints;
  features->grid =
      std::make_shared<const feature::FeatureGrid>(undistorted, cv::Rect2f(0, 0, 200, 100));
  track::Frame frame;
  frame.index = 3;
  frame.features = features;
  frame.clearMatches();
  return frame;
}

TEST(FeatureSubset, KeepsTheChosenFeaturesInOrderWithEveryField) {
  auto frame = frameWithFeatures(6);
  const auto original = frame.features;
  track::keepFeatures(frame, {1, 4, 5});
  ASSERT_EQ(frame.size(), 3U);
  EXPECT_EQ(frame.points.size(), 3U);
  EXPECT_EQ(frame.outliers.size(), 3U);
  const std::vector<int> expected{1, 4, 5};
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const auto i = static_cast<std::size_t>(expected[k]);
    EXPECT_EQ(frame.features->keypoints[k].pt, original->keypoints[i].pt);
    EXPECT_EQ(frame.features->keypoints[k].octave, original->keypoints[i].octave);
    EXPECT_EQ(frame.features->undistorted[k], original->undistorted[i]);
    EXPECT_EQ(frame.features->depth[k], original->depth[i]);
    EXPECT_EQ(frame.features->u_right[k], original->u_right[i]);
    EXPECT_EQ(frame.features->descriptors.at<uchar>(static_cast<int>(k), 0), expected[k]);
  }
  ASSERT_TRUE(frame.features->grid);
  EXPECT_EQ(frame.features->grid->bounds(), original->grid->bounds());
  // The grid indexes the subset: feature 4 of the original is now feature 1.
  const auto near = frame.features->grid->featuresInArea(original->undistorted[4], 2.0F);
  ASSERT_EQ(near.size(), 1U);
  EXPECT_EQ(near[0], 1U);
}

TEST(FeatureSubset, RejectsBadIndices) {
  auto frame = frameWithFeatures(4);
  EXPECT_THROW(track::keepFeatures(frame, {2, 1}), Error);
  EXPECT_THROW(track::keepFeatures(frame, {0, 4}), Error);
  track::keepFeatures(frame, {});
  EXPECT_EQ(frame.size(), 0U);
}

}  // namespace
