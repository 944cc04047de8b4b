#include "lumaslam/track/frame_builder.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::track {

FrameBuilder::FrameBuilder(const FrameCamera& camera, const feature::OrbSettings& orb)
    : camera_(camera),
      extractor_(orb),
      pyramid_(std::make_shared<const map::ScalePyramid>(
          map::ScalePyramid::make(orb.nLevels, orb.scaleFactor))),
      bounds_(camera.undistortedBounds()) {}

Frame FrameBuilder::build(std::size_t index, double timestamp, const cv::Mat& gray,
                          const cv::Mat& depth_m, const cv::Mat& mask) const {
  if (gray.type() != CV_8UC1) fail("frame {}: expected an 8-bit gray image", index);
  if (gray.size() != camera_.size) {
    fail("frame {}: image is {}x{}, the settings say {}x{}", index, gray.cols, gray.rows,
         camera_.size.width, camera_.size.height);
  }
  if (!depth_m.empty() && (depth_m.type() != CV_32FC1 || depth_m.size() != gray.size())) {
    fail("frame {}: depth must be CV_32FC1 metres of the image size", index);
  }
  auto extracted = extractor_.extract(gray, mask);
  auto features = std::make_shared<map::FeatureSet>();
  features->keypoints = std::move(extracted.keypoints);
  features->descriptors = extracted.descriptors;
  const std::size_t n = features->keypoints.size();

  std::vector<cv::Point2f> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = features->keypoints[i].pt;
  if (camera_.hasDistortion() && n > 0) {
    cv::undistortPoints(points, points, camera_.K(), cv::Mat(camera_.distortion), cv::noArray(),
                        camera_.K());
  }
  features->undistorted = points;

  features->depth.assign(n, -1.0F);
  features->u_right.assign(n, -1.0F);
  if (!depth_m.empty() && camera_.bf > 0.0) {
    for (std::size_t i = 0; i < n; ++i) {
      const auto& kp = features->keypoints[i].pt;
      const int row = std::clamp(cvRound(kp.y), 0, depth_m.rows - 1);
      const int col = std::clamp(cvRound(kp.x), 0, depth_m.cols - 1);
      const float z = depth_m.at<float>(row, col);
      if (std::isfinite(z) && z > 0.0F) {
        features->depth[i] = z;
        features->u_right[i] = points[i].x - static_cast<float>(camera_.bf) / z;
      }
    }
  }

  std::vector<cv::KeyPoint> undistorted_keypoints = features->keypoints;
  for (std::size_t i = 0; i < n; ++i) undistorted_keypoints[i].pt = points[i];
  features->grid =
      std::make_shared<const feature::FeatureGrid>(std::move(undistorted_keypoints), bounds_);

  Frame frame;
  frame.index = index;
  frame.timestamp = timestamp;
  frame.features = std::move(features);
  frame.clearMatches();
  return frame;
}

}  // namespace lumaslam::track
