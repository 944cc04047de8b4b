// Map files (`run --map`, `map info`): header, size, checksum, then the cereal archive and
// its structure check.
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/map/map_file.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lumaslam::fuzz::InputFile input("fuzz.map", data, size);
  lumaslam::fuzz::parseOrReject([&] { lumaslam::map::readMapFileInfo(input.path()); });
  return 0;
}
