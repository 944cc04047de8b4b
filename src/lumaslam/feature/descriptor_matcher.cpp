#include "lumaslam/feature/descriptor_matcher.h"

#include <limits>

#include <opencv2/features2d.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/feature/rotation_histogram.h"

namespace lumaslam::feature {

namespace {

struct Candidate {
  int index = -1;
  int distance = std::numeric_limits<int>::max();
};

}  // namespace

void checkDescriptors(const cv::Mat& descriptors, const char* what, int expectedRows) {
  if (descriptors.empty() && expectedRows <= 0) return;
  if (descriptors.type() != CV_8UC1 || descriptors.cols != kDescriptorBytes) {
    fail("{}: descriptors must be CV_8UC1 with {} columns, got type {} with {} columns", what,
         kDescriptorBytes, descriptors.type(), descriptors.cols);
  }
  if (expectedRows >= 0 && descriptors.rows != expectedRows) {
    fail("{}: expected {} descriptor rows (one per keypoint), got {}", what, expectedRows,
         descriptors.rows);
  }
}

std::vector<cv::DMatch> matchBruteForce(const cv::Mat& query, const cv::Mat& train,
                                        const MatchOptions& options) {
  checkDescriptors(query, "matchBruteForce query");
  checkDescriptors(train, "matchBruteForce train");
  if (query.empty() || train.empty()) return {};
  const cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> forward;
  matcher.knnMatch(query, train, forward, 2);
  std::vector<cv::DMatch> backward;
  if (options.crossCheck) matcher.match(train, query, backward);

  std::vector<cv::DMatch> matches;
  for (const auto& nearest : forward) {
    if (nearest.empty()) continue;
    const cv::DMatch& best = nearest[0];
    if (best.distance > options.maxDistance) continue;
    if (nearest.size() > 1 && options.ratio < 1.0f &&
        best.distance >= options.ratio * nearest[1].distance) {
      continue;
    }
    if (options.crossCheck && backward[best.trainIdx].trainIdx != best.queryIdx) continue;
    matches.push_back(best);
  }
  return matches;
}

std::vector<cv::DMatch> matchInWindow(const std::vector<cv::KeyPoint>& queryKeypoints,
                                      const cv::Mat& queryDescriptors, const FeatureGrid& trainGrid,
                                      const cv::Mat& trainDescriptors, float radius,
                                      const MatchOptions& options) {
  const int queryCount = static_cast<int>(queryKeypoints.size());
  const int trainCount = static_cast<int>(trainGrid.keypoints().size());
  checkDescriptors(queryDescriptors, "matchInWindow query", queryCount);
  checkDescriptors(trainDescriptors, "matchInWindow train", trainCount);

  std::vector<Candidate> bestForQuery(queryCount);
  std::vector<Candidate> bestForTrain(trainCount);
  for (int q = 0; q < queryCount; ++q) {
    const cv::KeyPoint& keypoint = queryKeypoints[q];
    const int tolerance = options.maxOctaveDifference;
    const int minLevel = tolerance < 0 ? -1 : std::max(0, keypoint.octave - tolerance);
    const int maxLevel = tolerance < 0 ? -1 : keypoint.octave + tolerance;
    Candidate best;
    int secondDistance = std::numeric_limits<int>::max();
    for (const std::size_t t : trainGrid.featuresInArea(keypoint.pt, radius, minLevel, maxLevel)) {
      const int distance =
          hammingDistance(queryDescriptors, q, trainDescriptors, static_cast<int>(t));
      if (distance < best.distance) {
        secondDistance = best.distance;
        best = {static_cast<int>(t), distance};
      } else if (distance < secondDistance) {
        secondDistance = distance;
      }
      if (distance < bestForTrain[t].distance) bestForTrain[t] = {q, distance};
    }
    if (best.index < 0 || best.distance > options.maxDistance) continue;
    if (options.ratio < 1.0f && secondDistance != std::numeric_limits<int>::max() &&
        best.distance >= options.ratio * secondDistance) {
      continue;
    }
    bestForQuery[q] = best;
  }

  std::vector<cv::DMatch> matches;
  for (int q = 0; q < queryCount; ++q) {
    const Candidate& best = bestForQuery[q];
    if (best.index < 0) continue;
    if (options.crossCheck && bestForTrain[best.index].index != q) continue;
    matches.emplace_back(q, best.index, static_cast<float>(best.distance));
  }
  if (options.checkRotation) {
    matches = filterByRotationConsistency(matches, queryKeypoints, trainGrid.keypoints());
  }
  return matches;
}

}  // namespace lumaslam::feature
