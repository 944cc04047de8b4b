// ORB extractor on real EuRoC and KITTI frames: count, placement, coverage vs cv::ORB, mask,
// rotation and scale behaviour, descriptors identical to cv::ORB's, bad input.
#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/feature/grid_coverage.h"
#include "lumaslam/feature/grid_fast.h"
#include "lumaslam/feature/hamming.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/feature/projection_matcher.h"
#include "lumaslam/feature/steered_brief.h"
#include "real_frames.h"

namespace lumaslam::feature {
namespace {

using test::errorOf;
using test::eurocFrame;
using test::kittiFrame;
using test::loadGray;

const OrbExtractor& defaultExtractor() {
  static const OrbExtractor extractor{OrbSettings{}};
  return extractor;
}

double circularDifference(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d < -180.0) d += 360.0;
  return d;
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

class OrbOnRealFrames : public ::testing::TestWithParam<std::string> {
 protected:
  cv::Mat image() const {
    return GetParam() == "euroc" ? loadGray(eurocFrame("cam0", 0)) : loadGray(kittiFrame(0));
  }
};

TEST_P(OrbOnRealFrames, ExtractsTheRequestedNumberWithinTheImage) {
  const cv::Mat gray = image();
  const OrbExtractor& extractor = defaultExtractor();
  const OrbFeatures features = extractor.extract(gray);
  const int n = static_cast<int>(features.keypoints.size());
  EXPECT_LE(n, 1000);
  EXPECT_GE(n, 970);
  ASSERT_EQ(features.descriptors.rows, n);
  EXPECT_EQ(features.descriptors.cols, 32);
  EXPECT_EQ(features.descriptors.type(), CV_8UC1);
  ASSERT_EQ(static_cast<int>(features.pyramid.size()), 8);

  std::vector<int> perLevel(8, 0);
  for (const cv::KeyPoint& keypoint : features.keypoints) {
    ASSERT_GE(keypoint.octave, 0);
    ASSERT_LT(keypoint.octave, 8);
    ++perLevel[keypoint.octave];
    const float scale = extractor.levels().scale(keypoint.octave);
    EXPECT_NEAR(keypoint.size, 31.0f * scale, 1e-3f);
    EXPECT_GE(keypoint.angle, 0.0f);
    EXPECT_LT(keypoint.angle, 360.0f);
    // The whole descriptor patch (19 px at the keypoint's level) lies inside the image.
    EXPECT_GE(keypoint.pt.x, 19.0f * scale - 1.0f);
    EXPECT_GE(keypoint.pt.y, 19.0f * scale - 1.0f);
    EXPECT_LE(keypoint.pt.x, gray.cols - 19.0f * scale + 1.0f);
    EXPECT_LE(keypoint.pt.y, gray.rows - 19.0f * scale + 1.0f);
  }
  for (int level = 0; level < 8; ++level) {
    EXPECT_LE(perLevel[level], extractor.featureBudget()[level]) << "level " << level;
    EXPECT_GT(perLevel[level], 0) << "level " << level;
  }
  EXPECT_EQ(extractor.levels().sigma2(3),
            extractor.levels().scale(3) * extractor.levels().scale(3));
}

TEST_P(OrbOnRealFrames, CoversTheImageAtLeastAsWellAsOpenCvOrb) {
  const cv::Mat gray = image();
  const OrbFeatures ours = defaultExtractor().extract(gray);
  std::vector<cv::KeyPoint> theirs;
  cv::ORB::create(1000, 1.2f, 8)->detect(gray, theirs);
  const double ourCoverage = gridCoverage(ours.keypoints, gray.size());
  const double theirCoverage = gridCoverage(theirs, gray.size());
  RecordProperty("our_coverage", std::to_string(ourCoverage));
  RecordProperty("cv_orb_coverage", std::to_string(theirCoverage));
  EXPECT_GE(ourCoverage, theirCoverage);
  EXPECT_GE(ourCoverage, 0.85);
}

TEST_P(OrbOnRealFrames, KeepsFeaturesOutOfTheMask) {
  const cv::Mat gray = image();
  cv::Mat mask = cv::Mat::zeros(gray.size(), CV_8UC1);
  cv::rectangle(mask, cv::Rect(gray.cols / 4, gray.rows / 4, gray.cols / 3, gray.rows / 2),
                cv::Scalar(255), cv::FILLED);
  cv::circle(mask, cv::Point(gray.cols * 4 / 5, gray.rows / 3), gray.rows / 6, cv::Scalar(1),
             cv::FILLED);
  const OrbFeatures unmasked = defaultExtractor().extract(gray);
  const auto insideMask = [&](const cv::KeyPoint& k) {
    return mask.at<uchar>(cvRound(k.pt.y), cvRound(k.pt.x)) != 0;
  };
  ASSERT_GT(std::count_if(unmasked.keypoints.begin(), unmasked.keypoints.end(), insideMask), 50)
      << "the mask should cover textured parts of the image for this test to mean anything";

  const OrbFeatures masked = defaultExtractor().extract(gray, mask);
  EXPECT_EQ(std::count_if(masked.keypoints.begin(), masked.keypoints.end(), insideMask), 0);
  EXPECT_GE(masked.keypoints.size(), 900u) << "the budget moves to the unmasked area";
  EXPECT_EQ(masked.descriptors.rows, static_cast<int>(masked.keypoints.size()));
}

INSTANTIATE_TEST_SUITE_P(EurocAndKitti, OrbOnRealFrames, ::testing::Values("euroc", "kitti"));

TEST(OrbExtractor, AngleFollowsAnImageRotation) {
  const cv::Mat gray = loadGray(eurocFrame("cam0", 0));
  const double rotationDegrees = 40.0;
  const cv::Point2f center(gray.cols / 2.0f, gray.rows / 2.0f);
  const cv::Mat M = cv::getRotationMatrix2D(center, rotationDegrees, 1.0);
  cv::Mat rotated;
  cv::warpAffine(gray, rotated, M, gray.size(), cv::INTER_LINEAR);
  // Direction (1, 0) after the warp gives the expected keypoint angle change (y points down).
  const double expectedChange = std::atan2(M.at<double>(1, 0), M.at<double>(0, 0)) * 180.0 / CV_PI;

  const OrbFeatures before = defaultExtractor().extract(gray);
  const OrbFeatures after = defaultExtractor().extract(rotated);
  std::vector<double> angleErrors;
  std::vector<double> distances;
  for (int i = 0; i < static_cast<int>(before.keypoints.size()); ++i) {
    const cv::KeyPoint& k = before.keypoints[i];
    const cv::Point2f moved(static_cast<float>(M.at<double>(0, 0) * k.pt.x +
                                               M.at<double>(0, 1) * k.pt.y + M.at<double>(0, 2)),
                            static_cast<float>(M.at<double>(1, 0) * k.pt.x +
                                               M.at<double>(1, 1) * k.pt.y + M.at<double>(1, 2)));
    int nearest = -1;
    float nearestDistance = 1.5f * before.keypoints[i].size / 31.0f;
    for (int j = 0; j < static_cast<int>(after.keypoints.size()); ++j) {
      if (after.keypoints[j].octave != k.octave) continue;
      const float d = static_cast<float>(cv::norm(after.keypoints[j].pt - moved));
      if (d < nearestDistance) {
        nearestDistance = d;
        nearest = j;
      }
    }
    if (nearest < 0) continue;
    angleErrors.push_back(
        std::abs(circularDifference(after.keypoints[nearest].angle - k.angle, expectedChange)));
    distances.push_back(hammingDistance(before.descriptors, i, after.descriptors, nearest));
  }
  ASSERT_GE(angleErrors.size(), 200u) << "too few repeated keypoints to judge";
  EXPECT_LT(median(angleErrors), 3.0);
  const auto closeAngles =
      std::count_if(angleErrors.begin(), angleErrors.end(), [](double e) { return e < 10.0; });
  EXPECT_GE(closeAngles, static_cast<long>(0.8 * angleErrors.size()));
  // Steered BRIEF: the same corner gives nearly the same descriptor after rotation.
  EXPECT_LT(median(distances), 40.0);
}

TEST(OrbExtractor, ScalingTheImageShiftsTheOctave) {
  const cv::Mat gray = loadGray(eurocFrame("cam0", 0));
  constexpr int kShift = 2;
  const double factor = std::pow(1.2, kShift);
  cv::Mat smaller;
  cv::resize(gray, smaller, cv::Size(cvRound(gray.cols / factor), cvRound(gray.rows / factor)), 0,
             0, cv::INTER_AREA);
  const OrbFeatures large = defaultExtractor().extract(gray);
  const OrbFeatures small = defaultExtractor().extract(smaller);

  std::map<int, int> octaveShiftVotes;
  int compared = 0;
  for (int i = 0; i < static_cast<int>(large.keypoints.size()); ++i) {
    const cv::KeyPoint& k = large.keypoints[i];
    const cv::Point2f expected = k.pt * static_cast<float>(1.0 / factor);
    int best = -1;
    int bestDistance = kThLow;
    for (int j = 0; j < static_cast<int>(small.keypoints.size()); ++j) {
      const float tolerance = 2.0f * small.keypoints[j].size / 31.0f;
      if (cv::norm(small.keypoints[j].pt - expected) > tolerance) continue;
      const int d = hammingDistance(large.descriptors, i, small.descriptors, j);
      if (d < bestDistance) {
        bestDistance = d;
        best = j;
      }
    }
    if (best < 0) continue;
    ++compared;
    ++octaveShiftVotes[k.octave - small.keypoints[best].octave];
  }
  ASSERT_GE(compared, 100);
  const auto mode = std::max_element(octaveShiftVotes.begin(), octaveShiftVotes.end(),
                                     [](auto& a, auto& b) { return a.second < b.second; });
  EXPECT_EQ(mode->first, kShift);
  EXPECT_GE(mode->second, compared / 2);
}

TEST(OrbExtractor, DescriptorsAreBitIdenticalToOpenCvOrb) {
  // cv::ORB with provided keypoints keeps their angle and samples the same learned pattern on
  // a 7x7 sigma-2 smoothed image. It smooths a region of a reflect-padded buffer, which rounds
  // ~1% of pixels differently from smoothing the bare image. Given that same smoothed image,
  // computeSteeredBrief must agree on every bit (this checks the pattern table), and so must
  // the extractor, which smooths its padded pyramid levels the same way.
  const cv::Mat gray = loadGray(eurocFrame("cam0", 5));
  const OrbFeatures ours = defaultExtractor().extract(gray);
  std::vector<cv::KeyPoint> levelZero;
  std::vector<int> rows;
  for (int i = 0; i < static_cast<int>(ours.keypoints.size()); ++i) {
    if (ours.keypoints[i].octave == 0) {
      levelZero.push_back(ours.keypoints[i]);
      rows.push_back(i);
    }
  }
  ASSERT_GE(levelZero.size(), 100u);
  std::vector<cv::KeyPoint> computed = levelZero;
  cv::Mat theirs;
  cv::ORB::create(1000, 1.2f, 1, 19, 0, 2, cv::ORB::HARRIS_SCORE, 31)
      ->compute(gray, computed, theirs);
  ASSERT_EQ(computed.size(), levelZero.size());

  cv::Mat padded;
  cv::copyMakeBorder(gray, padded, 32, 32, 32, 32, cv::BORDER_REFLECT_101);
  cv::Mat smoothedLikeOpenCv = padded(cv::Rect(32, 32, gray.cols, gray.rows));
  cv::GaussianBlur(smoothedLikeOpenCv, smoothedLikeOpenCv, cv::Size(7, 7), 2, 2,
                   cv::BORDER_REFLECT_101);
  int identical = 0;
  int extractorIdentical = 0;
  for (int i = 0; i < static_cast<int>(computed.size()); ++i) {
    ASSERT_EQ(computed[i].pt, levelZero[i].pt);
    ASSERT_EQ(computed[i].angle, levelZero[i].angle);
    Descriptor descriptor;
    computeSteeredBrief(smoothedLikeOpenCv, levelZero[i].pt, levelZero[i].angle, descriptor.data());
    if (hammingDistance(theirs.ptr<std::uint8_t>(i), descriptor.data()) == 0) ++identical;
    if (hammingDistance(theirs, i, ours.descriptors, rows[i]) == 0) ++extractorIdentical;
  }
  EXPECT_EQ(identical, static_cast<int>(computed.size()));
  EXPECT_EQ(extractorIdentical, static_cast<int>(computed.size()));
}

// ORB-SLAM's per-cell rule written out plainly: FAST at the low threshold over the region
// kEdgeThreshold - 3 px inside the border; in 30-px cells of that region (counted from FAST's
// 3-px ring), a cell with a corner of response >= the high threshold keeps only those.
std::vector<cv::KeyPoint> perCellReference(const cv::Mat& image, int high, int low,
                                           int& fallbackCells, int& cellCount) {
  const int border = kEdgeThreshold - 3;
  const cv::Rect region(border, border, image.cols - 2 * border, image.rows - 2 * border);
  std::vector<cv::KeyPoint> all;
  cv::FAST(image(region), all, low, true);
  const int columns = std::max(1, region.width / kFastCellSize);
  const int rows = std::max(1, region.height / kFastCellSize);
  const int cellWidth = (region.width + columns - 1) / columns;
  const int cellHeight = (region.height + rows - 1) / rows;
  const auto cellOf = [&](const cv::KeyPoint& k) {
    return std::min(static_cast<int>(k.pt.y - 3) / cellHeight, rows - 1) * columns +
           std::min(static_cast<int>(k.pt.x - 3) / cellWidth, columns - 1);
  };
  std::vector<bool> strong(static_cast<std::size_t>(columns * rows), false);
  for (const cv::KeyPoint& k : all) {
    if (k.response >= high) strong[cellOf(k)] = true;
  }
  cellCount = columns * rows;
  fallbackCells = static_cast<int>(std::count(strong.begin(), strong.end(), false));
  std::vector<cv::KeyPoint> kept;
  for (cv::KeyPoint k : all) {
    if (strong[cellOf(k)] && k.response < high) continue;
    k.pt += cv::Point2f(static_cast<float>(border), static_cast<float>(border));
    kept.push_back(k);
  }
  return kept;
}

TEST(GridFast, EqualsOneLowThresholdPassSplitIntoCells) {
  // detectFastInCells runs a high-threshold pass and low-threshold passes over just the cells
  // it left empty (or one low pass when most cells are empty); either way it must give the
  // plain rule's corners, responses and raster order on every pyramid level, for textured
  // frames with some empty cells and for a low-contrast frame where nearly all are empty.
  const cv::Mat euroc = loadGray(eurocFrame("cam0", 0));
  cv::Mat lowContrast;
  euroc.convertTo(lowContrast, CV_8U, 0.2, 40);
  int levelsWithSomeFallback = 0;
  int levelsWithMostlyFallback = 0;
  for (cv::Mat image : {euroc, loadGray(kittiFrame(0)), lowContrast}) {
    for (int level = 0; level < 8; ++level) {
      for (const auto& [high, low] : {std::pair{20, 7}, std::pair{40, 12}}) {
        int fallback = 0;
        int cells = 0;
        const std::vector<cv::KeyPoint> expected =
            perCellReference(image, high, low, fallback, cells);
        const std::vector<cv::KeyPoint> found = detectFastInCells(image, high, low);
        ASSERT_EQ(found.size(), expected.size()) << "level " << level << ", " << image.size;
        for (std::size_t i = 0; i < found.size(); ++i) {
          ASSERT_EQ(found[i].pt, expected[i].pt) << "level " << level << ", corner " << i;
          ASSERT_EQ(found[i].response, expected[i].response) << "level " << level;
        }
        if (fallback > 0 && fallback < cells / 2) ++levelsWithSomeFallback;
        if (fallback > cells * 8 / 10) ++levelsWithMostlyFallback;
      }
      cv::resize(image, image, cv::Size(cvRound(image.cols / 1.2), cvRound(image.rows / 1.2)));
    }
  }
  EXPECT_GE(levelsWithSomeFallback, 5);
  EXPECT_GE(levelsWithMostlyFallback, 5);
}

TEST(OrbExtractor, ParallelLevelsGiveTheSameFeatures) {
  const cv::Mat gray = loadGray(kittiFrame(10));
  OrbSettings settings;
  settings.parallelLevels = true;
  const OrbFeatures parallel = OrbExtractor(settings).extract(gray);
  const OrbFeatures sequential = defaultExtractor().extract(gray);
  ASSERT_EQ(parallel.keypoints.size(), sequential.keypoints.size());
  for (std::size_t i = 0; i < parallel.keypoints.size(); ++i) {
    EXPECT_EQ(parallel.keypoints[i].pt, sequential.keypoints[i].pt);
    EXPECT_EQ(parallel.keypoints[i].angle, sequential.keypoints[i].angle);
  }
  EXPECT_EQ(cv::norm(parallel.descriptors, sequential.descriptors, cv::NORM_HAMMING), 0.0);
}

TEST(OrbExtractor, FlatImageGivesNoFeaturesWithoutFailing) {
  const cv::Mat flat(480, 640, CV_8UC1, cv::Scalar(128));
  const OrbFeatures features = defaultExtractor().extract(flat);
  EXPECT_TRUE(features.keypoints.empty());
  EXPECT_EQ(features.descriptors.rows, 0);
  EXPECT_EQ(features.descriptors.cols, 32);
}

void expectErrorMentioning(const std::function<void()>& action, const std::string& text) {
  const std::string message = errorOf(action);
  EXPECT_NE(message.find(text), std::string::npos)
      << "expected lumaslam::Error mentioning '" << text << "': " << message;
}

TEST(OrbExtractor, RejectsBadImagesAndMasks) {
  const OrbExtractor& extractor = defaultExtractor();
  const cv::Mat gray(480, 640, CV_8UC1, cv::Scalar(0));
  expectErrorMentioning([&] { extractor.extract(cv::Mat()); }, "empty");
  expectErrorMentioning([&] { extractor.extract(cv::Mat(480, 640, CV_8UC3)); }, "CV_8UC1");
  expectErrorMentioning([&] { extractor.extract(cv::Mat(20, 640, CV_8UC1)); }, "too small");
  expectErrorMentioning([&] { extractor.extract(gray, cv::Mat(240, 320, CV_8UC1)); }, "mask");
  expectErrorMentioning([&] { extractor.extract(gray, cv::Mat(480, 640, CV_32FC1)); }, "mask");
}

}  // namespace
}  // namespace lumaslam::feature
