// Dynamic masks on constructed images with known answers: margin growth, depth refinement
// (a person at 1.5 m in front of a wall at 4 m) and keypoint filtering.
#include <cmath>

#include <gtest/gtest.h>

#include "lumaslam/core/error.h"
#include "lumaslam/detect/dynamic_mask.h"

namespace lumaslam::detect {
namespace {

TEST(DynamicMask, CoversBoxesGrownByTheMargin) {
  const cv::Size size(200, 100);
  const cv::Mat mask = makeDynamicMask(size, {{50, 20, 30, 40}, {190, 90, 30, 30}}, 5);
  ASSERT_EQ(mask.size(), size);
  ASSERT_EQ(mask.type(), CV_8U);
  // First box grows to x 45..85, y 15..65.
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(45, 15, 40, 50))), 40 * 50);
  EXPECT_EQ(mask.at<uchar>(15, 45), 255);
  EXPECT_EQ(mask.at<uchar>(14, 45), 0);
  EXPECT_EQ(mask.at<uchar>(15, 44), 0);
  EXPECT_EQ(mask.at<uchar>(64, 84), 255);
  EXPECT_EQ(mask.at<uchar>(65, 84), 0);
  EXPECT_EQ(mask.at<uchar>(64, 85), 0);
  // Second box is clipped at the image corner: x 185..199, y 85..99.
  EXPECT_EQ(cv::countNonZero(mask), 40 * 50 + 15 * 15);

  EXPECT_EQ(cv::countNonZero(makeDynamicMask(size, {{50, 20, 30, 40}}, 0)), 30 * 40);
  EXPECT_EQ(cv::countNonZero(makeDynamicMask(size, {}, 5)), 0);
  EXPECT_THROW(makeDynamicMask(size, {}, -1), Error);
}

// A wall at 4 m with a person-shaped block at 1.5 m; some depth holes on both.
struct PersonScene {
  cv::Mat depth{240, 320, CV_32F, cv::Scalar(4.0f)};
  cv::Rect person{120, 40, 60, 180};
  cv::Rect2f box{110, 30, 80, 200};  // the detector's box: looser than the person
  PersonScene() {
    depth(person).setTo(1.5f);
    depth(cv::Rect(100, 100, 8, 8)).setTo(0.0f);  // hole on the wall inside the grown box
    depth.at<float>(50, 150) = std::nanf("");     // hole on the person
  }
};

TEST(DynamicMask, DepthRefinementFreesTheWallBehindThePerson) {
  const PersonScene scene;
  MaskParams params;
  params.margin_px = 10;
  params.depth_tolerance_m = 0.4;
  params.depth_edge_px = 0;
  const std::optional<double> person = personDepth(scene.depth, scene.box, params);
  ASSERT_TRUE(person);
  EXPECT_NEAR(*person, 1.5, 1e-6);

  const cv::Mat mask = makeDynamicMask(scene.depth.size(), {scene.box}, params.margin_px);
  const cv::Mat refined = refineMaskWithDepth(mask, scene.depth, {scene.box}, params);
  // Every person pixel stays masked (the NaN hole too: unknown depth is not freed).
  EXPECT_EQ(cv::countNonZero(refined(scene.person)), scene.person.area());
  // Wall pixels inside the box are freed, except the depth hole.
  const cv::Rect grown(100, 20, 100, 220);
  const int wall_pixels = grown.area() - scene.person.area();
  const int hole = 8 * 8;
  EXPECT_EQ(cv::countNonZero(refined(grown)), scene.person.area() + hole);
  EXPECT_EQ(cv::countNonZero(refined), scene.person.area() + hole);
  EXPECT_GT(wall_pixels, hole);

  // A larger tolerance than the gap keeps everything masked.
  params.depth_tolerance_m = 3.0;
  EXPECT_EQ(cv::countNonZero(refineMaskWithDepth(mask, scene.depth, {scene.box}, params)),
            cv::countNonZero(mask));
}

TEST(DynamicMask, DepthRefinementKeepsABandAroundThePersonMasked) {
  const PersonScene scene;
  MaskParams params;
  params.margin_px = 10;
  params.depth_edge_px = 6;
  const cv::Mat mask = makeDynamicMask(scene.depth.size(), {scene.box}, params.margin_px);
  const cv::Mat refined = refineMaskWithDepth(mask, scene.depth, {scene.box}, params);
  EXPECT_EQ(cv::countNonZero(refined(scene.person)), scene.person.area());
  // Wall pixels left and right of the person (x 120..179, rows 60..199 away from the hole):
  // masked within 6 px of the silhouette, freed beyond.
  for (int y : {60, 130, 199}) {
    EXPECT_EQ(refined.at<uchar>(y, 120 - 6), 255) << y;
    EXPECT_EQ(refined.at<uchar>(y, 120 - 7), 0) << y;
    EXPECT_EQ(refined.at<uchar>(y, 179 + 6), 255) << y;
    EXPECT_EQ(refined.at<uchar>(y, 179 + 7), 0) << y;
  }
  // The band costs only pixels near the person: far wall pixels of the grown box are free.
  EXPECT_EQ(refined.at<uchar>(25, 102), 0);
  EXPECT_EQ(refined.at<uchar>(235, 195), 0);
  // The band is all the guard adds: wider bands mask strictly more.
  params.depth_edge_px = 0;
  const int no_band = cv::countNonZero(refineMaskWithDepth(mask, scene.depth, {scene.box}, params));
  EXPECT_GT(cv::countNonZero(refined), no_band);
}

TEST(DynamicMask, DepthRefinementLeavesMaskedAreasOutsideBoxesAlone) {
  const PersonScene scene;
  cv::Mat mask = makeDynamicMask(scene.depth.size(), {scene.box}, 10);
  mask(cv::Rect(0, 0, 20, 20)).setTo(255);  // masked by someone else, no box: untouched
  const cv::Mat no_depth(scene.depth.size(), CV_32F, cv::Scalar(0.0f));
  EXPECT_EQ(cv::countNonZero(refineMaskWithDepth(mask, no_depth, {scene.box})),
            cv::countNonZero(mask));
  const cv::Mat refined = refineMaskWithDepth(mask, scene.depth, {scene.box});
  EXPECT_EQ(cv::countNonZero(refined(cv::Rect(0, 0, 20, 20))), 400);

  EXPECT_THROW(refineMaskWithDepth(mask, cv::Mat(10, 10, CV_32F), {scene.box}), Error);
  EXPECT_THROW(refineMaskWithDepth(mask, cv::Mat(scene.depth.size(), CV_16U), {scene.box}), Error);
}

TEST(DynamicMask, FilterKeypointsKeepsThoseOutsideTheMask) {
  const cv::Mat mask = makeDynamicMask({100, 100}, {{10, 10, 20, 20}}, 0);
  const std::vector<cv::KeyPoint> keypoints{
      {5.0f, 5.0f, 7.0f},     // outside
      {15.0f, 15.0f, 7.0f},   // inside
      {29.6f, 15.0f, 7.0f},   // rounds to x 30: outside
      {29.4f, 15.0f, 7.0f},   // rounds to x 29: inside
      {-3.0f, 150.0f, 7.0f},  // off the image: kept
  };
  EXPECT_EQ(filterKeypoints(keypoints, mask), (std::vector<int>{0, 2, 4}));
}

}  // namespace
}  // namespace lumaslam::detect
