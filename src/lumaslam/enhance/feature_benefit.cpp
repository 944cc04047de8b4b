#include "lumaslam/enhance/feature_benefit.h"

#include <algorithm>
#include <cctype>
#include <map>

#include <opencv2/features2d.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::enhance {

OrbFeatures detectOrb(const cv::Mat& gray, const MatchMetricParams& params) {
  if (gray.type() != CV_8UC1) {
    fail("match metric: expected an 8-bit gray image, got {}", cv::typeToString(gray.type()));
  }
  const auto orb = cv::ORB::create(params.features, 1.2f, 8, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31,
                                   params.fast_threshold);
  OrbFeatures features;
  orb->detectAndCompute(gray, cv::noArray(), features.keypoints, features.descriptors);
  return features;
}

MatchCount countCorrectMatches(const OrbFeatures& a, const OrbFeatures& b,
                               const MatchMetricParams& params) {
  MatchCount count;
  if (a.descriptors.empty() || b.descriptors.empty()) return count;
  std::vector<cv::DMatch> matches;
  cv::BFMatcher(cv::NORM_HAMMING, true).match(a.descriptors, b.descriptors, matches);
  count.matches = static_cast<int>(matches.size());
  for (const auto& match : matches) {
    const cv::Point2f offset = a.keypoints[match.queryIdx].pt - b.keypoints[match.trainIdx].pt;
    if (cv::norm(offset) < params.max_offset_px) ++count.correct;
  }
  return count;
}

double gridCoverage(const std::vector<cv::KeyPoint>& keypoints, cv::Size image, int cells) {
  if (image.empty() || cells < 1) return 0.0;
  cv::Mat occupied(cells, cells, CV_8UC1, cv::Scalar(0));
  for (const auto& keypoint : keypoints) {
    const int cx = std::clamp(static_cast<int>(keypoint.pt.x * cells / image.width), 0, cells - 1);
    const int cy = std::clamp(static_cast<int>(keypoint.pt.y * cells / image.height), 0, cells - 1);
    occupied.at<uchar>(cy, cx) = 1;
  }
  return static_cast<double>(cv::countNonZero(occupied)) / (cells * cells);
}

std::vector<ExposurePair> findExposurePairs(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail("{}: not a folder", dir.string());
  std::map<std::string, ExposurePair> pairs;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string stem = entry.path().stem().string();
    if (stem.size() < 3 || stem[stem.size() - 2] != '_') continue;
    const char side = static_cast<char>(std::toupper(static_cast<unsigned char>(stem.back())));
    if (side != 'A' && side != 'B') continue;
    // Scene = folder name: MEFB spells the two files of a pair differently (FarmHouse_B).
    std::string scene = entry.path().parent_path().lexically_relative(dir).string();
    if (scene.empty() || scene == ".") scene = stem.substr(0, stem.size() - 2);
    auto& pair = pairs[scene];
    pair.scene = scene;
    (side == 'A' ? pair.dark : pair.bright) = entry.path();
  }
  std::vector<ExposurePair> result;
  for (auto& [scene, pair] : pairs) {
    if (!pair.dark.empty() && !pair.bright.empty()) result.push_back(pair);
  }
  if (result.empty()) fail("{}: no <scene>_A / <scene>_B image pairs found", dir.string());
  return result;
}

}  // namespace lumaslam::enhance
