#pragma once
// YOLOv5 (any export with the standard 1 x N x (5 + C) output) through OpenCV DNN.
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

#include "lumaslam/detect/detector.h"
#include "lumaslam/detect/detector_params.h"
#include "lumaslam/detect/yolo_output.h"

namespace lumaslam::detect {

class YoloDetector : public Detector {
 public:
  // Loads params.model and params.namesPath(); throws Error naming the file when either is
  // missing or invalid, when the model is not a square image model, or when a class of
  // params.classes is not in the names. params.threads > 0 calls cv::setNumThreads (global
  // to the process: OpenCV has one thread pool).
  explicit YoloDetector(const DetectorParams& params);

  // 8-bit BGR, BGRA or gray; throws Error for anything else.
  Detections detect(const cv::Mat& image, double timestamp) override;
  std::string describe() const override;

  int inputSize() const { return input_size_; }
  const std::vector<std::string>& classNames() const { return names_; }

 private:
  std::filesystem::path model_path_;
  cv::dnn::Net net_;
  int input_size_ = 0;
  std::vector<std::string> names_;
  YoloDecodeParams decode_;
  std::vector<std::string> output_names_;
};

}  // namespace lumaslam::detect
