// Dataset folders written by synth: TUM RGB-D and EuRoC layouts, read back with plain code.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/synth/dataset_writer.h"
#include "test_paths.h"

using namespace lumaslam::synth;
using lumaslam::test::errorOf;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> readLines(const fs::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

TEST(SynthWriter, TumLayoutMatchesTheRenderer) {
  lumaslam::test::TempDir dir("synth_tum");
  const fs::path out = dir.path() / "walking";
  const Preset& preset = findPreset("walking-xyz-rgbd");
  const SequenceRenderer sequence(preset, 4, 9);
  writeDataset(sequence, out);

  const auto rgb = readLines(out / "rgb.txt");
  ASSERT_EQ(rgb.size(), 3u + 4u);
  EXPECT_EQ(rgb[0], "# color images");
  EXPECT_EQ(rgb[2], "# timestamp filename");
  const auto depth = readLines(out / "depth.txt");
  ASSERT_EQ(depth.size(), 3u + 4u);
  EXPECT_EQ(depth[0], "# depth maps");
  const auto gt = readLines(out / "groundtruth.txt");
  ASSERT_EQ(gt.size(), 3u + 4u);
  EXPECT_EQ(gt[0], "# ground truth trajectory");
  EXPECT_EQ(gt[2], "# timestamp tx ty tz qx qy qz qw");
  EXPECT_EQ(readLines(out / "associations.txt").size(), 4u);

  double previous_time = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Frame frame = sequence.render(i);
    std::istringstream rgb_line(rgb[3 + i]), gt_line(gt[3 + i]), depth_line(depth[3 + i]);
    std::string stamp, file, depth_stamp, depth_file;
    rgb_line >> stamp >> file;
    depth_line >> depth_stamp >> depth_file;
    EXPECT_EQ(stamp, tumTimestamp(frame.timestamp_ns));
    EXPECT_EQ(file, "rgb/" + stamp + ".png");
    const double time = std::stod(stamp);
    EXPECT_NEAR(time - previous_time, i == 0 ? time : 1.0 / 30.0,
                i == 0 ? 0.0 : 0.0021);  // 30 Hz, +-1 ms jitter
    previous_time = time;

    const cv::Mat image = cv::imread((out / file).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(image.empty()) << file;
    EXPECT_EQ(cv::norm(image, frame.cam0.image, cv::NORM_INF), 0.0);
    const cv::Mat depth_png = cv::imread((out / depth_file).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth_png.type(), CV_16U);
    cv::Mat metres;
    depth_png.convertTo(metres, CV_32F, 1.0 / 5000.0);
    EXPECT_LT(cv::norm(metres, frame.sensor_depth, cv::NORM_INF), 1.0 / 5000.0);
    const cv::Mat mask =
        cv::imread((out / "mask" / (stamp + ".png")).string(), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(cv::norm(mask, frame.cam0.mask, cv::NORM_INF), 0.0);

    double t, tx, ty, tz, qx, qy, qz, qw;
    gt_line >> t >> tx >> ty >> tz >> qx >> qy >> qz >> qw;
    EXPECT_DOUBLE_EQ(t, time);
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    EXPECT_LT((Eigen::Vector3d(tx, ty, tz) - frame.cam0.T_w_c.translation()).norm(), 2e-6);
    EXPECT_LT(q.angularDistance(Eigen::Quaterniond(frame.cam0.T_w_c.linear())), 1e-5);
  }

  // detections.txt: one line per box, boxes inside the image.
  int boxes = 0;
  for (const auto& line : readLines(out / "detections.txt")) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::string stamp, cls;
    int x, y, w, h;
    ASSERT_TRUE(in >> stamp >> cls >> x >> y >> w >> h) << line;
    EXPECT_TRUE(cls == "person" || cls == "box");
    EXPECT_GE(x, 0);
    EXPECT_LE(x + w, 640);
    EXPECT_LE(y + h, 480);
    ++boxes;
  }
  int expected_boxes = 0;
  for (int i = 0; i < 4; ++i)
    expected_boxes += static_cast<int>(sequence.render(i).cam0.boxes.size());
  EXPECT_EQ(boxes, expected_boxes);

  const auto settings = lumaslam::core::SettingsFile::open(out / "settings.yaml");
  EXPECT_DOUBLE_EQ(settings.get<double>("Camera.fx"), 535.4);
  EXPECT_EQ(settings.get<int>("Camera.width"), 640);
  EXPECT_DOUBLE_EQ(settings.get<double>("DepthMapFactor"), 5000.0);
  EXPECT_DOUBLE_EQ(settings.get<double>("Camera.fps"), 30.0);
  EXPECT_EQ(settings.get<int>("ORBextractor.nFeatures"), 1000);
}

TEST(SynthWriter, SameSeedWritesTheSameBytes) {
  lumaslam::test::TempDir dir("synth_bytes");
  writeSequence(dir.path() / "a", "flash-rgbd", 2, 5);
  writeSequence(dir.path() / "b", "flash-rgbd", 2, 5);
  for (const auto& entry : fs::recursive_directory_iterator(dir.path() / "a")) {
    if (!entry.is_regular_file()) continue;
    const fs::path other = dir.path() / "b" / fs::relative(entry.path(), dir.path() / "a");
    EXPECT_EQ(readBytes(entry.path()), readBytes(other)) << other;
  }
}

TEST(SynthWriter, EurocLayoutMatchesTheRenderer) {
  lumaslam::test::TempDir dir("synth_euroc");
  const fs::path out = dir.path() / "stereo";
  const SequenceRenderer sequence(findPreset("xyz-stereo"), 3, 2);
  writeDataset(sequence, out);
  for (const char* cam : {"cam0", "cam1"}) {
    const auto csv = readLines(out / "mav0" / cam / "data.csv");
    ASSERT_EQ(csv.size(), 4u);
    EXPECT_EQ(csv[0], "#timestamp [ns],filename");
    for (int i = 0; i < 3; ++i) {
      const std::string ns = std::to_string(sequence.timestampNs(i));
      EXPECT_EQ(csv[1 + i], ns + "," + ns + ".png");
      const cv::Mat image =
          cv::imread((out / "mav0" / cam / "data" / (ns + ".png")).string(), cv::IMREAD_UNCHANGED);
      ASSERT_FALSE(image.empty());
      EXPECT_EQ(image.type(), CV_8UC1);
      EXPECT_EQ(image.cols, 752);
    }
    cv::FileStorage yaml((out / "mav0" / cam / "sensor.yaml").string(), cv::FileStorage::READ);
    ASSERT_TRUE(yaml.isOpened());
    EXPECT_EQ(static_cast<int>(yaml["rate_hz"]), 20);
    std::vector<double> intrinsics, t_bs;
    yaml["intrinsics"] >> intrinsics;
    yaml["T_BS"]["data"] >> t_bs;
    ASSERT_EQ(intrinsics.size(), 4u);
    EXPECT_DOUBLE_EQ(intrinsics[0], 458.654);
    ASSERT_EQ(t_bs.size(), 16u);
    EXPECT_DOUBLE_EQ(t_bs[3], std::string(cam) == "cam1" ? 0.11 : 0.0);
  }
  // Ground truth at 200 Hz over the image span: 2 intervals of 50 ms = 21 rows.
  const auto gt = readLines(out / "mav0" / "state_groundtruth_estimate0" / "data.csv");
  ASSERT_EQ(gt.size(), 1u + 21u);
  EXPECT_EQ(gt[0].rfind("#timestamp, p_RS_R_x [m]", 0), 0u);
  std::vector<double> values;
  std::stringstream row(gt[1 + 10]);  // the second camera frame
  for (std::string cell; std::getline(row, cell, ',');) values.push_back(std::stod(cell));
  ASSERT_EQ(values.size(), 17u);
  const lumaslam::SE3 pose = sequence.render(1).cam0.T_w_c;
  EXPECT_EQ(static_cast<std::int64_t>(values[0]) / 1000, sequence.timestampNs(1) / 1000);
  EXPECT_LT((Eigen::Vector3d(values[1], values[2], values[3]) - pose.translation()).norm(), 2e-6);
  const Eigen::Quaterniond q(values[4], values[5], values[6], values[7]);
  EXPECT_LT(q.angularDistance(Eigen::Quaterniond(pose.linear())), 1e-6);

  const auto settings = lumaslam::core::SettingsFile::open(out / "settings.yaml");
  EXPECT_DOUBLE_EQ(settings.get<double>("Stereo.b"), 0.11);
  EXPECT_NEAR(settings.get<double>("Camera.bf"), 458.654 * 0.11, 1e-6);
  EXPECT_NEAR(settings.getMatrix("Stereo.T_c1_c2", 4, 4).at<double>(0, 3), 0.11, 1e-12);
  EXPECT_EQ(settings.getMatrix("LEFT.K", 3, 3).at<double>(0, 0), 458.654);
}

TEST(SynthWriter, UnwritableOutputNamesThePath) {
  lumaslam::test::TempDir dir("synth_bad");
  const fs::path file = dir.path() / "a_file";
  std::ofstream(file) << "x";
  const std::string message = errorOf([&] { writeSequence(file / "out", "xyz-rgbd", 1, 1); });
  EXPECT_NE(message.find("a_file"), std::string::npos) << message;
  EXPECT_THROW(writeSequence(dir.path() / "x", "no-such-preset", 1, 1), lumaslam::Error);
}
