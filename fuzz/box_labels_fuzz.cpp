// Ground-truth boxes of `detect --eval`: box lists ("image class x1 y1 x2 y2" per line) and
// Pascal VOC XML annotations, both parsers on the same bytes.
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/detect/box_labels.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lumaslam::fuzz::InputFile input("labels.txt", data, size);
  lumaslam::fuzz::parseOrReject([&] { lumaslam::detect::readBoxList(input.path()); });
  lumaslam::fuzz::parseOrReject([&] { lumaslam::detect::readVocAnnotation(input.path()); });
  return 0;
}
