// Class-name files (`Detector.names`, coco80.names): one name per line, line i = class id i;
// then the ids of the classes a detector is asked for (`Detector.classes`).
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/detect/class_names.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lumaslam::fuzz::InputFile input("classes.names", data, size);
  lumaslam::fuzz::parseOrReject([&] {
    const auto names = lumaslam::detect::readClassNames(input.path());
    lumaslam::detect::classIds(names, {"person", "car"}, input.path().string());
  });
  return 0;
}
