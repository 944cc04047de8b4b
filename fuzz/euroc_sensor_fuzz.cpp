// EuRoC mav0/camN/sensor.yaml (intrinsics, distortion, resolution, T_BS).
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/io/euroc_sensor_yaml.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lumaslam::fuzz::InputFile input("sensor.yaml", data, size);
  lumaslam::fuzz::parseOrReject([&] { lumaslam::io::readEurocCameraYaml(input.path()); });
  return 0;
}
