// Corrupt map files whose counts would make the reader allocate gigabytes (inputs found by
// fuzz/map_file_fuzz.cpp, checksums made right so that only the count is wrong): each is an
// Error naming the file and the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/map/map_file.h"

namespace lumaslam {
namespace {

const std::filesystem::path kRegressions =
    std::filesystem::path(LUMASLAM_SOURCE_DIR) / "fuzz/regressions/map_file";

void expectMapInfoError(const std::filesystem::path& file, const std::string& problem) {
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  const std::string message = test::errorOf([&] { map::readMapFileInfo(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << "for " << file << ": " << message;
  EXPECT_NE(message.find(problem), std::string::npos) << "for " << file << ": " << message;
}

TEST(MapFileCorrupt, LengthBeyondTheBytesLeftIsAnError) {
  // The sensor name's length set to 3 GiB: this allocated 3 GB for 9 s before failing.
  expectMapInfoError(kRegressions / "sensor_length_3GiB.map",
                     "malformed map content (a length field says 3221225472 entries");
}

TEST(MapFileCorrupt, HugeFeatureGridIsAnError) {
  // Grid columns x rows beyond 2^63: std::length_error escaped from loadMapFile.
  expectMapInfoError(kRegressions / "grid_1600483449x1868983913_cells.map",
                     "keyframe 0: feature grid of 1600483449x1868983913 cells");
}

}  // namespace
}  // namespace lumaslam
