#include <gtest/gtest.h>

#include <fstream>

#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "test_paths.h"

using lumaslam::Error;
using lumaslam::core::SettingsFile;

namespace {

const char* kOrbSlamStyle = R"(%YAML:1.0
Camera.type: "PinHole"
Camera.fx: 535.4
Camera.width: 640
Camera.RGB: 1
ORBextractor.nFeatures: 1000
Enhancement:
   preset: "best"
Stereo.T_c1_c2: !!opencv-matrix
   rows: 4
   cols: 4
   dt: f
   data: [1.0, 0.0, 0.0, 0.11, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0, 0, 0, 1.0]
)";

TEST(SettingsFile, ReadsFlatAndNestedKeysWithTypes) {
  const auto s = SettingsFile::fromString(kOrbSlamStyle, "test.yaml");
  EXPECT_DOUBLE_EQ(s.get<double>("Camera.fx"), 535.4);
  EXPECT_EQ(s.get<int>("Camera.width"), 640);
  EXPECT_DOUBLE_EQ(s.get<double>("Camera.width"), 640.0);
  EXPECT_TRUE(s.get<bool>("Camera.RGB"));
  EXPECT_EQ(s.get<std::string>("Camera.type"), "PinHole");
  EXPECT_EQ(s.get<std::string>("Enhancement.preset"), "best");
  EXPECT_EQ(s.get<int>("ORBextractor.nLevels", 8), 8);
  const cv::Mat T = s.getMatrix("Stereo.T_c1_c2", 4, 4);
  EXPECT_EQ(T.type(), CV_64F);
  EXPECT_NEAR(T.at<double>(0, 3), 0.11, 1e-6);
}

TEST(SettingsFile, ErrorsNameFileKeyAndExpectedType) {
  const auto s = SettingsFile::fromString(kOrbSlamStyle, "test.yaml");
  try {
    (void)s.get<double>("Camera.fy");
    FAIL() << "missing key accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.yaml"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("Camera.fy"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("number"), std::string::npos);
  }
  EXPECT_THROW((void)s.get<double>("Camera.type"), Error);    // string where number expected
  EXPECT_THROW((void)s.get<int>("Camera.fx"), Error);         // 535.4 is no integer
  EXPECT_THROW((void)s.get<int>("Camera.type", 3), Error);    // present but wrong type
  EXPECT_THROW((void)s.getMatrix("Stereo.T_c1_c2", 3, 3), Error);
}

TEST(SettingsFile, MissingOrBrokenFileIsAClearError) {
  lumaslam::test::TempDir dir("settings");
  EXPECT_THROW((void)SettingsFile::open(dir.path() / "nope.yaml"), Error);
  const auto broken = dir.path() / "broken.yaml";
  std::ofstream(broken) << "%YAML:1.0\nCamera.fx: [1, 2\n  : :\n";
  try {
    (void)SettingsFile::open(broken);
    FAIL() << "broken YAML accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.yaml"), std::string::npos);
  }
}

}  // namespace
