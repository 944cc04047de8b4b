// Length fields of map files are checked against the bytes left before anything is allocated
// (map/bounded_lengths.h): a 2 KB file that claims a 3 GiB string is an Error, not 3 GB of RAM.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "lumaslam/core/error.h"
#include "lumaslam/map/map_file.h"

namespace lumaslam {
namespace {

// fuzz/regressions/map_file: the seed map with its sensor name's length set to 3 GiB (and
// the checksum made right again, so only the length is wrong).
const std::filesystem::path kHugeLength =
    std::filesystem::path(LUMASLAM_SOURCE_DIR) / "fuzz/regressions/map_file/sensor_length_3GiB.map";

TEST(MapFileLengths, LengthBeyondTheFileIsAnErrorNamingFileAndField) {
  ASSERT_TRUE(std::filesystem::exists(kHugeLength));
  try {
    map::readMapFileInfo(kHugeLength);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(kHugeLength.string()), std::string::npos) << message;
    EXPECT_NE(message.find("malformed map content"), std::string::npos) << message;
    EXPECT_NE(message.find("length field says 3221225472 entries"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace lumaslam
