#pragma once
// Stereo correspondences of a rectified pair, as ORB-SLAM's Frame::ComputeStereoMatches:
// for each left ORB feature, the right features in its row band (widened by the scale of
// their level) and disparity range [0, bf / minDepth] at an adjacent pyramid level are
// compared by Hamming distance; the best one under the threshold is refined by SAD patch
// correlation along the row on the left feature's level with a parabola fit, and matches
// whose SAD distance is far above the median are dropped. Gives the right column u_r and the
// depth z = bf / (u_l - u_r) per left feature. Beyond ORB-SLAM: a left feature with two
// similar candidates at clearly different columns (repeated texture) is left unmatched.
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "lumaslam/feature/hamming.h"
#include "lumaslam/feature/orb_extractor.h"

namespace lumaslam::feature {

struct StereoMatcherParams {
  double bf = 0.0;        // baseline (m) * fx (px) of the rectified pair
  double minDepth = 0.0;  // metres; maxDisparity = bf / minDepth (ORB-SLAM: the baseline)
  int maxDescriptorDistance = (kThHigh + kThLow) / 2;
  // Ambiguity: unmatched if a candidate more than 2 * scale px away from the best one has a
  // distance <= best / ambiguityRatio. 1 keeps ORB-SLAM's behaviour (no check).
  float ambiguityRatio = 0.9F;
  float rowBand = 2.0F;                 // a right feature covers rows v +- rowBand * scale(level)
  int patchRadius = 5;                  // SAD window (2w+1)^2 on the pyramid level
  int searchRadius = 5;                 // SAD search +-L pixels along the row on that level
  double sadOutlierFactor = 1.5 * 1.4;  // drop matches with SAD >= factor * median SAD
};

struct StereoMatches {
  std::vector<float> uRight;  // per left feature, level-0 pixels; -1 if unmatched
  std::vector<float> depth;   // per left feature, metres; -1 if unmatched
  int matched = 0;
};

class StereoMatcher {
 public:
  // Throws Error if bf or minDepth is not positive.
  StereoMatcher(const StereoMatcherParams& params, const ScaleLevels& levels);

  // `left` and `right` from the same OrbExtractor on the two rectified images (their pyramids
  // are used for the SAD refinement). Thread-safe.
  StereoMatches match(const OrbFeatures& left, const OrbFeatures& right) const;

  const StereoMatcherParams& params() const { return params_; }
  double maxDisparity() const { return params_.bf / params_.minDepth; }

 private:
  // Sub-pixel right column (level-0 px) of left feature `kpL` around right column `uR0`,
  // and its SAD distance; false if the window leaves the image or the minimum is at the edge.
  bool refineBySad(const OrbFeatures& left, const OrbFeatures& right, const cv::KeyPoint& kpL,
                   float uR0, float& uRight, int& sad) const;
  // Right column (level-0 px) of the best right feature for left feature iL among `rowBand`
  // (the right features covering its row): adjacent level, disparity in [0, maxDisparity],
  // Hamming distance under the threshold, no similar candidate elsewhere on the row.
  // `candidates` is scratch space.
  std::optional<float> bestRightColumn(const OrbFeatures& left, const OrbFeatures& right,
                                       std::size_t iL, const std::vector<int>& rowBand,
                                       double maxDisparity,
                                       std::vector<std::pair<int, float>>& candidates) const;

  StereoMatcherParams params_;
  ScaleLevels levels_;
};

}  // namespace lumaslam::feature
