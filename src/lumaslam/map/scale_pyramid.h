#pragma once
// Per-level scale of an image pyramid (ORB-SLAM's mvScaleFactors / mvLevelSigma2): level l is
// the image scaled by 1/scale^l; a keypoint on level l has a position sigma of scale^l pixels.
#include <cmath>
#include <vector>

namespace lumaslam::map {

struct ScalePyramid {
  int levels = 8;
  double factor = 1.2;
  std::vector<double> scale;       // factor^l
  std::vector<double> sigma2;      // scale^2
  std::vector<double> inv_sigma2;  // 1 / sigma2

  static ScalePyramid make(int levels, double factor) {
    ScalePyramid p;
    p.levels = levels;
    p.factor = factor;
    for (int l = 0; l < levels; ++l) {
      p.scale.push_back(std::pow(factor, l));
      p.sigma2.push_back(p.scale.back() * p.scale.back());
      p.inv_sigma2.push_back(1.0 / p.sigma2.back());
    }
    return p;
  }
  double logFactor() const { return std::log(factor); }
};

}  // namespace lumaslam::map
