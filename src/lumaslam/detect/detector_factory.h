#pragma once
#include <memory>

#include "lumaslam/detect/detector.h"
#include "lumaslam/detect/detector_params.h"

namespace lumaslam::detect {

// YoloDetector or BoxFileDetector according to params.type.
std::unique_ptr<Detector> makeDetector(const DetectorParams& params);

}  // namespace lumaslam::detect
