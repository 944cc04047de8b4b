#include "lumaslam/feature/intensity_centroid.h"

#include <cmath>

namespace lumaslam::feature {

IntensityCentroid::IntensityCentroid() : rowHalfWidth_(kHalfPatchSize + 1, 0) {
  const int vmax = static_cast<int>(std::floor(kHalfPatchSize * std::sqrt(2.0) / 2 + 1));
  const int vmin = static_cast<int>(std::ceil(kHalfPatchSize * std::sqrt(2.0) / 2));
  for (int v = 0; v <= vmax; ++v) {
    rowHalfWidth_[v] =
        static_cast<int>(std::lround(std::sqrt(kHalfPatchSize * kHalfPatchSize - v * v)));
  }
  // Rows beyond 45 degrees copy the column extents of the rows below it (disc symmetry).
  for (int v = kHalfPatchSize, v0 = 0; v >= vmin; --v) {
    while (rowHalfWidth_[v0] == rowHalfWidth_[v0 + 1]) ++v0;
    rowHalfWidth_[v] = v0;
    ++v0;
  }
}

float IntensityCentroid::angle(const cv::Mat& image, cv::Point2f point) const {
  const int step = static_cast<int>(image.step1());
  const uchar* center = image.ptr<uchar>(cvRound(point.y)) + cvRound(point.x);
  int m10 = 0;  // first moments: m10 = sum u*I, m01 = sum v*I
  int m01 = 0;
  for (int u = -kHalfPatchSize; u <= kHalfPatchSize; ++u) m10 += u * center[u];
  for (int v = 1; v <= kHalfPatchSize; ++v) {
    int rowDifference = 0;
    const int d = rowHalfWidth_[v];
    for (int u = -d; u <= d; ++u) {
      const int below = center[u + v * step];
      const int above = center[u - v * step];
      rowDifference += below - above;
      m10 += u * (below + above);
    }
    m01 += v * rowDifference;
  }
  return cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));
}

}  // namespace lumaslam::feature
