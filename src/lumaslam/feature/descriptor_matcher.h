#pragma once
// Matching two sets of ORB descriptors without a map: everything against everything, or
// within a pixel window around each query keypoint (e.g. map initialisation, stereo/consecutive
// frames). Results are cv::DMatch with queryIdx/trainIdx/distance (Hamming bits).
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/feature/feature_grid.h"
#include "lumaslam/feature/hamming.h"

namespace lumaslam::feature {

struct MatchOptions {
  int maxDistance = kThLow;
  // Lowe's ratio test: best < ratio * second best (second best among other train features).
  // 1 or more disables it.
  float ratio = 0.8f;
  // Keep a match only if the query is also the best among all queries for its train feature.
  bool crossCheck = true;
  // Windowed matching only: |query octave - train octave| <= this (negative: any octave).
  int maxOctaveDifference = 1;
  // Windowed matching only: apply the rotation-consistency histogram (rotation_histogram.h).
  bool checkRotation = false;
};

// Throws Error if the descriptors are not CV_8UC1 with 32 columns.
std::vector<cv::DMatch> matchBruteForce(const cv::Mat& query, const cv::Mat& train,
                                        const MatchOptions& options = {});

// Candidates for query i are the train features within a square window of half-size `radius`
// around query keypoint i (trainGrid.featuresInArea), train descriptors in grid order.
std::vector<cv::DMatch> matchInWindow(const std::vector<cv::KeyPoint>& queryKeypoints,
                                      const cv::Mat& queryDescriptors, const FeatureGrid& trainGrid,
                                      const cv::Mat& trainDescriptors, float radius,
                                      const MatchOptions& options = {});

// Throws Error naming `what` unless `descriptors` is CV_8UC1 with 32 columns and, when
// expectedRows >= 0, that many rows.
void checkDescriptors(const cv::Mat& descriptors, const char* what, int expectedRows = -1);

}  // namespace lumaslam::feature
