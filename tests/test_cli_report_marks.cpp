// moving_features.txt and the marks of the report's sample frames (issue 18): a synthetic
// walking-people run with the generator's true boxes writes, per frame, the boxes and the
// features it dropped, with timing.csv's counts; the report's sample frames draw them red with
// the run's counts; a run folder without the file still gives a report, and a broken file is
// said in the section while the rest of the report is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "test_cli.h"

namespace {

using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

namespace fs = std::filesystem;

// timing.csv as rows of column name -> field, keyed by frame.
std::map<long, std::map<std::string, std::string>> timingRows(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> columns;
  std::stringstream header(line);
  for (std::string field; std::getline(header, field, ',');) columns.push_back(field);
  std::map<long, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::map<std::string, std::string> row;
    std::string field;
    for (const std::string& column : columns) {
      std::getline(fields, field, ',');
      row[column] = field;
    }
    rows[std::stol(row.at("frame"))] = row;
  }
  return rows;
}

// moving_features.txt's frame lines as their whitespace-separated numbers, keyed by frame.
std::map<long, std::vector<double>> markLines(const fs::path& file) {
  std::ifstream in(file);
  std::map<long, std::vector<double>> lines;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line.starts_with('#') || line.starts_with("image ")) continue;
    std::stringstream fields(line);
    std::vector<double> numbers;
    for (double value = 0; fields >> value;) numbers.push_back(value);
    lines[static_cast<long>(numbers.at(0))] = numbers;
  }
  return lines;
}

// The text of the element carrying data-key="KEY"; empty when there is none.
std::string keyText(const std::string& html, const std::string& key) {
  const auto at = html.find("data-key=\"" + key + "\"");
  if (at == std::string::npos) return {};
  const auto begin = html.find('>', at) + 1;
  return html.substr(begin, html.find('<', begin) - begin);
}

// The frame index of every data-key="frame.N.dropped" in the page.
std::vector<long> markedFrames(const std::string& html) {
  std::vector<long> frames;
  const std::string opening = "data-key=\"frame.";
  for (auto at = html.find(opening); at != std::string::npos; at = html.find(opening, at + 1)) {
    const auto begin = at + opening.size();
    const auto dot = html.find('.', begin);
    const std::string_view suffix = ".dropped\"";
    if (html.compare(dot, suffix.size(), suffix) == 0) {
      frames.push_back(std::stol(html.substr(begin, dot - begin)));
    }
  }
  return frames;
}

// The decoded <img class="enhanced"> of frame N (empty when there is none).
cv::Mat enhancedImage(const std::string& html, long frame) {
  const auto at = html.find("alt=\"enhanced frame " + std::to_string(frame) + "\"");
  if (at == std::string::npos) return {};
  const std::string prefix = "src=\"data:image/jpeg;base64,";
  const auto begin = html.find(prefix, at) + prefix.size();
  const std::string text = html.substr(begin, html.find('"', begin) - begin);
  static const std::string digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned int block = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    block = (block << 6) | static_cast<unsigned int>(digits.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<unsigned char>((block >> bits) & 0xFF));
    }
  }
  return cv::imdecode(bytes, cv::IMREAD_COLOR);
}

// Strongly red (the marks are drawn in pure red, BGR 0 0 255).
bool isRed(const cv::Vec3b& p) {
  return p[2] > 180 && p[1] < 80 && p[0] < 80;
}

// The dropped and moving positions of a moving_features.txt line (after the counts and boxes),
// each with a red pixel within 4 pixels of it once scaled by `scale` to the drawn image.
int positionsMarkedRed(const cv::Mat& bgr, const std::vector<double>& line, double scale) {
  const auto boxes = static_cast<std::size_t>(line.at(2));
  int marked = 0;
  for (std::size_t at = 5 + 4 * boxes; at + 1 < line.size(); at += 2) {
    const int cx = static_cast<int>(line[at] * scale);
    const int cy = static_cast<int>(line[at + 1] * scale);
    bool red = false;
    for (int y = std::max(cy - 4, 0); y <= std::min(cy + 4, bgr.rows - 1); ++y) {
      for (int x = std::max(cx - 4, 0); x <= std::min(cx + 4, bgr.cols - 1); ++x) {
        red = red || isRed(bgr.at<cv::Vec3b>(y, x));
      }
    }
    marked += red ? 1 : 0;
  }
  return marked;
}

// A copy of the run folder's results for the report, without moving_features.txt.
fs::path copyWithoutMarks(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const char* name : {"trajectory.txt", "timing.csv", "summary.json"}) {
    fs::copy_file(from / name, to / name);
  }
  return to;
}

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
