// KITTI calib.txt (P0..P3 projection matrices).
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/io/kitti_reader.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lumaslam::fuzz::InputFile input("calib.txt", data, size);
  lumaslam::fuzz::parseOrReject([&] { lumaslam::io::KittiReader::readCalibration(input.path()); });
  return 0;
}
