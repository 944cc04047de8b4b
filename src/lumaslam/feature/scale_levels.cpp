#include "lumaslam/feature/scale_levels.h"

#include <algorithm>
#include <cmath>

namespace lumaslam::feature {

ScaleLevels::ScaleLevels(int nLevels, float scaleFactor) : scaleFactor_(scaleFactor) {
  float scale = 1.0f;
  for (int level = 0; level < nLevels; ++level) {
    scale_.push_back(scale);
    inverseScale_.push_back(1.0f / scale);
    sigma2_.push_back(scale * scale);
    inverseSigma2_.push_back(1.0f / (scale * scale));
    scale *= scaleFactor;
  }
}

std::vector<int> ScaleLevels::featureBudget(int total) const {
  const int levels = count();
  std::vector<int> budget(levels, 0);
  const double ratio = 1.0 / scaleFactor_;
  double perLevel = total * (1.0 - ratio) / (1.0 - std::pow(ratio, levels));
  int assigned = 0;
  for (int level = 0; level + 1 < levels; ++level) {
    budget[level] = static_cast<int>(std::lround(perLevel));
    assigned += budget[level];
    perLevel *= ratio;
  }
  budget[levels - 1] = std::max(total - assigned, 0);
  return budget;
}

}  // namespace lumaslam::feature
