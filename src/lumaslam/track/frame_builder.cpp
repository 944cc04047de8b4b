#include "lumaslam/track/frame_builder.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/core/side_job.h"

namespace lumaslam::track {
namespace {

std::optional<feature::StereoMatcher> stereoMatcherFor(const FrameCamera& camera,
                                                       const feature::ScaleLevels& levels) {
  if (!(camera.bf > 0.0)) return std::nullopt;
  feature::StereoMatcherParams params;
  params.bf = camera.bf;
  params.minDepth = camera.bf / camera.pinhole.fx();  // ORB-SLAM: nothing closer than one baseline
  return feature::StereoMatcher(params, levels);
}

}  // namespace

FrameBuilder::FrameBuilder(const FrameCamera& camera, const feature::OrbSettings& orb,
                           bool threaded)
    : camera_(camera),
      extractor_(orb),
      stereo_matcher_(stereoMatcherFor(camera, extractor_.levels())),
      pyramid_(std::make_shared<const feature::ScaleLevels>(extractor_.levels())),
      bounds_(camera.pinhole.undistortedBounds()),
      threaded_(threaded) {}

void FrameBuilder::checkImage(std::size_t index, const cv::Mat& gray, const char* what) const {
  if (gray.type() != CV_8UC1) fail("frame {}: expected an 8-bit gray {}", index, what);
  if (gray.size() != camera_.size()) {
    fail("frame {}: {} is {}x{}, the settings say {}x{}", index, what, gray.cols, gray.rows,
         camera_.size().width, camera_.size().height);
  }
}

std::shared_ptr<map::FeatureSet> FrameBuilder::featureSetFrom(
    feature::OrbFeatures&& extracted) const {
  auto features = std::make_shared<map::FeatureSet>();
  features->keypoints = std::move(extracted.keypoints);
  features->descriptors = extracted.descriptors;
  const std::size_t n = features->keypoints.size();

  std::vector<cv::Point2f> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = features->keypoints[i].pt;
  features->undistorted = camera_.pinhole.undistortPoints(points);
  features->depth.assign(n, -1.0F);
  features->u_right.assign(n, -1.0F);
  return features;
}

Frame FrameBuilder::frameFrom(std::size_t index, double timestamp,
                              std::shared_ptr<map::FeatureSet> features) const {
  std::vector<cv::KeyPoint> undistorted_keypoints = features->keypoints;
  for (std::size_t i = 0; i < features->size(); ++i) {
    undistorted_keypoints[i].pt = features->undistorted[i];
  }
  features->grid =
      std::make_shared<const feature::FeatureGrid>(std::move(undistorted_keypoints), bounds_);

  Frame frame;
  frame.index = index;
  frame.timestamp = timestamp;
  frame.features = std::move(features);
  frame.clearMatches();
  return frame;
}

Frame FrameBuilder::build(std::size_t index, double timestamp, const cv::Mat& gray,
                          const cv::Mat& depth_m, const cv::Mat& mask) const {
  checkImage(index, gray, "image");
  if (!depth_m.empty() && (depth_m.type() != CV_32FC1 || depth_m.size() != gray.size())) {
    fail("frame {}: depth must be CV_32FC1 metres of the image size", index);
  }
  auto features = featureSetFrom(extractor_.extract(gray, mask));
  if (!depth_m.empty() && camera_.bf > 0.0) {
    for (std::size_t i = 0; i < features->size(); ++i) {
      const auto& kp = features->keypoints[i].pt;
      const int row = std::clamp(cvRound(kp.y), 0, depth_m.rows - 1);
      const int col = std::clamp(cvRound(kp.x), 0, depth_m.cols - 1);
      const float z = depth_m.at<float>(row, col);
      if (std::isfinite(z) && z > 0.0F) {
        features->depth[i] = z;
        features->u_right[i] = features->undistorted[i].x - static_cast<float>(camera_.bf) / z;
      }
    }
  }
  return frameFrom(index, timestamp, std::move(features));
}

Frame FrameBuilder::buildStereo(std::size_t index, double timestamp, const cv::Mat& left,
                                const cv::Mat& right, const cv::Mat& mask) const {
  if (!stereo_matcher_ || camera_.pinhole.hasDistortion()) {
    fail("frame {}: stereo frames need a rectified camera (no distortion) with bf > 0", index);
  }
  checkImage(index, left, "left image");
  checkImage(index, right, "right image");
  // The right image's features are only matched against the (masked) left ones: no mask.
  auto right_job = core::startSideJob(threaded_, [&] { return extractor_.extract(right); });
  auto extracted_left = extractor_.extract(left, mask);
  const auto extracted_right = right_job.get();
  const auto matches = stereo_matcher_->match(extracted_left, extracted_right);

  auto features = featureSetFrom(std::move(extracted_left));
  features->depth = matches.depth;
  features->u_right = matches.uRight;
  return frameFrom(index, timestamp, std::move(features));
}

}  // namespace lumaslam::track
