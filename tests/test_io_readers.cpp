#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/euroc_sensor_yaml.h"
#include "lumaslam/io/kitti_reader.h"
#include "lumaslam/io/text_lines.h"
#include "lumaslam/io/timestamp_association.h"
#include "lumaslam/io/trajectory_io.h"
#include "test_paths.h"

namespace lumaslam::io {
namespace {

namespace fs = std::filesystem;
using test::dataDir;
using test::TempDir;

const fs::path kTumDir = "tum/rgbd_dataset_freiburg1_xyz_textonly";
const fs::path kEurocDir = "euroc/V1_01_easy_micro";
const fs::path kKittiSequence = "kitti/odometry_07_first160/sequences/07";

using test::errorOf;

#define EXPECT_ERROR_CONTAINS(action, text)                                   \
  do {                                                                        \
    const std::string message = errorOf([&] { action; });                     \
    EXPECT_NE(message.find(text), std::string::npos) << "error: " << message; \
  } while (false)

struct ListEntry {
  double timestamp;
  std::string file;
};

std::vector<ListEntry> readList(const fs::path& file) {
  std::vector<ListEntry> entries;
  for (const auto& line : readDataLines(file)) {
    const auto fields = splitFields(line.text, " ");
    entries.push_back({parseNumber(fields[0], file, line), std::string(fields[1])});
  }
  return entries;
}

std::vector<double> timestampsOf(const std::vector<ListEntry>& entries) {
  std::vector<double> times;
  for (const auto& entry : entries) times.push_back(entry.timestamp);
  return times;
}

void writeBytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

// ---------------------------------------------------------------- TUM RGB-D

TEST(TimestampAssociation, IsOneToOneClosestFirst) {
  // Both 0.0 and 0.010 are closest to 0.008; the closer pair (0.010, 0.008) wins.
  const auto matches = associateTimestamps({0.0, 0.010, 0.5}, {0.008, 0.9}, 0.02);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].first, 1u);
  EXPECT_EQ(matches[0].second, 0u);
  EXPECT_TRUE(associateTimestamps({0.0}, {0.02}, 0.02).empty());  // strictly below max dt
}

TEST(TumReader, AssociatesFr1XyzLikeAssociatePy) {
  const fs::path root = dataDir() / kTumDir;
  const auto rgb = readList(root / "rgb.txt");
  const auto depth = readList(root / "depth.txt");
  ASSERT_EQ(rgb.size(), 798u);
  ASSERT_EQ(depth.size(), 798u);
  const auto matches = associateTimestamps(timestampsOf(rgb), timestampsOf(depth), 0.02);
  // TUM's associate.py (run on these two files with --max_difference 0.02) pairs 792.
  EXPECT_EQ(matches.size(), 792u);
  std::set<std::size_t> used_rgb, used_depth;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    EXPECT_LT(std::abs(rgb[matches[i].first].timestamp - depth[matches[i].second].timestamp), 0.02);
    EXPECT_TRUE(used_rgb.insert(matches[i].first).second);
    EXPECT_TRUE(used_depth.insert(matches[i].second).second);
    if (i > 0) {
      EXPECT_GT(matches[i].first, matches[i - 1].first);
    }
  }

  EXPECT_EQ(openDataset("tum:" + root.string())->size(), 792u);
  EXPECT_EQ(openDataset("tum-mono:" + root.string())->size(), 798u);
  const auto reader = openDataset("tum:" + root.string());
  EXPECT_TRUE(reader->hasDepth());
  EXPECT_EQ(reader->groundTruth().size(), 3000u);
  EXPECT_EQ(loadGroundTruth("tum:" + root.string()).size(), 3000u);
}

// A copy of the fr1_xyz lists with tiny generated images for the first ten rgb and depth
// entries: rgb pixel value = 10 * row in rgb.txt, depth value = 1000 + row in depth.txt.
class TumImagesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path source = dataDir() / kTumDir;
    for (const char* name : {"rgb.txt", "depth.txt", "groundtruth.txt"})
      fs::copy_file(source / name, dir_.path() / name);
    fs::create_directories(dir_.path() / "rgb");
    fs::create_directories(dir_.path() / "depth");
    rgb_ = readList(source / "rgb.txt");
    depth_ = readList(source / "depth.txt");
    for (int i = 0; i < 10; ++i) {
      cv::imwrite((dir_.path() / rgb_[i].file).string(),
                  cv::Mat(6, 8, CV_8UC3, cv::Scalar(10 * i, 10 * i + 1, 10 * i + 2)));
      cv::imwrite((dir_.path() / depth_[i].file).string(),
                  cv::Mat(6, 8, CV_16UC1, cv::Scalar(1000 + i)));
    }
  }
  std::string spec() const { return "tum:" + dir_.path().string(); }

  TempDir dir_{"tum_images"};
  std::vector<ListEntry> rgb_, depth_;
};

TEST_F(TumImagesTest, ReadsAssociatedColourAndDepth) {
  ReaderOptions options;
  options.max_frames = 5;
  const auto reader = openDataset(spec(), options);
  EXPECT_EQ(reader->size(), 5u);
  std::size_t count = 0;
  while (const auto frame = reader->next()) {
    ASSERT_EQ(frame->image.type(), CV_8UC3);  // colour kept for TUM rgb
    ASSERT_EQ(frame->depth.type(), CV_16UC1);
    const int rgb_row = frame->image.at<cv::Vec3b>(0, 0)[0] / 10;
    const int depth_row = frame->depth.at<std::uint16_t>(0, 0) - 1000;
    EXPECT_EQ(frame->timestamp, rgb_[rgb_row].timestamp);
    EXPECT_EQ(frame->image_path, dir_.path() / rgb_[rgb_row].file);
    EXPECT_LT(std::abs(rgb_[rgb_row].timestamp - depth_[depth_row].timestamp), 0.02);
    EXPECT_EQ(frame->index, count);
    ++count;
  }
  EXPECT_EQ(count, 5u);
}

TEST_F(TumImagesTest, CorruptImageIsAnErrorOrASkip) {
  // Row 1 is associated (row 2 is not: its two nearest depth images go to closer rgb images).
  const fs::path corrupt = dir_.path() / rgb_[1].file;
  writeBytes(corrupt, "\x89PNG\r\n\x1a\n this is not really a png");
  ReaderOptions options;
  options.max_frames = 5;
  {
    const auto reader = openDataset(spec(), options);
    const std::string message = errorOf([&] {
      while (reader->next()) {
      }
    });
    EXPECT_NE(message.find(corrupt.string() + ": cannot decode image"), std::string::npos)
        << message;
  }
  options.skip_unreadable_images = true;
  const auto reader = openDataset(spec(), options);
  std::vector<double> timestamps;
  while (const auto frame = reader->next()) timestamps.push_back(frame->timestamp);
  EXPECT_EQ(timestamps.size(), 4u);
  for (double t : timestamps) EXPECT_NE(t, rgb_[1].timestamp);
}

TEST_F(TumImagesTest, MissingDepthImageNamesTheFile) {
  const fs::path missing = dir_.path() / depth_[0].file;
  fs::remove(missing);
  const auto reader = openDataset(spec());
  EXPECT_ERROR_CONTAINS(reader->next(), missing.string() + ": image file not found");
}

TEST_F(TumImagesTest, EightBitDepthImageIsAnError) {
  const fs::path depth = dir_.path() / depth_[0].file;
  cv::imwrite(depth.string(), cv::Mat(6, 8, CV_8UC1, cv::Scalar(7)));
  const auto reader = openDataset(spec());
  EXPECT_ERROR_CONTAINS(reader->next(), depth.string() + ": depth image must be 16-bit");
}

// ---------------------------------------------------------------- EuRoC

TEST(EurocReader, ReadsStereoMicroSequenceWithCalibration) {
  const fs::path root = dataDir() / kEurocDir;
  const auto reader = openDataset("euroc:" + root.string());
  ASSERT_EQ(reader->size(), 95u);
  EXPECT_TRUE(reader->isStereo());
  EXPECT_FALSE(reader->hasDepth());

  const auto calibration = reader->calibration();
  ASSERT_TRUE(calibration);
  EXPECT_DOUBLE_EQ(calibration->left.fx, 458.654);
  EXPECT_DOUBLE_EQ(calibration->left.fy, 457.296);
  EXPECT_DOUBLE_EQ(calibration->left.cx, 367.215);
  EXPECT_DOUBLE_EQ(calibration->left.cy, 248.375);
  EXPECT_EQ(calibration->left.size, (camera::ImageSize{752, 480}));
  EXPECT_EQ(calibration->left.model, camera::CameraModel::Pinhole);
  EXPECT_DOUBLE_EQ(calibration->left.distortion[0], -0.28340811);
  EXPECT_DOUBLE_EQ(calibration->left.distortion[3], 1.76187114e-05);
  EXPECT_DOUBLE_EQ(calibration->left.distortion[4], 0.0);  // k3: EuRoC lists four
  EXPECT_DOUBLE_EQ(calibration->left.fps, 20.0);
  ASSERT_TRUE(calibration->right);
  EXPECT_DOUBLE_EQ(calibration->right->fx, 457.587);
  // The VI-sensor's stereo baseline is about 11 cm, mostly along the left camera's x axis.
  EXPECT_NEAR(calibration->baseline(), 0.110, 0.002);
  EXPECT_GT(calibration->T_left_right->translation().x(), 0.109);

  std::size_t count = 0;
  double previous = 0.0;
  while (const auto frame = reader->next()) {
    if (count == 0) {
      EXPECT_DOUBLE_EQ(frame->timestamp, 1403715273.262142976);
      EXPECT_EQ(frame->image.type(), CV_8UC1);
      EXPECT_EQ(frame->image.size(), cv::Size(752, 480));
      EXPECT_EQ(frame->right.size(), cv::Size(752, 480));
      EXPECT_EQ(frame->image_path.filename(), "1403715273262142976.png");
    } else {
      EXPECT_NEAR(frame->timestamp - previous, 0.05, 1e-6);
    }
    EXPECT_FALSE(frame->right.empty());
    previous = frame->timestamp;
    ++count;
  }
  EXPECT_EQ(count, 95u);

  const Trajectory gt = reader->groundTruth();  // ORB-SLAM3's cam0 csv in the dataset root
  ASSERT_EQ(gt.size(), 74u);
  EXPECT_DOUBLE_EQ(gt.front().timestamp, 1403715274.312143104);
  EXPECT_EQ(loadGroundTruth("euroc:" + root.string()).size(), 74u);
}

TEST(EurocReader, MonoModeAndFrameLimits) {
  ReaderOptions options;
  options.first_frame = 90;
  const auto reader = openDataset("euroc-mono:" + (dataDir() / kEurocDir).string(), options);
  EXPECT_FALSE(reader->isStereo());
  EXPECT_EQ(reader->size(), 5u);
  const auto frame = reader->next();
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->index, 90u);
  EXPECT_TRUE(frame->right.empty());
  EXPECT_DOUBLE_EQ(frame->timestamp, 1403715277.762142976);
}

TEST(EurocSensorYaml, ReadsFilesWithoutYamlHeader) {
  TempDir dir("euroc_yaml");
  std::ifstream original(dataDir() / kEurocDir / "mav0/cam1/sensor.yaml");
  std::string first_line, rest;
  std::getline(original, first_line);
  ASSERT_EQ(first_line, "%YAML:1.0");
  rest.assign(std::istreambuf_iterator<char>(original), {});
  writeBytes(dir.path() / "sensor.yaml", rest);  // as in the original EuRoC download
  const auto camera = readEurocCameraYaml(dir.path() / "sensor.yaml");
  ASSERT_TRUE(camera.camera);
  EXPECT_DOUBLE_EQ(camera.camera->fx, 457.587);
  EXPECT_DOUBLE_EQ(camera.camera->cy, 255.238);
  EXPECT_EQ(camera.distortion_model, "radial-tangential");
  EXPECT_NEAR(camera.T_body_cam.translation().y(), 0.0453689425024, 1e-12);
  EXPECT_NEAR(camera.T_body_cam.linear().determinant(), 1.0, 1e-12);

  writeBytes(dir.path() / "broken.yaml", "camera_model: pinhole\nresolution: [752, 480]\n");
  EXPECT_ERROR_CONTAINS(readEurocCameraYaml(dir.path() / "broken.yaml"),
                        "broken.yaml: key 'intrinsics' is missing");
  writeBytes(dir.path() / "short.yaml", "intrinsics: [1, 2, 3]\n");
  EXPECT_ERROR_CONTAINS(readEurocCameraYaml(dir.path() / "short.yaml"),
                        "key 'intrinsics': expected 4 numbers, found 3");
  const std::string camera_lines = "intrinsics: [400, 400, 320, 240]\nresolution: [640, 480]\n";
  writeBytes(dir.path() / "three.yaml", camera_lines +
                                            "distortion_model: radial-tangential\n"
                                            "distortion_coefficients: [0.1, 0.2, 0.3]\n");
  EXPECT_ERROR_CONTAINS(readEurocCameraYaml(dir.path() / "three.yaml"),
                        "key 'distortion_coefficients': expected 4 or 5 numbers");
}

// A fisheye model (TUM-VI's equidistant) has no camera/ model: the dataset still reads, with
// its body transform for the ground truth, but offers no calibration hint.
TEST(EurocSensorYaml, ADistortionModelCameraHasNoModelForGivesNoCamera) {
  TempDir dir("euroc_yaml_equidistant");
  writeBytes(dir.path() / "sensor.yaml",
             "intrinsics: [190.9, 190.9, 254.9, 256.9]\nresolution: [512, 512]\n"
             "distortion_model: equidistant\n"
             "distortion_coefficients: [0.003, 0.0007, -0.002, 0.0002]\n");
  const auto camera = readEurocCameraYaml(dir.path() / "sensor.yaml");
  EXPECT_FALSE(camera.camera);
  EXPECT_EQ(camera.distortion_model, "equidistant");
  EXPECT_TRUE(camera.T_body_cam.isApprox(SE3::Identity()));
  writeBytes(dir.path() / "none.yaml",
             "intrinsics: [400, 400, 320, 240]\nresolution: [640, 480]\n"
             "distortion_model: none\n");
  const auto undistorted = readEurocCameraYaml(dir.path() / "none.yaml");
  ASSERT_TRUE(undistorted.camera);
  EXPECT_FALSE(undistorted.camera->hasDistortion());
}

TEST(EurocReader, ConvertsBodyGroundTruthToCam0) {
  TempDir dir("euroc_gt");
  const fs::path mav0 = dir.path() / "mav0";
  fs::create_directories(mav0 / "cam0");
  fs::create_directories(mav0 / "state_groundtruth_estimate0");
  fs::copy_file(dataDir() / kEurocDir / "mav0/cam0/sensor.yaml", mav0 / "cam0/sensor.yaml");
  Trajectory body;
  for (int i = 0; i < 5; ++i) {
    StampedPose pose;
    pose.timestamp = 1403715273.0 + 0.005 * i;
    pose.T_w_c.linear() = Eigen::AngleAxisd(0.2 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.T_w_c.translation() = Eigen::Vector3d(i, 2.0 * i, 1.0);
    body.push_back(pose);
  }
  writeTrajectory(mav0 / "state_groundtruth_estimate0/data.csv", body, TrajectoryFormat::EurocCsv);
  const SE3 T_BS = readEurocCameraYaml(mav0 / "cam0/sensor.yaml").T_body_cam;
  const Trajectory camera = loadGroundTruth("euroc:" + dir.path().string());
  ASSERT_EQ(camera.size(), body.size());
  for (std::size_t i = 0; i < body.size(); ++i)
    EXPECT_TRUE(camera[i].T_w_c.isApprox(body[i].T_w_c * T_BS, 1e-12)) << i;
  // The cam0 origin sits T_BS's translation (~6.8 cm) away from the body origin.
  EXPECT_NEAR((camera[0].T_w_c.translation() - body[0].T_w_c.translation()).norm(),
              T_BS.translation().norm(), 1e-12);
}

// ---------------------------------------------------------------- KITTI

TEST(KittiReader, ReadsSequence07Excerpt) {
  const fs::path sequence = dataDir() / kKittiSequence;
  const auto reader = openDataset("kitti:" + sequence.string());
  EXPECT_EQ(reader->size(), 160u);
  EXPECT_FALSE(reader->isStereo());  // the excerpt has no image_1/
  const auto calibration = reader->calibration();
  ASSERT_TRUE(calibration);
  EXPECT_DOUBLE_EQ(calibration->left.fx, 707.0912);
  EXPECT_DOUBLE_EQ(calibration->left.cx, 601.8873);
  EXPECT_DOUBLE_EQ(calibration->left.cy, 183.1104);
  EXPECT_EQ(calibration->left.size, (camera::ImageSize{1226, 370}));
  EXPECT_EQ(calibration->left.model, camera::CameraModel::Rectified);
  EXPECT_DOUBLE_EQ(calibration->left.fps, 10.0);

  const auto frame = reader->next();
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->image.size(), cv::Size(1226, 370));
  EXPECT_EQ(frame->image.type(), CV_8UC1);
  EXPECT_EQ(frame->timestamp, 0.0);

  const Trajectory gt = reader->groundTruth();  // found at ../../poses/07.txt
  ASSERT_EQ(gt.size(), 160u);
  double length = 0.0;
  for (std::size_t i = 1; i < gt.size(); ++i)
    length += (gt[i].T_w_c.translation() - gt[i - 1].T_w_c.translation()).norm();
  EXPECT_NEAR(length, 90.6, 0.5);
  EXPECT_DOUBLE_EQ(gt.back().timestamp, 16.53376);
  EXPECT_EQ(loadGroundTruth("kitti:" + (sequence / "").string()).size(), 160u);

  ReaderOptions options;
  options.first_frame = 157;
  const auto tail = openDataset("kitti-mono:" + sequence.string(), options);
  std::vector<std::size_t> indices;
  while (const auto f = tail->next()) indices.push_back(f->index);
  EXPECT_EQ(indices, (std::vector<std::size_t>{157, 158, 159}));
}

TEST(KittiReader, StereoBaselineFromCalib) {
  const auto hint = KittiReader::readCalibration(dataDir() / kKittiSequence / "calib.txt");
  ASSERT_TRUE(hint.T_left_right);
  EXPECT_NEAR(hint.baseline(), 379.8145 / 707.0912, 1e-9);  // 0.537 m
  EXPECT_GT(hint.T_left_right->translation().x(), 0.0);
}

// ---------------------------------------------------------------- video and folder

TEST(VideoReader, ReadsFirstFramesOfVtest) {
  const fs::path video = dataDir() / "opencv_samples/vtest/vtest.avi";
  EXPECT_EQ(openDataset("video:" + video.string())->size(), 795u);
  ReaderOptions options;
  options.max_frames = 3;
  const auto reader = openDataset("video:" + video.string(), options);
  EXPECT_EQ(reader->size(), 3u);
  std::vector<double> timestamps;
  while (const auto frame = reader->next()) {
    EXPECT_EQ(frame->image.size(), cv::Size(768, 576));
    EXPECT_EQ(frame->image.type(), CV_8UC3);
    timestamps.push_back(frame->timestamp);
  }
  ASSERT_EQ(timestamps.size(), 3u);
  EXPECT_NEAR(timestamps[1] - timestamps[0], 0.1, 1e-6);  // 10 fps
  EXPECT_NEAR(timestamps[2] - timestamps[1], 0.1, 1e-6);

  options.first_frame = 50;
  options.max_frames = 1;
  options.image_read_flags = cv::IMREAD_GRAYSCALE;
  const auto later = openDataset("video:" + video.string(), options);
  const auto frame = later->next();
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->index, 50u);
  EXPECT_NEAR(frame->timestamp, 5.0, 1e-6);
  EXPECT_EQ(frame->image.type(), CV_8UC1);
  EXPECT_FALSE(later->next());
}

TEST(FolderReader, ReadsImagesInNameOrderWithTimestamps) {
  TempDir dir("folder");
  for (int i = 0; i < 4; ++i)
    cv::imwrite((dir.path() / fmt::format("img_{:03d}.png", i)).string(),
                cv::Mat(4, 5, CV_8UC1, cv::Scalar(i)));
  writeBytes(dir.path() / "notes.txt", "not an image");
  ReaderOptions options;
  options.fps = 20.0;
  auto reader = openDataset("folder:" + dir.path().string(), options);
  EXPECT_EQ(reader->size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const auto frame = reader->next();
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->image.at<cv::Vec3b>(0, 0)[0], i);  // name order, read as colour
    EXPECT_DOUBLE_EQ(frame->timestamp, i / 20.0);
  }
  EXPECT_FALSE(reader->next());

  writeBytes(dir.path() / "times.txt", "# t\n10.5\n11\n11.25\n12\n");
  options.timestamps = dir.path() / "times.txt";
  reader = openDataset("folder:" + dir.path().string(), options);
  reader->next();
  EXPECT_DOUBLE_EQ(reader->next()->timestamp, 11.0);

  writeBytes(dir.path() / "short_times.txt", "1\n2\n3\n");
  options.timestamps = dir.path() / "short_times.txt";
  EXPECT_ERROR_CONTAINS(openDataset("folder:" + dir.path().string(), options),
                        "short_times.txt: 3 timestamps for 4 images");

  writeBytes(dir.path() / "list.txt", "5.0 img_003.png\n6.0 img_001.png\n");
  options.timestamps = dir.path() / "list.txt";
  reader = openDataset("folder:" + dir.path().string(), options);
  EXPECT_EQ(reader->size(), 2u);
  EXPECT_EQ(reader->next()->image.at<cv::Vec3b>(0, 0)[0], 3);
}

TEST(FolderReader, ReadsRealJpegFolder) {
  ReaderOptions options;
  options.max_frames = 1;
  const auto reader = openDataset(
      "folder:" + (dataDir() / "llvip/night_people_sample/visible/test").string(), options);
  const auto frame = reader->next();
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->image.size(), cv::Size(1280, 1024));
  EXPECT_EQ(frame->image.type(), CV_8UC3);
  EXPECT_EQ(frame->image_path.filename(), "190001.jpg");
}

// ---------------------------------------------------------------- bad input

TEST(OpenDataset, BadSpecsAndFoldersGiveClearErrors) {
  TempDir dir("bad_specs");
  EXPECT_ERROR_CONTAINS(openDataset("bag:" + dir.path().string()), "expected KIND:PATH");
  EXPECT_ERROR_CONTAINS(openDataset("tum:"), "path after 'tum:' is empty");
  const fs::path missing = dir.path() / "nowhere";
  EXPECT_ERROR_CONTAINS(openDataset("euroc:" + missing.string()),
                        missing.string() + ": dataset path not found");
  EXPECT_ERROR_CONTAINS(openDataset("folder:" + dir.path().string()), "empty sequence");
  EXPECT_ERROR_CONTAINS(openDataset("euroc:" + dir.path().string()), "no mav0/ folder");
  EXPECT_ERROR_CONTAINS(openDataset("kitti:" + dir.path().string()), "no image_0/ folder");
  EXPECT_ERROR_CONTAINS(openDataset("tum:" + dir.path().string()),
                        (dir.path() / "rgb.txt").string() + ": file not found");
  EXPECT_ERROR_CONTAINS(loadGroundTruth("folder:" + dir.path().string()), "has no ground truth");

  writeBytes(dir.path() / "rgb.txt", "# only comments\n");
  EXPECT_ERROR_CONTAINS(openDataset("tum-mono:" + dir.path().string()), "rgb.txt: empty sequence");
  writeBytes(dir.path() / "rgb.txt", "1.0 rgb/a.png\nnot-a-time rgb/b.png\n");
  EXPECT_ERROR_CONTAINS(openDataset("tum-mono:" + dir.path().string()),
                        "rgb.txt:2: bad number 'not-a-time'");

  writeBytes(dir.path() / "rgb.txt", "2.0 rgb/a.png\n1.0 rgb/b.png\n");
  EXPECT_ERROR_CONTAINS(openDataset("tum-mono:" + dir.path().string()),
                        "rgb.txt:2: timestamp 1.0 does not increase");

  const fs::path fake_video = dir.path() / "fake.avi";
  writeBytes(fake_video, "RIFF this is not a video at all");
  EXPECT_ERROR_CONTAINS(openDataset("video:" + fake_video.string()), fake_video.string());

  ReaderOptions options;
  options.first_frame = 160;
  EXPECT_ERROR_CONTAINS(openDataset("kitti:" + (dataDir() / kKittiSequence).string(), options),
                        "first frame 160 is past the end of the 160 frames");
}

}  // namespace
}  // namespace lumaslam::io
