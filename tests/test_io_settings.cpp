#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>
#include <opencv2/imgcodecs.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/settings.h"
#include "test_paths.h"

using lumaslam::Error;
using lumaslam::camera::CameraModel;
using lumaslam::core::SettingsFile;
using lumaslam::io::loadSettings;
using lumaslam::io::SensorType;
using lumaslam::io::Settings;
namespace fs = std::filesystem;

namespace {

fs::path config(const std::string& name) {
  return lumaslam::test::sourceDir() / "configs" / name;
}

Settings parse(const std::string& yaml, std::optional<SensorType> sensor = std::nullopt) {
  return Settings::fromFile(SettingsFile::fromString(yaml, "test.yaml"), sensor);
}

// The message of the Error parsing `yaml` raises (test::errorOf).
std::string errorOf(const std::string& yaml) {
  return lumaslam::test::errorOf([&] { (void)parse(yaml); });
}

const std::string kMonoNew = R"(%YAML:1.0
File.version: "1.0"
Camera.type: "PinHole"
Camera1.fx: 500.0
Camera1.fy: 501.0
Camera1.cx: 320.0
Camera1.cy: 240.0
Camera1.k1: -0.1
Camera.width: 640
Camera.height: 480
Camera.fps: 30
Camera.RGB: 0
ORBextractor.nFeatures: 1500
ORBextractor.scaleFactor: 1.2
ORBextractor.nLevels: 8
ORBextractor.iniThFAST: 20
ORBextractor.minThFAST: 7
)";

// Replaces the first line starting with `key` ("Camera1.fx:") by `line` ("" removes it).
std::string with(std::string yaml, const std::string& key, const std::string& line) {
  const auto at = yaml.find("\n" + key);
  if (at == std::string::npos) return yaml + line + "\n";
  const auto end = yaml.find('\n', at + 1);
  return yaml.replace(at + 1, end - at, line.empty() ? "" : line + "\n");
}

std::vector<double> tBs(const fs::path& sensorYaml) {
  return SettingsFile::open(sensorYaml).get<std::vector<double>>("T_BS.data");
}

Eigen::Isometry3d toPose(const std::vector<double>& rowMajor) {
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = rowMajor.at(i);
  return Eigen::Isometry3d(m);
}

TEST(Settings, EveryShippedConfigLoads) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(lumaslam::test::sourceDir() / "configs")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const Settings s = loadSettings(entry.path());
    EXPECT_GT(s.camera.fx, 0.0);
    EXPECT_EQ(s.stereo.has_value(), s.sensor != SensorType::Monocular);
    EXPECT_EQ(s.path, entry.path());
    ++count;
  }
  EXPECT_GE(count, 14);
}

TEST(Settings, TumConfigsHoldTheDatasetCalibration) {
  const Settings fr1 = loadSettings(config("tum_fr1_rgbd.yaml"));
  EXPECT_EQ(fr1.sensor, SensorType::Rgbd);
  EXPECT_DOUBLE_EQ(fr1.camera.fx, 517.306408);
  EXPECT_DOUBLE_EQ(fr1.camera.distortion[4], 1.163314);  // k3
  EXPECT_DOUBLE_EQ(fr1.depth.depthMapFactor, 5000.0);
  EXPECT_NEAR(fr1.bf(), 40.0, 0.01);
  EXPECT_NEAR(fr1.closeDepth(), 40.0 * fr1.baseline(), 1e-12);
  EXPECT_FALSE(fr1.camera.rgb);  // BGR, as cv::imread and lumaslam::Dataset give

  const Settings fr3 = loadSettings(config("tum_fr3_mono.yaml"));
  EXPECT_EQ(fr3.sensor, SensorType::Monocular);
  EXPECT_DOUBLE_EQ(fr3.camera.fy, 539.2);
  EXPECT_FALSE(fr3.camera.hasDistortion());
  EXPECT_FALSE(fr3.stereo.has_value());
  EXPECT_EQ(loadSettings(config("tum_fr2_rgbd.yaml")).camera.cx, 325.141442);
}

TEST(Settings, EurocStereoConfigMatchesTheRealSensorFiles) {
  const fs::path mav = lumaslam::test::dataDir() / "euroc/V1_01_easy_micro/mav0";
  const auto cam0 = SettingsFile::open(mav / "cam0/sensor.yaml");
  const auto cam1 = SettingsFile::open(mav / "cam1/sensor.yaml");
  const Settings s = loadSettings(config("euroc_stereo.yaml"));
  ASSERT_EQ(s.sensor, SensorType::Stereo);
  ASSERT_TRUE(s.stereo && s.stereo->right);

  const auto k0 = cam0.get<std::vector<double>>("intrinsics");
  const auto d1 = cam1.get<std::vector<double>>("distortion_coefficients");
  EXPECT_DOUBLE_EQ(s.camera.fx, k0.at(0));
  EXPECT_DOUBLE_EQ(s.camera.cy, k0.at(3));
  EXPECT_DOUBLE_EQ(s.stereo->right->distortion[0], d1.at(0));
  EXPECT_DOUBLE_EQ(s.stereo->right->distortion[3], d1.at(3));
  EXPECT_EQ(s.camera.size.width, cam0.get<std::vector<double>>("resolution").at(0));

  const auto T_c1_c2 =
      toPose(tBs(mav / "cam0/sensor.yaml")).inverse() * toPose(tBs(mav / "cam1/sensor.yaml"));
  EXPECT_TRUE(s.stereo->T_c1_c2.matrix().isApprox(T_c1_c2.matrix(), 1e-9));
  EXPECT_NEAR(s.baseline(), 0.110, 0.001);
  EXPECT_DOUBLE_EQ(s.depth.thDepth, 60.0);
  const std::string summary = s.summary();
  EXPECT_NE(summary.find("stereo"), std::string::npos) << summary;
  EXPECT_NE(summary.find("b=0.1101"), std::string::npos) << summary;
  EXPECT_NE(summary.find("unrectified"), std::string::npos) << summary;
}

TEST(Settings, KittiConfigMatchesRealCalibAndImageSize) {
  const fs::path seq = lumaslam::test::dataDir() / "kitti/odometry_07_first160/sequences/07";
  std::ifstream calib(seq / "calib.txt");
  ASSERT_TRUE(calib) << seq / "calib.txt";
  std::map<std::string, std::vector<double>> P;
  for (std::string line; std::getline(calib, line);) {
    std::istringstream in(line);
    std::string name;
    in >> name;
    for (double v; in >> v;) P[name].push_back(v);
  }
  const cv::Mat image = cv::imread((seq / "image_0/000000.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(image.empty());

  const Settings s = loadSettings(config("kitti_04-12_stereo.yaml"));
  EXPECT_EQ(s.camera.model, CameraModel::Rectified);
  EXPECT_DOUBLE_EQ(s.camera.fx, P["P0:"].at(0));
  EXPECT_DOUBLE_EQ(s.camera.cx, P["P0:"].at(2));
  EXPECT_DOUBLE_EQ(s.camera.cy, P["P0:"].at(6));
  EXPECT_NEAR(s.bf(), -P["P1:"].at(3), 0.01);
  EXPECT_EQ(s.camera.size.width, image.cols);
  EXPECT_EQ(s.camera.size.height, image.rows);
  EXPECT_TRUE(s.stereo->T_c1_c2.translation().isApprox(Eigen::Vector3d(s.baseline(), 0, 0)));

  const Settings mono = loadSettings(config("kitti_00-02_mono.yaml"));
  EXPECT_EQ(mono.sensor, SensorType::Monocular);
  EXPECT_NE(loadSettings(config("kitti_03_mono.yaml")).camera.fx, mono.camera.fx);
}

// Camera.RGB names the colour order of images handed to the System API; without it they are
// BGR, as in ORB-SLAM3 (mbRGB = 0) and as cv::imread gives them.
TEST(Settings, ColourOrderIsBgrUnlessCameraRgbSaysRgb) {
  EXPECT_FALSE(parse(with(kMonoNew, "Camera.RGB:", "")).camera.rgb);
  EXPECT_FALSE(parse(with(kMonoNew, "Camera.RGB:", "Camera.RGB: 0")).camera.rgb);
  EXPECT_TRUE(parse(with(kMonoNew, "Camera.RGB:", "Camera.RGB: 1")).camera.rgb);
}

TEST(Settings, ReadsNewKeysWithDefaults) {
  const Settings s = parse(kMonoNew);
  EXPECT_EQ(s.sensor, SensorType::Monocular);  // inferred: no stereo or depth keys
  EXPECT_EQ(s.camera.model, CameraModel::Pinhole);
  EXPECT_DOUBLE_EQ(s.camera.fy, 501.0);
  EXPECT_DOUBLE_EQ(s.camera.distortion[0], -0.1);
  EXPECT_DOUBLE_EQ(s.camera.distortion[4], 0.0);
  EXPECT_TRUE(s.camera.hasDistortion());
  EXPECT_FALSE(s.camera.rgb);
  EXPECT_FALSE(s.system.sequential);
  EXPECT_TRUE(s.system.datasetRoot.empty());
  EXPECT_EQ(s.file->origin(), "test.yaml");
  EXPECT_EQ(s.baseline(), 0.0);
}

TEST(Settings, OldOrbSlam2KeysGiveTheSameSettingsAsNewOnes) {
  const std::string oldRgbd = R"(%YAML:1.0
Camera.fx: 517.306408
Camera.fy: 516.469215
Camera.cx: 318.643040
Camera.cy: 255.313989
Camera.k1: 0.262383
Camera.k2: -0.953104
Camera.p1: -0.005358
Camera.p2: 0.002628
Camera.k3: 1.163314
Camera.width: 640
Camera.height: 480
Camera.fps: 30.0
Camera.bf: 40.0
Camera.RGB: 1
ThDepth: 40.0
DepthMapFactor: 5000.0
)";
  const Settings old = parse(oldRgbd);
  const Settings fresh = loadSettings(config("tum_fr1_rgbd.yaml"));
  EXPECT_EQ(old.sensor, SensorType::Rgbd);  // inferred from DepthMapFactor
  EXPECT_DOUBLE_EQ(old.camera.fx, fresh.camera.fx);
  EXPECT_EQ(old.camera.distortion, fresh.camera.distortion);
  EXPECT_NEAR(old.bf(), 40.0, 1e-9);
  EXPECT_NEAR(old.baseline(), fresh.baseline(), 1e-5);
  EXPECT_DOUBLE_EQ(old.depth.depthMapFactor, fresh.depth.depthMapFactor);
  EXPECT_DOUBLE_EQ(old.depth.thDepth, 40.0);

  // An ORB-SLAM2 stereo file (Camera.bf, no Camera2) is a rectified pair.
  std::string oldStereo = with(oldRgbd, "DepthMapFactor:", "");
  oldStereo = with(oldStereo, "Camera.k1:", "Camera.k1: 0.0");
  oldStereo = with(oldStereo, "Camera.k2:", "Camera.k2: 0.0");
  oldStereo = with(oldStereo, "Camera.p1:", "Camera.p1: 0.0");
  oldStereo = with(oldStereo, "Camera.p2:", "Camera.p2: 0.0");
  oldStereo = with(oldStereo, "Camera.k3:", "Camera.k3: 0.0");
  const Settings stereo = parse(oldStereo);
  EXPECT_EQ(stereo.sensor, SensorType::Stereo);
  EXPECT_FALSE(stereo.stereo->right.has_value());
  EXPECT_NEAR(stereo.stereo->T_c1_c2.translation().x(), 40.0 / 517.306408, 1e-12);
}

TEST(Settings, SensorSystemKeysAndOverride) {
  const std::string rgbd =
      kMonoNew + "Stereo.b: 0.08\nStereo.ThDepth: 40\nRGBD.DepthMapFactor: 1000\n";
  EXPECT_EQ(parse(rgbd).sensor, SensorType::Rgbd);
  EXPECT_EQ(parse(rgbd + "System.sensor: \"mono\"\n").sensor, SensorType::Monocular);
  EXPECT_EQ(parse(rgbd, SensorType::Stereo).sensor, SensorType::Stereo);  // argument wins
  EXPECT_EQ(parse(rgbd + "System.sensor: \"mono\"\n", SensorType::Rgbd).sensor, SensorType::Rgbd);

  const Settings s = parse(kMonoNew + "System:\n  sequential: 1\n");
  EXPECT_TRUE(s.system.sequential);

  // Other modules' sections stay readable through the shared file.
  const Settings withSection = parse(kMonoNew + "Enhancement.preset: \"night\"\n");
  EXPECT_EQ(withSection.file->get<std::string>("Enhancement.preset"), "night");
}

// System.queueCapacity never sized a queue and is no longer read (issue 21): a file with it, even
// with a value once rejected, loads with a warning naming the key and the detection queue's
// own key, and the key does not count as unknown.
TEST(Settings, RetiredQueueCapacityLoadsWithAWarning) {
  const auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(16);
  const auto logger = spdlog::default_logger();
  logger->sinks().push_back(sink);
  const auto parsed = [] { return parse(kMonoNew + "System.queueCapacity: 0\n"); };
  EXPECT_NO_THROW(parsed());
  logger->sinks().pop_back();
  std::string logged;
  for (const auto& line : sink->last_formatted()) logged += line;
  EXPECT_NE(logged.find("test.yaml: key 'System.queueCapacity' is ignored"), std::string::npos)
      << logged;
  EXPECT_NE(logged.find("Detector.queueCapacity"), std::string::npos) << logged;
  EXPECT_TRUE(parsed().file->askedKeys().contains("System.queueCapacity"));
}

// The motion test is on by default for RGB-D only; the key turns it on or off for any sensor.
TEST(Settings, MotionEvidenceDefaultsBySensor) {
  const std::string rgbd =
      kMonoNew + "Stereo.b: 0.08\nStereo.ThDepth: 40\nRGBD.DepthMapFactor: 1000\n";
  EXPECT_TRUE(parse(rgbd).dynamic.motionEvidenceFor(SensorType::Rgbd));
  EXPECT_FALSE(parse(rgbd).dynamic.motionEvidenceFor(SensorType::Stereo));
  EXPECT_FALSE(parse(kMonoNew).dynamic.motionEvidenceFor(SensorType::Monocular));
  EXPECT_FALSE(
      parse(rgbd + "Dynamic.motionEvidence: 0\n").dynamic.motionEvidenceFor(SensorType::Rgbd));
  EXPECT_TRUE(parse(kMonoNew + "Dynamic.motionEvidence: 1\n")
                  .dynamic.motionEvidenceFor(SensorType::Monocular));
}

TEST(Settings, DatasetRootIsResolvedAgainstTheSettingsFolder) {
  lumaslam::test::TempDir dir("settings_root");
  const fs::path file = dir.path() / "run.yaml";
  std::ofstream(file) << kMonoNew << "System.datasetRoot: \"data/seq\"\n";
  EXPECT_EQ(loadSettings(file).system.datasetRoot, dir.path() / "data/seq");
  std::ofstream(file) << kMonoNew << "System.datasetRoot: \"/abs/seq\"\n";
  EXPECT_EQ(loadSettings(file).system.datasetRoot, fs::path("/abs/seq"));
}

TEST(Settings, LoopVocabularyIsResolvedAgainstTheSettingsFolder) {
  lumaslam::test::TempDir dir("settings_vocab");
  const fs::path file = dir.path() / "run.yaml";
  std::ofstream(file) << kMonoNew;
  EXPECT_TRUE(loadSettings(file).loop.vocabulary.empty());
  std::ofstream(file) << kMonoNew << "Loop.vocabulary: \"voc/orb.bin\"\n";
  EXPECT_EQ(loadSettings(file).loop.vocabulary, dir.path() / "voc/orb.bin");
  std::ofstream(file) << kMonoNew << "Loop.vocabulary: \"/abs/ORBvoc.txt\"\n";
  EXPECT_EQ(loadSettings(file).loop.vocabulary, fs::path("/abs/ORBvoc.txt"));
  // "none" is the keyword that turns the vocabulary off, not a file next to the settings.
  std::ofstream(file) << kMonoNew << "Loop.vocabulary: none\n";
  EXPECT_EQ(loadSettings(file).loop.vocabulary, fs::path("none"));
}

TEST(Settings, LoopClosingIsOnByDefaultAndCanBeTurnedOff) {
  EXPECT_TRUE(parse(kMonoNew).loop.closing);
  EXPECT_FALSE(parse(kMonoNew + "Loop.closing: 0\n").loop.closing);
  EXPECT_TRUE(parse(kMonoNew + "Loop.closing: 1\n").loop.closing);
}

TEST(Settings, ResizeScalesIntrinsics) {
  const Settings s = parse(kMonoNew + "Camera.newWidth: 320\nCamera.newHeight: 240\n");
  ASSERT_TRUE(s.camera.resizeTo.has_value());
  const auto working = s.camera.atWorkingSize();
  EXPECT_DOUBLE_EQ(working.fx, 250.0);
  EXPECT_DOUBLE_EQ(working.cy, 120.0);
  EXPECT_EQ(working.size.width, 320);
  EXPECT_FALSE(working.resizeTo.has_value());
  EXPECT_EQ(working.distortion, s.camera.distortion);
}

struct BadCase {
  std::string yaml;
  std::vector<std::string> mentions;  // substrings the message must contain
};

TEST(Settings, BadSettingsNameFileKeyAndValue) {
  const std::string stereoRectified = with(kMonoNew, "Camera.type:", "Camera.type: \"Rectified\"") +
                                      "System.sensor: stereo\nStereo.ThDepth: 35\n";
  const std::string stereoPinhole = kMonoNew + "System.sensor: stereo\nStereo.ThDepth: 35\n";
  const std::string badRotation =
      "Stereo.T_c1_c2: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: d\n"
      "  data: [1, 0.5, 0, 0.1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n";
  const std::vector<BadCase> cases = {
      {with(kMonoNew, "Camera1.fx:", "Camera1.fx: -3.5"), {"test.yaml", "Camera1.fx", "-3.5"}},
      {with(kMonoNew, "Camera1.fx:", ""),
       {"test.yaml", "Camera1.fx", "Camera.fx", "missing", "number"}},
      {with(kMonoNew, "Camera1.fy:", "Camera1.fy: \"abc\""), {"Camera1.fy", "number", "abc"}},
      {with(kMonoNew, "Camera.width:", "Camera.width: 0"), {"Camera.width", "0"}},
      {with(kMonoNew, "Camera.height:", ""), {"Camera.height", "missing", "integer"}},
      {with(kMonoNew, "Camera1.cx:", "Camera1.cx: 900"), {"Camera1.cx", "900"}},
      {with(kMonoNew, "Camera.type:", "Camera.type: \"KannalaBrandt8\""),
       {"Camera.type", "KannalaBrandt8"}},
      {with(kMonoNew, "Camera.type:", "Camera.type: \"Fancy\""), {"Camera.type", "Fancy"}},
      {with(kMonoNew, "File.version:", "File.version: \"2.0\""), {"File.version", "2.0"}},
      {kMonoNew + "System.sensor: \"lidar\"\n", {"System.sensor", "lidar"}},
      {kMonoNew + "Camera1.fx: 510.0\n",
       {"test.yaml: key 'Camera1.fx' is set twice: lines 4 and 18"}},
      {kMonoNew + "Camera.newWidth: 320\n", {"Camera.newHeight"}},
      {stereoRectified, {"test.yaml", "Stereo.b", "baseline"}},
      {stereoRectified + "Stereo.b: -0.1\n", {"Stereo.b", "-0.1"}},
      {with(stereoRectified, "Stereo.ThDepth:", "Stereo.ThDepth: 0") + "Stereo.b: 0.1\n",
       {"Stereo.ThDepth", "0"}},
      {with(stereoRectified, "Stereo.ThDepth:", "") + "Stereo.b: 0.1\n",
       {"Stereo.ThDepth", "missing"}},
      {stereoPinhole + badRotation, {"Camera2.fx", "missing"}},
      {stereoPinhole + "Camera2.fx: 500\nCamera2.fy: 500\nCamera2.cx: 320\nCamera2.cy: 240\n" +
           badRotation,
       {"Stereo.T_c1_c2", "rotation"}},
      {stereoPinhole + "Camera2.fx: 500\nCamera2.fy: 500\nCamera2.cx: 320\nCamera2.cy: 240\n",
       {"Stereo.T_c1_c2", "missing", "4x4"}},
      {kMonoNew + "System.sensor: rgbd\nStereo.b: 0.08\nStereo.ThDepth: 40\n",
       {"RGBD.DepthMapFactor", "DepthMapFactor", "missing"}},
      {kMonoNew +
           "System.sensor: rgbd\nStereo.b: 0.08\nStereo.ThDepth: 40\nRGBD.DepthMapFactor: 0\n",
       {"RGBD.DepthMapFactor", "0"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.yaml);
    const std::string message = errorOf(c.yaml);
    ASSERT_FALSE(message.empty()) << "bad settings accepted";
    for (const auto& m : c.mentions) EXPECT_NE(message.find(m), std::string::npos) << message;
  }
}

TEST(Settings, MissingFileIsAnError) {
  lumaslam::test::TempDir dir("settings_missing");
  // A missing file is not accepted.
  const std::string message =
      lumaslam::test::errorOf([&] { (void)loadSettings(dir.path() / "none.yaml"); });
  EXPECT_NE(message.find("none.yaml"), std::string::npos);
}

}  // namespace
