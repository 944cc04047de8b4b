#include "lumaslam/feature/orb_extractor.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/feature/grid_fast.h"
#include "lumaslam/feature/intensity_centroid.h"
#include "lumaslam/feature/quadtree_distribution.h"
#include "lumaslam/feature/steered_brief.h"

namespace lumaslam::feature {

namespace {

constexpr int kPyramidBorder = 8;  // > the 3-px radius of the 7x7 descriptor smoothing

const IntensityCentroid& intensityCentroid() {
  static const IntensityCentroid centroid;
  return centroid;
}

// Drops candidates whose level-0 position falls on a nonzero mask pixel.
void removeMasked(std::vector<cv::KeyPoint>& candidates, const cv::Mat& mask, float scale) {
  if (mask.empty()) return;
  std::erase_if(candidates, [&](const cv::KeyPoint& candidate) {
    const int x = std::min(cvRound(candidate.pt.x * scale), mask.cols - 1);
    const int y = std::min(cvRound(candidate.pt.y * scale), mask.rows - 1);
    return mask.at<uchar>(y, x) != 0;
  });
}

const OrbSettings& validated(const OrbSettings& settings) {
  settings.validate("OrbExtractor settings");
  return settings;
}

}  // namespace

OrbExtractor::OrbExtractor(const OrbSettings& settings)
    : settings_(validated(settings)),
      levels_(settings_.nLevels, settings_.scaleFactor),
      budget_(levels_.featureBudget(settings_.nFeatures)) {}

std::vector<cv::Mat> OrbExtractor::buildPyramid(const cv::Mat& image) const {
  // Every level is the centre of a buffer with a reflected border, as cv::ORB builds it: the
  // descriptor smoothing of such a sub-image reads real neighbours instead of extrapolating
  // at each pixel, which takes OpenCV's separable filter path (half the instructions of the
  // bit-exact path it uses for whole images) and gives cv::ORB's smoothed pixels.
  std::vector<cv::Mat> pyramid(levels_.count());
  for (int level = 0; level < levels_.count(); ++level) {
    const float inverse = levels_.inverseScale(level);
    const cv::Size size(cvRound(image.cols * inverse), cvRound(image.rows * inverse));
    if (size.width < 1 || size.height < 1) break;
    cv::Mat padded(size.height + 2 * kPyramidBorder, size.width + 2 * kPyramidBorder, CV_8UC1);
    pyramid[level] = padded(cv::Rect(kPyramidBorder, kPyramidBorder, size.width, size.height));
    if (level == 0) {
      image.copyTo(pyramid[level]);
    } else {
      cv::resize(pyramid[level - 1], pyramid[level], size, 0, 0, cv::INTER_LINEAR);
    }
    cv::copyMakeBorder(pyramid[level], padded, kPyramidBorder, kPyramidBorder, kPyramidBorder,
                       kPyramidBorder, cv::BORDER_REFLECT_101 | cv::BORDER_ISOLATED);
  }
  return pyramid;
}

void OrbExtractor::extractLevel(const cv::Mat& levelImage, int level, const cv::Mat& mask,
                                std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) const {
  keypoints.clear();
  descriptors.release();
  if (levelImage.empty() || budget_[level] == 0) return;
  std::vector<cv::KeyPoint> candidates =
      detectFastInCells(levelImage, settings_.iniThFAST, settings_.minThFAST);
  removeMasked(candidates, mask, levels_.scale(level));
  keypoints = distributeByQuadtree(candidates, detectionArea(levelImage.size()), budget_[level]);
  if (keypoints.empty()) return;

  const float scale = levels_.scale(level);
  const float size = kPatchSize * scale;
  const cv::Mat smoothed = smoothForDescriptors(levelImage);
  descriptors.create(static_cast<int>(keypoints.size()), kDescriptorBytes, CV_8UC1);
  for (int i = 0; i < static_cast<int>(keypoints.size()); ++i) {
    cv::KeyPoint& keypoint = keypoints[i];
    keypoint.angle = intensityCentroid().angle(levelImage, keypoint.pt);
    computeSteeredBrief(smoothed, keypoint.pt, keypoint.angle, descriptors.ptr<uchar>(i));
    keypoint.octave = level;
    keypoint.size = size;
    keypoint.pt *= scale;
  }
}

OrbFeatures OrbExtractor::extract(const cv::Mat& image, const cv::Mat& mask) const {
  if (image.empty()) fail("OrbExtractor: input image is empty");
  if (image.type() != CV_8UC1) {
    fail("OrbExtractor: input image must be 8-bit gray (CV_8UC1), got {} channel(s) of depth {}",
         image.channels(), image.depth());
  }
  if (image.cols < 2 * kEdgeThreshold + 1 || image.rows < 2 * kEdgeThreshold + 1) {
    fail("OrbExtractor: input image {}x{} is too small (needs at least {} px per side)", image.cols,
         image.rows, 2 * kEdgeThreshold + 1);
  }
  if (!mask.empty() && (mask.type() != CV_8UC1 || mask.size() != image.size())) {
    fail(
        "OrbExtractor: mask must be CV_8UC1 of the image size {}x{}, got {}x{} with {} "
        "channel(s) of depth {}",
        image.cols, image.rows, mask.cols, mask.rows, mask.channels(), mask.depth());
  }

  OrbFeatures features;
  features.pyramid = buildPyramid(image);
  const int levelCount = levels_.count();
  std::vector<std::vector<cv::KeyPoint>> levelKeypoints(levelCount);
  std::vector<cv::Mat> levelDescriptors(levelCount);
  const auto extractRange = [&](const cv::Range& range) {
    for (int level = range.start; level < range.end; ++level) {
      extractLevel(features.pyramid[level], level, mask, levelKeypoints[level],
                   levelDescriptors[level]);
    }
  };
  if (settings_.parallelLevels) {
    cv::parallel_for_(cv::Range(0, levelCount), extractRange);
  } else {
    extractRange(cv::Range(0, levelCount));
  }

  for (int level = 0; level < levelCount; ++level) {
    features.keypoints.insert(features.keypoints.end(), levelKeypoints[level].begin(),
                              levelKeypoints[level].end());
  }
  std::vector<cv::Mat> nonEmpty;
  for (const cv::Mat& descriptors : levelDescriptors) {
    if (!descriptors.empty()) nonEmpty.push_back(descriptors);
  }
  if (nonEmpty.empty()) {
    features.descriptors.create(0, kDescriptorBytes, CV_8UC1);
  } else {
    cv::vconcat(nonEmpty, features.descriptors);
  }
  return features;
}

}  // namespace lumaslam::feature
