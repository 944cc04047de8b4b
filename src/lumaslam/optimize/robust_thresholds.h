#pragma once
// Chi-square thresholds at 95% for 2 (mono) and 3 (stereo) degrees of freedom, as in
// ORB-SLAM: an observation with invSigma2 * |error|^2 above them is an outlier, and the Huber
// kernel's delta is their square root.
#include <cmath>

namespace lumaslam::optimize {

inline constexpr double kChi2Mono = 5.991;
inline constexpr double kChi2Stereo = 7.815;

struct RobustThresholds {
  double chi2Mono = kChi2Mono;
  double chi2Stereo = kChi2Stereo;
  double huberDeltaMono() const { return std::sqrt(chi2Mono); }
  double huberDeltaStereo() const { return std::sqrt(chi2Stereo); }
};

}  // namespace lumaslam::optimize
