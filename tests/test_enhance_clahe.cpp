// Our CLAHE against cv::CLAHE with the same grid and limit, on real EuRoC/KITTI frames and on
// synthetic frames, including sizes that are not multiples of the grid.
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/enhance/clahe.h"
#include "test_paths.h"

namespace lumaslam::enhance {
namespace {

// Fraction of pixels where the two images differ by at most one gray level.
double agreement(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  return 1.0 - static_cast<double>(cv::countNonZero(diff > 1)) / static_cast<double>(a.total());
}

void expectMatchesOpenCv(const cv::Mat& gray, int tiles_x, int tiles_y, double limit) {
  const cv::Mat ours = Clahe(tiles_x, tiles_y).apply(gray, limit);
  cv::Mat reference;
  cv::createCLAHE(limit, {tiles_x, tiles_y})->apply(gray, reference);
  ASSERT_EQ(ours.size(), gray.size());
  ASSERT_EQ(ours.type(), CV_8UC1);
  EXPECT_GE(agreement(ours, reference), 0.995) << gray.cols << "x" << gray.rows << " grid "
                                               << tiles_x << "x" << tiles_y << " limit " << limit;
}

std::vector<cv::Mat> realFrames() {
  const auto euroc = test::dataDir() / "euroc/V1_01_easy_micro/mav0/cam0/data";
  const auto kitti = test::dataDir() / "kitti/odometry_07_first160/sequences/07/image_0";
  std::vector<cv::Mat> frames;
  for (const auto& path : {euroc / "1403715273262142976.png", euroc / "1403715277962142976.png",
                           kitti / "000000.png", kitti / "000100.png"}) {
    cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    if (image.empty())
      ADD_FAILURE() << "cannot read " << path;
    else
      frames.push_back(image);
  }
  return frames;
}

cv::Mat syntheticFrame(cv::Size size, int seed, double gain) {
  cv::RNG rng(seed);
  cv::Mat image(size, CV_8UC1, cv::Scalar(30));
  for (int i = 0; i < 40; ++i) {
    const cv::Point a(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const cv::Point b(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const cv::Scalar shade(rng.uniform(0, 256));
    if (i % 2)
      cv::rectangle(image, a, b, shade, cv::FILLED);
    else
      cv::circle(image, a, rng.uniform(2, 60), shade, cv::FILLED);
  }
  cv::Mat noise(size, CV_8UC1);
  rng.fill(noise, cv::RNG::NORMAL, 0, 8);
  image += noise;
  image.convertTo(image, CV_8U, gain);  // gain < 1 makes a dark frame
  return image;
}

TEST(EnhanceClahe, MatchesOpenCvOnRealFrames) {
  for (const cv::Mat& frame : realFrames()) {
    for (double limit : {1.0, 2.0, 4.0, 40.0}) expectMatchesOpenCv(frame, 8, 8, limit);
    expectMatchesOpenCv(frame, 5, 7, 3.0);  // neither 752/1226 nor 480/370 is a multiple
  }
}

TEST(EnhanceClahe, MatchesOpenCvOnCropsNotDivisibleByTheGrid) {
  const cv::Mat frame = realFrames().front();
  for (const cv::Rect crop : {cv::Rect(0, 0, 751, 479), cv::Rect(3, 0, 641, 480),
                              cv::Rect(10, 3, 640, 477), cv::Rect(0, 0, 37, 29)}) {
    expectMatchesOpenCv(frame(crop).clone(), 8, 8, 2.0);
    expectMatchesOpenCv(frame(crop).clone(), 7, 6, 12.0);
  }
}

TEST(EnhanceClahe, MatchesOpenCvOnSyntheticFrames) {
  int seed = 1;
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(752, 480), cv::Size(333, 217),
                              cv::Size(1226, 370), cv::Size(9, 9)}) {
    for (double gain : {1.0, 0.15}) {
      const cv::Mat frame = syntheticFrame(size, seed++, gain);
      for (double limit : {1.0, 2.0, 8.0}) expectMatchesOpenCv(frame, 8, 8, limit);
      expectMatchesOpenCv(frame, 4, 2, 3.0);
    }
  }
}

TEST(EnhanceClahe, UnclippedEqualisationMatchesOpenCv) {
  expectMatchesOpenCv(syntheticFrame({320, 240}, 7, 0.5), 8, 8, 0.0);
}

TEST(EnhanceClahe, PerTileLimitsEqualTheFixedLimitWhenAllTheSame) {
  const cv::Mat frame = syntheticFrame({200, 150}, 3, 0.4);
  const Clahe clahe(4, 3);
  const cv::Mat uniform = clahe.apply(frame, cv::Mat(3, 4, CV_64FC1, cv::Scalar(2.5)));
  EXPECT_EQ(cv::countNonZero(uniform != clahe.apply(frame, 2.5)), 0);
  // A higher limit in one tile can only raise that tile's contrast.
  cv::Mat limits(3, 4, CV_64FC1, cv::Scalar(1.0));
  limits.at<double>(1, 1) = 3.0;
  const cv::Mat mixed = clahe.apply(frame, limits);
  EXPECT_GT(cv::countNonZero(mixed != clahe.apply(frame, 1.0)), 0);
}

TEST(EnhanceClahe, RejectsBadInput) {
  const Clahe clahe(8, 8);
  EXPECT_THROW(clahe.apply(cv::Mat(), 2.0), Error);
  EXPECT_THROW(clahe.apply(cv::Mat(10, 10, CV_16UC1, cv::Scalar(5)), 2.0), Error);
  EXPECT_THROW(clahe.apply(cv::Mat(10, 10, CV_8UC3), 2.0), Error);
  EXPECT_THROW(clahe.apply(cv::Mat(10, 10, CV_8UC1), cv::Mat(2, 2, CV_64FC1)), Error);
  EXPECT_THROW(Clahe(0, 8), Error);
  const cv::Mat one(1, 1, CV_8UC1, cv::Scalar(77));
  const cv::Mat out = clahe.apply(one, 2.0);
  ASSERT_EQ(out.size(), one.size());
  cv::Mat reference;
  cv::createCLAHE(2.0, {8, 8})->apply(one, reference);
  EXPECT_NEAR(out.at<uchar>(0, 0), reference.at<uchar>(0, 0), 1);
}

}  // namespace
}  // namespace lumaslam::enhance
