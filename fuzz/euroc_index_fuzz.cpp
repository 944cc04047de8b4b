// EuRoC mav0/camN/data.csv image lists ("timestamp_ns,filename") and the stereo pairing by
// equal timestamps. The bytes up to the first NUL are cam0/data.csv, the rest cam1/data.csv
// (all of them both, without a NUL); both sensor.yaml files are a fixed valid one.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <spdlog/spdlog.h>

#include "input_file.h"
#include "lumaslam/io/euroc_reader.h"
#include "rejected_input.h"

namespace {

constexpr std::string_view kSensorYaml =
    "%YAML:1.0\n"
    "T_BS:\n"
    "  cols: 4\n"
    "  rows: 4\n"
    "  data: [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]\n"
    "rate_hz: 20\n"
    "resolution: [752, 480]\n"
    "camera_model: pinhole\n"
    "intrinsics: [458.654, 457.296, 367.215, 248.375]\n"
    "distortion_model: radial-tangential\n"
    "distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]\n";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = (spdlog::set_level(spdlog::level::off), true);
  (void)quiet;
  static const lumaslam::fuzz::InputFile cam0_yaml("euroc/mav0/cam0/sensor.yaml", kSensorYaml);
  static const lumaslam::fuzz::InputFile cam1_yaml("euroc/mav0/cam1/sensor.yaml", kSensorYaml);
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto split = bytes.find('\0');
  const std::string_view cam0 = bytes.substr(0, split);
  const std::string_view cam1 = split == std::string_view::npos ? bytes : bytes.substr(split + 1);
  const lumaslam::fuzz::InputFile cam0_list("euroc/mav0/cam0/data.csv", cam0);
  const lumaslam::fuzz::InputFile cam1_list("euroc/mav0/cam1/data.csv", cam1);
  const auto root = lumaslam::fuzz::scratchFolder() / "euroc";
  for (const bool stereo : {false, true})
    lumaslam::fuzz::parseOrReject([&] { lumaslam::io::EurocReader reader(root, stereo, {}); });
  return 0;
}
