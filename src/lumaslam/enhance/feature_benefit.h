#pragma once
// How much an enhancement helps ORB: correct matches between an enhanced dark frame and a
// well-exposed frame of the same view (same pixel positions, e.g. tripod exposure pairs).
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::enhance {

struct MatchMetricParams {
  int features = 1000;
  int fast_threshold = 20;
  double max_offset_px = 3.0;  // a match is correct when its keypoints are this close
};

struct OrbFeatures {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

// cv::ORB with the Harris score, `features` keypoints and the FAST threshold of `params`.
OrbFeatures detectOrb(const cv::Mat& gray, const MatchMetricParams& params = {});

struct MatchCount {
  int matches = 0;  // cross-checked Hamming matches
  int correct = 0;  // matches whose keypoint positions differ by < max_offset_px
};

MatchCount countCorrectMatches(const OrbFeatures& a, const OrbFeatures& b,
                               const MatchMetricParams& params = {});

// Fraction of cells of a cells x cells grid that hold at least one keypoint.
double gridCoverage(const std::vector<cv::KeyPoint>& keypoints, cv::Size image, int cells = 8);

// Dark/bright views of one scene, named <scene>_A.* (short exposure) and <scene>_B.* (long)
// as in the MEFB benchmark.
struct ExposurePair {
  std::string scene;
  std::filesystem::path dark;
  std::filesystem::path bright;
};

// Every _A/_B pair under `dir` (recursive, extension and case of the suffix ignored), sorted
// by scene. Throws Error when `dir` is not a folder or holds no pair.
std::vector<ExposurePair> findExposurePairs(const std::filesystem::path& dir);

}  // namespace lumaslam::enhance
