#pragma once
// Reading a run folder's moving_features.txt, timing.csv and report.html for the report marks
// tests (test_cli_report_marks*.cpp): the run's counts, the sample frames' data-key texts and
// their decoded pictures, and whether the marked positions are drawn red.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "base64_text.h"

namespace lumaslam::test {

// timing.csv as rows of column name -> field, keyed by frame.
inline std::map<long, std::map<std::string, std::string>> timingRows(
    const std::filesystem::path& file) {
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
inline std::map<long, std::vector<double>> markLines(const std::filesystem::path& file) {
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
inline std::string keyText(const std::string& html, const std::string& key) {
  const auto at = html.find("data-key=\"" + key + "\"");
  if (at == std::string::npos) return {};
  const auto begin = html.find('>', at) + 1;
  return html.substr(begin, html.find('<', begin) - begin);
}

// The frame index of every data-key="frame.N.dropped" in the page.
inline std::vector<long> markedFrames(const std::string& html) {
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
inline cv::Mat enhancedImage(const std::string& html, long frame) {
  const auto at = html.find("alt=\"enhanced frame " + std::to_string(frame) + "\"");
  if (at == std::string::npos) return {};
  const std::string prefix = "src=\"data:image/jpeg;base64,";
  const auto begin = html.find(prefix, at) + prefix.size();
  const auto bytes = decodeBase64(html.substr(begin, html.find('"', begin) - begin));
  if (bytes.empty()) return {};
  return cv::imdecode(bytes, cv::IMREAD_COLOR);
}

// Strongly red (the marks are drawn in pure red, BGR 0 0 255).
inline bool isRed(const cv::Vec3b& p) {
  return p[2] > 180 && p[1] < 80 && p[0] < 80;
}

// The dropped and moving positions of a moving_features.txt line (after the counts and boxes),
// each with a red pixel within 4 pixels of it once scaled by `scale` to the drawn image.
inline int positionsMarkedRed(const cv::Mat& bgr, const std::vector<double>& line, double scale) {
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
inline std::filesystem::path copyWithoutMarks(const std::filesystem::path& from,
                                              const std::filesystem::path& to) {
  std::filesystem::create_directories(to);
  for (const char* name : {"trajectory.txt", "timing.csv", "summary.json"}) {
    std::filesystem::copy_file(from / name, to / name);
  }
  return to;
}

}  // namespace lumaslam::test
