// The fused Enhancer (plan + apply, compensation folded into the CLAHE tables, SIMD passes)
// against the stage-by-stage ReferenceEnhancer, on real colour (MEFB) and gray (EuRoC, KITTI)
// frames, for every preset: gray and colour outputs agree within +-1 gray level everywhere.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/enhance/adaptive_limit.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/enhance/reference_pipeline.h"
#include "lumaslam/enhance/value_channel.h"
#include "test_paths.h"

namespace lumaslam::enhance {
namespace {

struct RealFrame {
  std::string name;
  cv::Mat image;
};

// MEFB is 512x339 colour (339 rows: not a multiple of an 8x8 grid), EuRoC 752x480 and KITTI
// 1226x370 gray (1226 columns: not a multiple of 8 either).
std::vector<RealFrame> realFrames() {
  const auto mefb = test::dataDir() / "mefb/exposure_pairs_43/input";
  const auto euroc = test::dataDir() / "euroc/V1_01_easy_micro/mav0";
  const auto kitti = test::dataDir() / "kitti/odometry_07_first160/sequences/07/image_0";
  const std::vector<std::pair<std::filesystem::path, int>> files = {
      {mefb / "Arno/Arno_A.png", cv::IMREAD_COLOR},
      {mefb / "Candle/Candle_A.png", cv::IMREAD_COLOR},
      {mefb / "Church/Church_A.png", cv::IMREAD_COLOR},
      {mefb / "Balloons/Balloons_B.png", cv::IMREAD_COLOR},
      {euroc / "cam0/data/1403715273262142976.png", cv::IMREAD_GRAYSCALE},
      {euroc / "cam1/data/1403715273262142976.png", cv::IMREAD_GRAYSCALE},
      {kitti / "000100.png", cv::IMREAD_GRAYSCALE},
  };
  std::vector<RealFrame> frames;
  for (const auto& [path, flags] : files) {
    cv::Mat image = cv::imread(path.string(), flags);
    if (image.empty()) {
      ADD_FAILURE() << "cannot read " << path << " (shared data missing?)";
    } else {
      frames.push_back({path.filename().string(), image});
    }
  }
  return frames;
}

int maxDifference(const cv::Mat& a, const cv::Mat& b) {
  EXPECT_EQ(a.size(), b.size());
  EXPECT_EQ(a.type(), b.type());
  if (a.size() != b.size() || a.type() != b.type()) return 255;
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  double max_diff = 0.0;
  cv::minMaxLoc(diff.reshape(1), nullptr, &max_diff);
  return static_cast<int>(max_diff);
}

TEST(EnhanceFused, EqualsTheStageByStageReferenceWithinOneGrayLevel) {
  const auto frames = realFrames();
  ASSERT_EQ(frames.size(), 7u);
  for (const auto& preset : EnhancerParams::presetNames()) {
    for (const auto& frame : frames) {
      SCOPED_TRACE(preset + " on " + frame.name);
      const auto params = EnhancerParams::forPreset(preset);
      const EnhancedFrame fused = Enhancer(params).enhance(frame.image);
      const EnhancedFrame reference = ReferenceEnhancer(params).enhance(frame.image);
      EXPECT_LE(maxDifference(fused.gray, reference.gray), 1);
      EXPECT_LE(maxDifference(fused.colour, reference.colour), 1);
      EXPECT_EQ(fused.report.compensated, reference.report.compensated);
      EXPECT_EQ(fused.report.limit.has_value(), reference.report.limit.has_value());
      if (fused.report.limit && reference.report.limit) {
        EXPECT_NEAR(*fused.report.limit, *reference.report.limit, 1e-9);
      }
    }
  }
}

TEST(EnhanceFused, FusedStatisticsEqualTheImageBasedOnes) {
  std::vector<cv::Mat> images;
  for (const auto& frame : realFrames()) {
    cv::Mat gray = frame.image;
    if (gray.channels() == 3) cv::cvtColor(gray, gray, cv::COLOR_BGR2GRAY);
    images.push_back(gray);
    images.push_back(gray(cv::Rect(3, 1, 37, 23)).clone());  // width not a multiple of lanes
  }
  images.push_back(cv::Mat(1, 1, CV_8UC1, cv::Scalar(9)));
  images.push_back(cv::Mat(1, 40, CV_8UC1, cv::Scalar(200)));
  cv::Mat column(40, 1, CV_8UC1);
  cv::RNG(3).fill(column, cv::RNG::UNIFORM, 0, 256);
  images.push_back(column);
  for (const cv::Mat& image : images) {
    cv::Mat laplacian;
    cv::Laplacian(image, laplacian, CV_16S);
    cv::Scalar mean;
    cv::Scalar stddev;
    cv::meanStdDev(laplacian, mean, stddev);
    const double expected = stddev[0] * stddev[0];
    EXPECT_NEAR(laplacianVariance(image), expected, 1e-9 * std::max(1.0, expected))
        << image.cols << "x" << image.rows;
    const double gradient_sigma = ContrastImages(image, SigmaSource::kGradient).stats().sigma;
    EXPECT_NEAR(gradientMagnitudeStd(image), gradient_sigma, 1e-9 * std::max(1.0, gradient_sigma))
        << image.cols << "x" << image.rows;
  }
}

TEST(EnhanceFused, SimdColourRebuildEqualsTheScalarFormula) {
  const auto frames = realFrames();
  ASSERT_FALSE(frames.empty());
  const cv::Mat bgr = frames.front().image;
  const cv::Mat value = valueChannel(bgr);
  cv::Mat brighter;
  cv::LUT(
      value,
      [] {
        cv::Mat table(1, 256, CV_8UC1);
        for (int i = 0; i < 256; ++i)
          table.at<uchar>(i) = cv::saturate_cast<uchar>(std::sqrt(i) * 16);
        return table;
      }(),
      brighter);
  const cv::Mat rebuilt = rebuildColour(bgr, value, brighter);
  int mismatches = 0;
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const int old_value = value.at<uchar>(y, x);
      const int new_value = brighter.at<uchar>(y, x);
      const float scale = old_value == 0 ? 0.0f : new_value * (1.0f / old_value);
      for (int c = 0; c < 3; ++c) {
        const int expected = old_value == 0
                                 ? new_value
                                 : cv::saturate_cast<uchar>(bgr.at<cv::Vec3b>(y, x)[c] * scale);
        mismatches += rebuilt.at<cv::Vec3b>(y, x)[c] != expected;
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(EnhanceFused, PlanAndApplyEqualEnhanceAndCheckTheSize) {
  const auto frames = realFrames();
  ASSERT_GE(frames.size(), 5u);
  for (const auto& preset : {"best", "paper", "clahe", "brightness"}) {
    for (const auto& frame : {frames[0], frames[4]}) {
      Enhancer enhancer(EnhancerParams::forPreset(preset));
      const EnhancementPlan plan = enhancer.plan(frame.image);
      const EnhancedFrame applied = enhancer.apply(frame.image, plan);
      const EnhancedFrame direct = enhancer.enhance(frame.image);
      EXPECT_EQ(maxDifference(applied.gray, direct.gray), 0) << preset << " " << frame.name;
      EXPECT_EQ(maxDifference(applied.colour, direct.colour), 0) << preset << " " << frame.name;
      EXPECT_THROW(enhancer.apply(frame.image(cv::Rect(0, 0, 64, 48)).clone(), plan), Error);
    }
  }
}

}  // namespace
}  // namespace lumaslam::enhance
