// Map files whose checksum and structure are right but whose numbers are not (a keypoint outside
// the image or the pyramid, a pose or point that is not finite, unusable ORB settings): each is
// an Error naming the file and the problem, from `map info` and from loading, and nothing is
// loaded. Such files are written here through saveMapFile, which stores what it is given.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map.h"
#include "lumaslam/map/map_file.h"
#include "lumaslam/map/map_point.h"
#include "test_paths.h"

namespace lumaslam {
namespace {

constexpr int kLevels = 8;
constexpr float kScale = 1.2F;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

map::MapFingerprint fingerprintOf640x480() {
  map::MapFingerprint f;
  f.sensor = "rgbd";
  f.image_width = 640;
  f.image_height = 480;
  f.camera = {500.0, 500.0, 320.0, 240.0, 40.0};
  f.orb_features = 1000;
  f.orb_scale_factor = kScale;
  f.orb_levels = kLevels;
  f.orb_ini_fast = 20;
  f.orb_min_fast = 7;
  return f;
}

// Two features (one with a map point 2 m in front of the camera) in a keyframe at the origin.
struct MapParts {
  map::FeatureSet features;
  SE3 T_c_w = SE3::Identity();
  Eigen::Vector3d point = Eigen::Vector3d(0.0, 0.0, 2.0);
  map::MapFingerprint fingerprint = fingerprintOf640x480();
};

MapParts validParts() {
  MapParts parts;
  auto& f = parts.features;
  f.keypoints = {cv::KeyPoint(100.0F, 120.0F, 31.0F, 10.0F, 0.5F, 0),
                 cv::KeyPoint(400.0F, 300.0F, 37.2F, 20.0F, 0.4F, 1)};
  f.undistorted = {f.keypoints[0].pt, f.keypoints[1].pt};
  f.u_right = {80.0F, -1.0F};
  f.depth = {2.0F, -1.0F};
  f.descriptors = cv::Mat(2, 32, CV_8U, cv::Scalar(7));
  return parts;
}

std::filesystem::path saveMap(const MapParts& parts, const std::filesystem::path& file) {
  const auto pyramid = std::make_shared<feature::ScaleLevels>(kLevels, kScale);
  map::Map map;
  auto keyframe = std::make_shared<map::KeyFrame>(map.nextKeyFrameId(), 0, 0.0, parts.T_c_w,
                                                  std::make_shared<map::FeatureSet>(parts.features),
                                                  pyramid, parts.fingerprint.camera);
  map.addKeyFrame(keyframe);
  auto point = std::make_shared<map::MapPoint>(map.nextMapPointId(), parts.point, keyframe);
  keyframe->setMapPoint(0, point);
  point->addObservation(keyframe, 0);
  map.addMapPoint(point);
  map::saveMapFile(map, parts.fingerprint, file);
  return file;
}

// `map info` and loading into a run with the map's own settings both refuse the file with a
// message naming it and `problem`; the run's map stays empty.
void expectRefused(const std::function<void(MapParts&)>& change, const std::string& problem) {
  test::TempDir dir("map_values");
  MapParts parts = validParts();
  change(parts);
  const auto file = saveMap(parts, dir.path() / "bad.map");
  const auto refused = [&](const std::function<void()>& read) {
    const std::string message = test::errorOf(read);
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos)
        << "expected: " << problem << "; " << message;
  };
  refused([&] { map::readMapFileInfo(file); });
  map::Map map;
  refused([&] {
    map::loadMapFile(file, parts.fingerprint,
                     std::make_shared<feature::ScaleLevels>(kLevels, kScale), map);
  });
  EXPECT_EQ(map.keyFrameCount(), 0U);
}

TEST(MapFileValues, TheValidMapOfTheseTestsLoads) {
  test::TempDir dir("map_values");
  const MapParts parts = validParts();
  const auto file = saveMap(parts, dir.path() / "good.map");
  EXPECT_EQ(map::readMapFileInfo(file).points, 1U);
  map::Map map;
  map::loadMapFile(file, parts.fingerprint, std::make_shared<feature::ScaleLevels>(kLevels, kScale),
                   map);
  EXPECT_EQ(map.keyFrameCount(), 1U);
}

TEST(MapFileValues, KeypointBeyondThePyramidIsAnError) {
  // Tracking reads the pyramid's scale tables at the keypoint's level.
  expectRefused([](MapParts& p) { p.features.keypoints[1].octave = kLevels; },
                "keypoint 1 at pyramid level 8 (the map has levels 0-7)");
  expectRefused([](MapParts& p) { p.features.keypoints[0].octave = -1; },
                "keypoint 0 at pyramid level -1");
}

TEST(MapFileValues, KeypointOutsideTheImageIsAnError) {
  expectRefused([](MapParts& p) { p.features.keypoints[1].pt.x = 700.0F; },
                "keypoint 1 at (700, 300) is outside the 640x480 image");
  expectRefused([](MapParts& p) { p.features.keypoints[0].pt.y = std::nanf(""); },
                "keypoint 0 at (100, nan) is outside the 640x480 image");
}

TEST(MapFileValues, KeypointValueThatIsNotANumberIsAnError) {
  expectRefused([](MapParts& p) { p.features.depth[0] = std::numeric_limits<float>::infinity(); },
                "keyframe 0: keypoint 0 has a value that is not a finite number");
  expectRefused([](MapParts& p) { p.features.undistorted[1].x = std::nanf(""); },
                "keypoint 1 has a value that is not a finite number");
}

TEST(MapFileValues, PoseThatIsNotARotationIsAnError) {
  expectRefused([](MapParts& p) { p.T_c_w.translation().x() = kNaN; },
                "keyframe 0: the pose is not a finite rotation and translation");
  expectRefused([](MapParts& p) { p.T_c_w.linear() *= 2.0; },
                "keyframe 0: the pose is not a finite rotation and translation");
}

TEST(MapFileValues, MapPointThatIsNotFiniteIsAnError) {
  expectRefused([](MapParts& p) { p.point.z() = kNaN; }, "map point 0: position, normal");
}

TEST(MapFileValues, UnusableSettingsInTheFingerprintAreAnError) {
  expectRefused([](MapParts& p) { p.fingerprint.orb_levels = 0; },
                "the map's ORBextractor.nLevels must be >= 1");
  expectRefused([](MapParts& p) { p.fingerprint.image_width = 0; }, "image size 0x480");
  expectRefused([](MapParts& p) { p.fingerprint.camera.fx = -1.0; }, "camera fx -1");
}

}  // namespace
}  // namespace lumaslam
