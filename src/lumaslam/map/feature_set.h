#pragma once
// The features of one frame as tracking hands them to a keyframe. Immutable once a keyframe
// holds it (shared, read without locks).
#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/feature/feature_grid.h"

namespace lumaslam::map {

struct FeatureSet {
  std::vector<cv::KeyPoint> keypoints;   // as detected (distorted), level-0 pixels, octave set
  std::vector<cv::Point2f> undistorted;  // same order, undistorted (rectified) pixels
  std::vector<float> u_right;            // stereo / virtual-stereo right u; < 0 if none
  std::vector<float> depth;              // metres; < 0 if none
  cv::Mat descriptors;                   // N x 32, CV_8U
  // Undistorted keypoints bucketed for window queries (projection search, fusion); may be
  // null for feature sets built by hand in tests.
  std::shared_ptr<const feature::FeatureGrid> grid;
  // Per feature, 1 when tracking found it moving (track::MotionEvidence): no map point is
  // made from it. Empty: none known. Set by the tracker before a keyframe holds the set.
  std::vector<std::uint8_t> moving;

  std::size_t size() const { return keypoints.size(); }
  bool hasStereo(std::size_t i) const { return i < u_right.size() && u_right[i] >= 0.0F; }
  bool isMoving(std::size_t i) const { return i < moving.size() && moving[i] != 0; }
};

}  // namespace lumaslam::map
