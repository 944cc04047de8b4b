// The report's sample-frame marks on runs whose tracked image is not the image as read (issue
// 18): an unrectified stereo pair (the real EuRoC excerpt, rectified by the Pipeline) and a
// synthetic RGB-D run resized by Camera.newWidth/newHeight. moving_features.txt is in the
// tracked image's pixels, so the report must draw on that image: the keypoints it extracts
// again are then the run's (green = kept, exactly), and the dropped features are red where the
// file puts them in a picture of the tracked image's size.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "report_marks.h"
#include "test_cli.h"

namespace {

using lumaslam::test::copyWithoutMarks;
using lumaslam::test::enhancedImage;
using lumaslam::test::keyText;
using lumaslam::test::markedFrames;
using lumaslam::test::markLines;
using lumaslam::test::positionsMarkedRed;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

namespace fs = std::filesystem;

// --enhance off in both runs: the report extracts again exactly the run's keypoints only
// without an enhancer's online statistics.
constexpr const char* kRunOptions = " --enhance off --sequential --report --out ";

// The report of `out` checked against its moving_features.txt: every sample frame's green
// keypoints are the run's kept ones, at least two frames dropped features, and those are red
// in the drawn picture (of `tracked_width` pixels, the tracked image's, at most 480) and not
// in the picture of a report made without the file.
void expectMarksWhereTheRunFoundThem(const fs::path& out, const fs::path& unmarked_dir,
                                     int tracked_width) {
  const std::string html = readTextFile(out / "report.html");
  ASSERT_EQ(runCli("report " + copyWithoutMarks(out, unmarked_dir).string()).exit_code, 0);
  const std::string unmarked = readTextFile(unmarked_dir / "report.html");
  const auto lines = markLines(out / "moving_features.txt");
  const auto frames = markedFrames(html);
  ASSERT_EQ(frames.size(), 3U) << "first, middle and last tracked frame";
  int frames_with_dropped = 0;
  for (const long frame : frames) {
    const auto& line = lines.at(frame);
    const auto dropped = static_cast<int>(line.at(3) + line.at(4));
    const auto kept = static_cast<long>(line.at(1)) - dropped;
    const std::string key = "frame." + std::to_string(frame) + ".";
    EXPECT_EQ(keyText(html, key + "green"), std::to_string(kept)) << frame;
    const cv::Mat marked_image = enhancedImage(html, frame);
    const cv::Mat unmarked_image = enhancedImage(unmarked, frame);
    ASSERT_FALSE(marked_image.empty());
    ASSERT_FALSE(unmarked_image.empty());
    EXPECT_EQ(marked_image.cols, std::min(tracked_width, 480)) << frame;
    if (dropped == 0) continue;
    ++frames_with_dropped;
    const double scale = marked_image.cols / static_cast<double>(tracked_width);
    EXPECT_EQ(positionsMarkedRed(marked_image, line, scale), dropped) << frame;
    EXPECT_LT(positionsMarkedRed(unmarked_image, line, scale), dropped / 2) << frame;
  }
  EXPECT_GE(frames_with_dropped, 2) << "sample frames with features dropped";
  EXPECT_EQ(html.find("class=\"note\">Sample frames"), std::string::npos) << "frames failed";
}

// The first `frames` cam0 timestamps of a EuRoC folder, in seconds as the box file takes them.
std::vector<std::string> eurocTimestamps(const fs::path& root, int frames) {
  std::ifstream csv(root / "mav0" / "cam0" / "data.csv");
  std::vector<std::string> stamps;
  for (std::string line; std::getline(csv, line) && static_cast<int>(stamps.size()) < frames;) {
    if (line.empty() || line.starts_with('#')) continue;
    const std::string ns = line.substr(0, line.find(','));
    stamps.push_back(ns.substr(0, ns.size() - 9) + "." + ns.substr(ns.size() - 9));
  }
  return stamps;
}

class CliReportMarksStereo : public ::testing::Test {
 protected:
  static constexpr int kFrames = 12;

  // A box near the left edge on even frames and near the right edge on odd ones, where the
  // rectification moves pixels most: each frame drops the features in its box (the previous
  // frame's box, on the other side, only masks where features are taken).
  static void writeBoxes(const fs::path& file) {
    std::ofstream out(file);
    int frame = 0;
    for (const std::string& stamp : eurocTimestamps(root(), kFrames)) {
      out << stamp << (frame++ % 2 == 0 ? " person 10 30 190 300\n" : " person 550 150 190 300\n");
    }
  }

  static void SetUpTestSuite() {
    ASSERT_TRUE(fs::exists(root()))
        << root() << " is missing: the shared data is a required test input (LUMASLAM_SHARED_DIR)";
    dir_ = std::make_unique<TempDir>("cli_report_marks_stereo");
    writeBoxes(dir_->path() / "boxes.txt");
    const auto settings = lumaslam::test::sourceDir() / "configs" / "euroc_stereo.yaml";
    const auto run = runCli("run --dataset euroc:" + root().string() + " --settings " +
                            settings.string() + " --max-frames " + std::to_string(kFrames) +
                            " --detector boxes:" + (dir_->path() / "boxes.txt").string() +
                            kRunOptions + out().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static fs::path root() { return lumaslam::test::dataDir() / "euroc" / "V1_01_easy_micro"; }
  static fs::path out() { return dir_->path() / "out"; }

  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> CliReportMarksStereo::dir_;

TEST_F(CliReportMarksStereo, TheMarksAreDrawnOnTheRectifiedImage) {
  ASSERT_NE(readTextFile(out() / "moving_features.txt").find("\nimage 752 480\n"),
            std::string::npos);
  expectMarksWhereTheRunFoundThem(out(), dir_->path() / "unmarked", 752);
  EXPECT_NE(readTextFile(out() / "report.html").find("as tracking takes it (rectified)"),
            std::string::npos);
}

class CliReportMarksResized : public ::testing::Test {
 protected:
  // The settings with Camera.newWidth/newHeight at half the 640x480 images.
  static fs::path resizedSettings() {
    const auto file = dir_->path() / "resized.yaml";
    std::ofstream(file) << readTextFile(data() / "settings.yaml")
                        << "\nCamera.newWidth: 320\nCamera.newHeight: 240\n";
    return file;
  }

  // detections.txt at half size: the run takes a box file's boxes in the pixels of the image
  // it detects on, the resized one. Whole pixels, as moving_features.txt keeps the boxes that
  // the report makes the extraction mask again from.
  static fs::path halfSizeBoxes() {
    const auto file = dir_->path() / "boxes.txt";
    std::ifstream in(data() / "detections.txt");
    std::ofstream out(file);
    for (std::string line; std::getline(in, line);) {
      std::stringstream fields(line);
      std::string stamp, name;
      int x = 0, y = 0, w = 0, h = 0;
      if (line.starts_with('#') || !(fields >> stamp >> name >> x >> y >> w >> h)) continue;
      out << stamp << ' ' << name << ' ' << x / 2 << ' ' << y / 2 << ' ' << w / 2 << ' ' << h / 2
          << '\n';
    }
    return file;
  }

  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>("cli_report_marks_resized");
    const auto synth =
        runCli("synth " + data().string() + " --preset walking-xyz-rgbd --frames 16 --seed 5");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    const auto run = runCli(
        "run --dataset tum:" + data().string() + " --settings " + resizedSettings().string() +
        " --detector boxes:" + halfSizeBoxes().string() + kRunOptions + out().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static fs::path data() { return dir_->path() / "data"; }
  static fs::path out() { return dir_->path() / "out"; }

  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> CliReportMarksResized::dir_;

TEST_F(CliReportMarksResized, TheMarksAreDrawnOnTheResizedImage) {
  ASSERT_NE(readTextFile(out() / "moving_features.txt").find("\nimage 320 240\n"),
            std::string::npos);
  expectMarksWhereTheRunFoundThem(out(), dir_->path() / "unmarked", 320);
  EXPECT_NE(readTextFile(out() / "report.html").find("as tracking takes it (resized to 320x240)"),
            std::string::npos);
}

}  // namespace
