#pragma once
// Per-level scale of the ORB image pyramid (ORB-SLAM's mvScaleFactor / mvLevelSigma2): level l
// is the image shrunk by scaleFactor^l. Extraction, matching, keyframes and map points share one.
// sigma2(l) = scale(l)^2 is the keypoint position variance (in level-0 pixels²) that
// reprojection-error chi² tests divide by.
#include <cmath>
#include <vector>

namespace lumaslam::feature {

class ScaleLevels {
 public:
  ScaleLevels(int nLevels, float scaleFactor);

  int count() const { return static_cast<int>(scale_.size()); }
  float scaleFactor() const { return scaleFactor_; }
  double logScaleFactor() const { return std::log(static_cast<double>(scaleFactor_)); }
  float scale(int level) const { return scale_.at(level); }
  float inverseScale(int level) const { return inverseScale_.at(level); }
  float sigma2(int level) const { return sigma2_.at(level); }
  float inverseSigma2(int level) const { return inverseSigma2_.at(level); }
  const std::vector<float>& scales() const { return scale_; }
  const std::vector<float>& sigma2s() const { return sigma2_; }

  // Feature budget per level: a geometric series with ratio 1/scaleFactor that sums to
  // `total` (smaller levels have less area, so fewer features), as ORB-SLAM distributes them.
  std::vector<int> featureBudget(int total) const;

 private:
  float scaleFactor_;
  std::vector<float> scale_, inverseScale_, sigma2_, inverseSigma2_;
};

}  // namespace lumaslam::feature
