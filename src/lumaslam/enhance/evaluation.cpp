#include "lumaslam/enhance/evaluation.h"

#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/core/gray_image.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/enhance/value_channel.h"

namespace lumaslam::enhance {
namespace {

cv::Mat readColour(const std::filesystem::path& path) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (image.empty()) fail("{}: cannot read image", path.string());
  return image;
}

}  // namespace

Candidate rawCandidate() {
  return {"raw", toGray};
}

Candidate openCvClaheCandidate(double clip_limit) {
  return {fmt::format("cv::CLAHE clip {}", clip_limit), [clip_limit](const cv::Mat& image) {
            cv::Mat out;
            cv::createCLAHE(clip_limit, {8, 8})->apply(toGray(image), out);
            return out;
          }};
}

Candidate enhancerCandidate(const std::string& name, const EnhancerParams& params) {
  return {name, [params](const cv::Mat& image) { return Enhancer(params).enhance(image).gray; }};
}

std::vector<Candidate> standardCandidates() {
  std::vector<Candidate> candidates = {rawCandidate()};
  for (double clip : {2.0, 4.0, 8.0, 12.0, 40.0}) {
    candidates.push_back(openCvClaheCandidate(clip));
  }
  for (const auto& name : EnhancerParams::presetNames()) {
    candidates.push_back(enhancerCandidate(name, EnhancerParams::forPreset(name)));
  }
  return candidates;
}

std::vector<PairScore> evaluateExposurePairs(const std::vector<ExposurePair>& pairs,
                                             const std::vector<Candidate>& candidates,
                                             const MatchMetricParams& metric) {
  std::vector<PairScore> scores(candidates.size());
  for (std::size_t c = 0; c < candidates.size(); ++c) scores[c].candidate = candidates[c].name;
  for (const auto& pair : pairs) {
    const cv::Mat dark = readColour(pair.dark);
    const cv::Mat bright = readColour(pair.bright);
    if (dark.size() != bright.size()) {
      fail("{}: size {}x{} differs from {} ({}x{})", pair.dark.string(), dark.cols, dark.rows,
           pair.bright.string(), bright.cols, bright.rows);
    }
    const OrbFeatures reference = detectOrb(toGray(bright), metric);
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const OrbFeatures features = detectOrb(candidates[c].to_gray(dark), metric);
      const MatchCount count = countCorrectMatches(features, reference, metric);
      scores[c].correct += count.correct;
      scores[c].matches += count.matches;
      scores[c].keypoints += static_cast<long>(features.keypoints.size());
      scores[c].correct_per_pair.push_back(count.correct);
    }
  }
  return scores;
}

cv::Mat darken(const cv::Mat& image, const DarkeningLevel& level, int seed) {
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3)) {
    fail("darken: expected an 8-bit gray or BGR image");
  }
  const cv::Mat value = image.channels() == 1 ? image : valueChannel(image);
  cv::Mat normalised;
  value.convertTo(normalised, CV_32F, 1.0 / 255.0);
  cv::Mat dark;
  cv::pow(normalised, 1.0 / level.gamma, dark);
  dark *= level.gain;
  cv::Mat noise(dark.size(), CV_32F);
  cv::RNG rng(static_cast<uint64_t>(seed));
  rng.fill(noise, cv::RNG::NORMAL, 0.0, level.noise_std);
  dark += noise;
  cv::Mat dark_value;
  dark.convertTo(dark_value, CV_8U, 255.0);
  return image.channels() == 1 ? dark_value : rebuildColour(image, value, dark_value);
}

std::vector<SequenceScore> evaluateDarkened(const std::vector<cv::Mat>& frames,
                                            const DarkeningLevel& level,
                                            const std::vector<Candidate>& candidates,
                                            const MatchMetricParams& metric) {
  std::vector<SequenceScore> scores(candidates.size());
  for (std::size_t c = 0; c < candidates.size(); ++c) scores[c].candidate = candidates[c].name;
  int seed = 0;
  for (const cv::Mat& frame : frames) {
    const OrbFeatures reference = detectOrb(toGray(frame), metric);
    const cv::Mat dark = darken(frame, level, seed++);
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const cv::Mat gray = candidates[c].to_gray(dark);
      const OrbFeatures features = detectOrb(gray, metric);
      scores[c].keypoints += static_cast<double>(features.keypoints.size());
      scores[c].coverage += gridCoverage(features.keypoints, gray.size());
      scores[c].inliers += countCorrectMatches(features, reference, metric).correct;
    }
  }
  const double n = frames.empty() ? 1.0 : static_cast<double>(frames.size());
  for (auto& score : scores) {
    score.keypoints /= n;
    score.coverage /= n;
    score.inliers /= n;
  }
  return scores;
}

}  // namespace lumaslam::enhance
