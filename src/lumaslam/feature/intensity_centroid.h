#pragma once
// Keypoint orientation by intensity centroid (Rosin 1999, ORB section 3.2): the angle of
// the vector from the keypoint to the centroid of the intensities on a circular patch.
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::feature {

inline constexpr int kPatchSize = 31;
inline constexpr int kHalfPatchSize = kPatchSize / 2;

class IntensityCentroid {
 public:
  IntensityCentroid();

  // Angle in degrees [0, 360) of the patch centred on the rounded `point`; image coordinates
  // (y down). The caller keeps the patch (radius 15) inside `image` (CV_8UC1).
  float angle(const cv::Mat& image, cv::Point2f point) const;

 private:
  // rowHalfWidth_[v]: half-width of the circular patch at row offset v, made symmetric so the
  // disc is identical when transposed (as ORB/ORB-SLAM's umax table).
  std::vector<int> rowHalfWidth_;
};

}  // namespace lumaslam::feature
