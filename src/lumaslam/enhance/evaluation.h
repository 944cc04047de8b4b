#pragma once
// Measurements behind the choice of defaults (docs/enhancement.md): each candidate turns an
// input image into the gray image ORB sees; candidates are scored on real exposure pairs and
// on real frames darkened with a known model.
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/enhance/enhancer_params.h"
#include "lumaslam/enhance/feature_benefit.h"

namespace lumaslam::enhance {

struct Candidate {
  std::string name;
  std::function<cv::Mat(const cv::Mat& image)> to_gray;  // image: 8-bit gray or BGR
};

Candidate rawCandidate();                           // plain gray conversion
Candidate openCvClaheCandidate(double clip_limit);  // cv::CLAHE 8x8 on the gray image
Candidate enhancerCandidate(const std::string& name, const EnhancerParams& params);

// raw, cv::CLAHE 8x8 with clip 2/4/8/12/40, then every preset.
std::vector<Candidate> standardCandidates();

struct PairScore {
  std::string candidate;
  long correct = 0;  // summed over pairs
  long matches = 0;
  long keypoints = 0;                 // on the enhanced dark images
  std::vector<int> correct_per_pair;  // in pair order
};

// For each pair: ORB on candidate(dark) and on gray(bright), correct matches (feature_benefit.h).
std::vector<PairScore> evaluateExposurePairs(const std::vector<ExposurePair>& pairs,
                                             const std::vector<Candidate>& candidates,
                                             const MatchMetricParams& metric = {});

// Dark model on 8-bit images: V_out = A * V_in^(1/gamma) + N(0, noise_std), in [0, 1] units
// for V (gray input: the image; colour: scaled by V_out/V_in like the HSV rebuild).
struct DarkeningLevel {
  double gain = 0.3;   // A
  double gamma = 0.6;  // < 1 darkens mid-tones further
  double noise_std = 0.01;
};
cv::Mat darken(const cv::Mat& image, const DarkeningLevel& level, int seed);

struct SequenceScore {
  std::string candidate;
  double keypoints = 0.0;  // mean per frame
  double coverage = 0.0;   // mean fraction of 8x8 cells with a keypoint
  double inliers = 0.0;    // mean correct matches against the un-darkened frame (raw gray)
};

// Darkens every frame, enhances it with each candidate and compares with the original frame.
std::vector<SequenceScore> evaluateDarkened(const std::vector<cv::Mat>& frames,
                                            const DarkeningLevel& level,
                                            const std::vector<Candidate>& candidates,
                                            const MatchMetricParams& metric = {});

}  // namespace lumaslam::enhance
