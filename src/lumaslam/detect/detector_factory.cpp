#include "lumaslam/detect/detector_factory.h"

#include "lumaslam/core/error.h"
#include "lumaslam/detect/box_file_detector.h"
#include "lumaslam/detect/yolo_detector.h"

namespace lumaslam::detect {

std::unique_ptr<Detector> makeDetector(const DetectorParams& params) {
  if (params.type == "yolo") return std::make_unique<YoloDetector>(params);
  if (params.type == "box_file") return std::make_unique<BoxFileDetector>(params);
  fail("Detector.type: expected 'yolo' or 'box_file', found '{}'", params.type);
}

}  // namespace lumaslam::detect
