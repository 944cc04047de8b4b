// Trajectory files (`eval`, ground truth): format detection, then TUM / EuRoC csv / KITTI
// parsing of the same bytes, and KITTI times.txt.
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/io/trajectory_io.h"
#include "rejected_input.h"

namespace {

void parseAs(const std::filesystem::path& file, lumaslam::io::TrajectoryFormat format) {
  lumaslam::fuzz::parseOrReject([&] { lumaslam::io::readTrajectory(file, format); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using lumaslam::io::TrajectoryFormat;
  const lumaslam::fuzz::InputFile input("trajectory.txt", data, size);
  for (const auto format : {TrajectoryFormat::Auto, TrajectoryFormat::Tum,
                            TrajectoryFormat::EurocCsv, TrajectoryFormat::Kitti})
    parseAs(input.path(), format);
  lumaslam::fuzz::parseOrReject([&] { lumaslam::io::readTimestamps(input.path()); });
  return 0;
}
