// Detector box files (`Detector.type: box_file`): "timestamp class x y w h" per line.
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/detect/box_file_detector.h"
#include "lumaslam/detect/detector_params.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Numeric class ids are names' line numbers: 0 person, 1 car.
  static const lumaslam::fuzz::InputFile names("classes.names", "person\ncar\n");
  const lumaslam::fuzz::InputFile input("detections.txt", data, size);
  lumaslam::detect::DetectorParams params;
  params.type = "box_file";
  params.box_file = input.path();
  params.names = names.path();
  lumaslam::fuzz::parseOrReject([&] { const lumaslam::detect::BoxFileDetector detector(params); });
  return 0;
}
