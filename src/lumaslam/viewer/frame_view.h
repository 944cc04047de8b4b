#pragma once
// What the tracking thread hands the viewer for one frame: plain values and image headers, so
// that handing over costs no drawing or encoding (done when a page asks for the picture).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace lumaslam::viewer {

struct StageTimes {  // milliseconds, as in timing.csv
  double enhance = 0, features = 0, tracking = 0, mapping = 0, detection_wait = 0, total = 0;
};

struct FrameView {
  std::size_t index = 0;
  double timestamp = 0.0;
  std::string state;  // "ok", "lost", ... (track::toString)
  std::string step;   // which tracking step succeeded
  int inliers = 0;
  bool keyframe = false;
  bool relocalized = false;
  int map = 0;
  std::optional<Eigen::Vector3d> camera_centre;  // world, when tracked
  cv::Mat raw;                       // the image as read (gray or BGR); owned by the view
  cv::Mat features_image;            // the gray image features were taken from (enhanced)
  cv::Mat right;                     // stereo: the right image as read, owned; else empty
  bool overlays_fit_raw = true;      // keypoints are in raw's pixels (not a rectified pair)
  std::vector<cv::Point2f> kept;     // keypoints used for tracking
  std::vector<cv::Point2f> dropped;  // keypoints removed as dynamic
  std::vector<cv::Rect2f> boxes;     // detections
  cv::Mat dynamic_mask;              // CV_8U, nonzero where features were not taken
  int moving_features = 0;
  StageTimes timing;
};

}  // namespace lumaslam::viewer
