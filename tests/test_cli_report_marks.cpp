// moving_features.txt and the marks of the report's sample frames (issue 18): a synthetic
// walking-people run with the generator's true boxes writes, per frame, the boxes and the
// features it dropped, with timing.csv's counts; the report's sample frames draw them red with
// the run's counts; a run folder without the file still gives a report, and a broken file is
// said in the section while the rest of the report is written.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
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
using lumaslam::test::timingRows;

namespace fs = std::filesystem;

class CliReportMarks : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>("cli_report_marks");
    const auto synth =
        runCli("synth " + data().string() + " --preset walking-xyz-rgbd --frames 40 --seed 5");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    // --enhance off: the report extracts again exactly the run's keypoints (an enhancer's
    // online statistics are not kept), so that what it draws green can be checked.
    const auto run = runCli("run --dataset tum:" + data().string() +
                            " --detector boxes:" + (data() / "detections.txt").string() +
                            " --enhance off --sequential --report --out " + out().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static fs::path data() { return dir_->path() / "data"; }
  static fs::path out() { return dir_->path() / "out"; }

  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> CliReportMarks::dir_;

TEST_F(CliReportMarks, TheFileHasEveryFrameWithTimingsCounts) {
  const auto file = out() / "moving_features.txt";
  ASSERT_TRUE(fs::exists(file));
  const auto timing = timingRows(out() / "timing.csv");
  const auto lines = markLines(file);
  ASSERT_EQ(lines.size(), timing.size());
  double dropped_total = 0;
  for (const auto& [frame, row] : timing) {
    ASSERT_TRUE(lines.count(frame)) << "frame " << frame;
    const auto& numbers = lines.at(frame);
    const double boxes = numbers.at(2), dropped = numbers.at(3), moving = numbers.at(4);
    EXPECT_EQ(boxes, std::stod(row.at("boxes"))) << "frame " << frame;
    EXPECT_EQ(dropped, std::stod(row.at("dropped_features"))) << "frame " << frame;
    EXPECT_EQ(moving, std::stod(row.at("moving_features"))) << "frame " << frame;
    EXPECT_EQ(static_cast<double>(numbers.size()), 5 + 4 * boxes + 2 * (dropped + moving))
        << "frame " << frame;
    EXPECT_GE(numbers.at(1), dropped + moving) << "frame " << frame;
    dropped_total += dropped;
  }
  EXPECT_GT(dropped_total, 0.0) << "the walking people's features are dropped";
  const auto manifest = nlohmann::json::parse(readTextFile(out() / "manifest.json"));
  bool listed = false;
  for (const auto& entry : manifest["files"]) {
    if (entry["name"] == "moving_features.txt") {
      listed = entry["bytes"].get<std::uintmax_t>() == fs::file_size(file);
    }
  }
  EXPECT_TRUE(listed) << manifest.dump(2);
}

TEST_F(CliReportMarks, SampleFramesMarkTheDroppedFeaturesWithTheRunsCounts) {
  const std::string html = readTextFile(out() / "report.html");
  const auto timing = timingRows(out() / "timing.csv");
  const auto frames = markedFrames(html);
  ASSERT_EQ(frames.size(), 3U) << "first, middle and last tracked frame";
  ASSERT_NE(readTextFile(out() / "moving_features.txt").find("\nimage 640 480\n"),
            std::string::npos);
  const auto unmarked_dir = copyWithoutMarks(out(), dir_->path() / "unmarked");
  ASSERT_EQ(runCli("report " + unmarked_dir.string()).exit_code, 0);
  const std::string unmarked = readTextFile(unmarked_dir / "report.html");
  const auto lines = markLines(out() / "moving_features.txt");
  int frames_with_dropped = 0;
  for (const long frame : frames) {
    const auto& row = timing.at(frame);
    const std::string key = "frame." + std::to_string(frame) + ".";
    EXPECT_EQ(keyText(html, key + "by_boxes"), row.at("dropped_features")) << frame;
    EXPECT_EQ(keyText(html, key + "by_motion_test"), row.at("moving_features")) << frame;
    EXPECT_EQ(keyText(html, key + "boxes"), row.at("boxes")) << frame;
    const long dropped =
        std::stol(row.at("dropped_features")) + std::stol(row.at("moving_features"));
    EXPECT_EQ(keyText(html, key + "dropped"), std::to_string(dropped)) << frame;
    if (dropped == 0) continue;
    ++frames_with_dropped;
    const cv::Mat marked_image = enhancedImage(html, frame);
    const cv::Mat unmarked_image = enhancedImage(unmarked, frame);
    ASSERT_FALSE(marked_image.empty());
    ASSERT_FALSE(unmarked_image.empty());
    const double scale = marked_image.cols / 640.0;  // the file's "image 640 480"
    EXPECT_EQ(positionsMarkedRed(marked_image, lines.at(frame), scale), dropped) << frame;
    EXPECT_LT(positionsMarkedRed(unmarked_image, lines.at(frame), scale), dropped / 2) << frame;
  }
  EXPECT_GT(frames_with_dropped, 0) << "a sample frame with features dropped";
  EXPECT_EQ(html.find("class=\"note\""), std::string::npos) << "a section says something failed";
}

// Green is what the run kept: the keypoints extracted again outside the previous frame's
// boxes (as the run took them), minus those at the run's dropped features.
TEST_F(CliReportMarks, TheKeypointsDrawnGreenAreTheOnesTheRunKept) {
  const std::string html = readTextFile(out() / "report.html");
  const auto lines = markLines(out() / "moving_features.txt");
  const auto frames = markedFrames(html);
  ASSERT_EQ(frames.size(), 3U);
  for (const long frame : frames) {
    const auto& line = lines.at(frame);
    const auto kept = static_cast<long>(line.at(1) - line.at(3) - line.at(4));
    const std::string key = "frame." + std::to_string(frame) + ".";
    EXPECT_EQ(keyText(html, key + "kept"), std::to_string(kept)) << frame;
    EXPECT_EQ(keyText(html, key + "green"), std::to_string(kept)) << frame;
  }
}

TEST_F(CliReportMarks, AnOldRunFolderWithoutTheFileStillGivesAReport) {
  const auto old = copyWithoutMarks(out(), dir_->path() / "old");
  const auto report = runCli("report " + old.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string html = readTextFile(old / "report.html");
  EXPECT_NE(html.find("No feature is marked: the run folder has no moving_features.txt"),
            std::string::npos);
  EXPECT_TRUE(markedFrames(html).empty());
  EXPECT_NE(html.find("alt=\"enhanced frame "), std::string::npos);
  EXPECT_EQ(html.find("class=\"note\""), std::string::npos) << "an old folder is no failure";
}

TEST_F(CliReportMarks, ABrokenFileIsSaidInTheSectionAndTheRestIsWritten) {
  const auto broken = copyWithoutMarks(out(), dir_->path() / "broken");
  std::ofstream(broken / "moving_features.txt") << "image 640 480\n0 100 1 2 0 10 10 5\n";
  const auto report = runCli("report " + broken.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string html = readTextFile(broken / "report.html");
  EXPECT_NE(html.find("No feature is marked: "), std::string::npos);
  EXPECT_NE(html.find("moving_features.txt: line 2: 8 fields, 13 expected"), std::string::npos);
  EXPECT_TRUE(markedFrames(html).empty());
  for (const char* section :
       {"id=\"evaluation\"", "id=\"timing\"", "id=\"moving\"", "alt=\"enhanced frame "}) {
    EXPECT_NE(html.find(section), std::string::npos) << section;
  }
}

}  // namespace
