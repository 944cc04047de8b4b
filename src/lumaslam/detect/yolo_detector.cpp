#include "lumaslam/detect/yolo_detector.h"

#include <spdlog/spdlog.h>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/detect/class_names.h"
#include "lumaslam/detect/letterbox.h"
#include "lumaslam/detect/onnx_input_shape.h"

namespace lumaslam::detect {
namespace {

// Square input side from the model's 1x3xHxW input; `configured` (> 0) wins when the model
// leaves the size symbolic, and must agree with it otherwise.
int inputSizeOf(const std::filesystem::path& model, int configured) {
  const auto shape = onnxInputShape(model);
  if (shape.size() != 4 || (shape[1] != 3 && shape[1] != -1)) {
    fail("{}: expected a 1x3xHxW image input, found {} dimensions", model.string(), shape.size());
  }
  const auto height = shape[2];
  const auto width = shape[3];
  if (height > 0 && width > 0) {
    if (height != width) fail("{}: input {}x{} is not square", model.string(), width, height);
    if (configured > 0 && configured != height) {
      fail("{}: model input is {}x{} but Detector.inputSize is {}", model.string(), width, height,
           configured);
    }
    return static_cast<int>(height);
  }
  if (configured <= 0)
    fail("{}: model input size is dynamic; set Detector.inputSize", model.string());
  return configured;
}

cv::dnn::Net loadNet(const std::filesystem::path& model) {
  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromONNX(model.string());
  } catch (const cv::Exception& e) {
    fail("{}: OpenCV cannot load the ONNX model: {}", model.string(), e.err);
  }
  if (net.empty()) fail("{}: OpenCV loaded an empty network", model.string());
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  return net;
}

cv::Mat toBgr(const cv::Mat& image) {
  if (image.empty()) fail("YoloDetector: empty image");
  if (image.depth() != CV_8U)
    fail("YoloDetector: expected an 8-bit image, found depth {}", image.depth());
  cv::Mat bgr;
  switch (image.channels()) {
    case 1:
      cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
      return bgr;
    case 3:
      return image;
    case 4:
      cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
      return bgr;
    default:
      fail("YoloDetector: expected 1, 3 or 4 channels, found {}", image.channels());
  }
}

}  // namespace

YoloDetector::YoloDetector(const DetectorParams& params) : model_path_(params.model) {
  // The model's own protobuf is checked first so that a garbage file gives our message.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(model_path_, ec))
    fail("{}: model file not found", model_path_.string());
  input_size_ = inputSizeOf(model_path_, params.input_size);
  net_ = loadNet(model_path_);
  output_names_ = net_.getUnconnectedOutLayersNames();
  if (output_names_.empty()) fail("{}: network has no output", model_path_.string());

  names_ = readClassNames(params.namesPath());
  decode_.confidence_threshold = params.confidence_threshold;
  decode_.nms_threshold = params.nms_threshold;
  decode_.class_ids = classIds(names_, params.classes, params.namesPath().string());
  if (params.threads > 0) cv::setNumThreads(params.threads);

  // One pass on a blank frame checks that output and names agree before the first real frame.
  const cv::Mat blank(input_size_, input_size_, CV_8UC3, cv::Scalar::all(114));
  try {
    detect(blank, 0.0);
  } catch (const Error& e) {
    fail("{}: {}", model_path_.string(), e.what());
  }
  spdlog::info("detector: {}", describe());
}

Detections YoloDetector::detect(const cv::Mat& image, double /*timestamp*/) {
  const Letterboxed boxed = letterbox(toBgr(image), input_size_);
  const cv::Mat blob = cv::dnn::blobFromImage(boxed.image, 1.0 / 255.0, cv::Size(), cv::Scalar(),
                                              /*swapRB=*/true, /*crop=*/false, CV_32F);
  net_.setInput(blob);
  std::vector<cv::Mat> outputs;
  try {
    net_.forward(outputs, output_names_);
  } catch (const cv::Exception& e) {
    fail("{}: inference failed: {}", model_path_.string(), e.err);
  }
  return decodeYoloOutput(outputs.front(), boxed.transform, names_, decode_);
}

std::string YoloDetector::describe() const {
  return fmt::format("yolo {} {}x{}, {} classes", model_path_.filename().string(), input_size_,
                     input_size_, names_.size());
}

}  // namespace lumaslam::detect
