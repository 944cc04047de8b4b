// TUM RGB-D index files (rgb.txt, depth.txt) and their timestamp association. The bytes up
// to the first NUL are rgb.txt, the rest depth.txt (all of them both, without a NUL).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <spdlog/spdlog.h>

#include "input_file.h"
#include "lumaslam/io/tum_rgbd_reader.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = (spdlog::set_level(spdlog::level::off), true);
  (void)quiet;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto split = bytes.find('\0');
  const std::string_view rgb = bytes.substr(0, split);
  const std::string_view depth = split == std::string_view::npos ? bytes : bytes.substr(split + 1);
  const lumaslam::fuzz::InputFile rgb_file("tum/rgb.txt", rgb);
  const lumaslam::fuzz::InputFile depth_file("tum/depth.txt", depth);
  lumaslam::fuzz::parseOrReject(
      [&] { lumaslam::io::TumRgbdReader reader(rgb_file.path().parent_path(), true, {}); });
  return 0;
}
