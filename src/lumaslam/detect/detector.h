#pragma once
// What the tracker needs from any object detector: the boxes of one frame.
#include "lumaslam/detect/detection.h"

namespace lumaslam::detect {

class Detector {
 public:
  virtual ~Detector() = default;

  // Detections in `image` (8-bit BGR or gray) for the frame taken at `timestamp` [s].
  // Image-based detectors ignore the timestamp; file-based ones use only the timestamp.
  // Not thread-safe: one caller at a time (DetectionWorker owns its detector).
  virtual Detections detect(const cv::Mat& image, double timestamp) = 0;

  // Short description for logs ("yolo yolov5n.onnx 640x640").
  virtual std::string describe() const = 0;
};

}  // namespace lumaslam::detect
