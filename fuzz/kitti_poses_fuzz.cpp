// KITTI ground truth (poses/XX.txt, 12 numbers per line) timed by the sequence's times.txt,
// as `KittiReader::readGroundTruth` reads them. The bytes up to the first NUL are the poses,
// the rest times.txt (all of them both, without a NUL).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "input_file.h"
#include "lumaslam/io/kitti_reader.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto split = bytes.find('\0');
  const std::string_view poses = bytes.substr(0, split);
  const std::string_view times = split == std::string_view::npos ? bytes : bytes.substr(split + 1);
  const lumaslam::fuzz::InputFile poses_file("kitti/poses/00.txt", poses);
  const lumaslam::fuzz::InputFile times_file("kitti/sequences/00/times.txt", times);
  lumaslam::fuzz::parseOrReject([&] {
    lumaslam::io::KittiReader::readGroundTruth(times_file.path().parent_path(), poses_file.path());
  });
  return 0;
}
