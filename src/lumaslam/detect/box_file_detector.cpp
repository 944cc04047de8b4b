#include "lumaslam/detect/box_file_detector.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "lumaslam/core/error.h"
#include "lumaslam/detect/class_names.h"

namespace lumaslam::detect {
namespace {

bool isInteger(const std::string& token) {
  return !token.empty() &&
         std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

BoxFileDetector::BoxFileDetector(const DetectorParams& params)
    : file_(params.box_file), tolerance_(params.box_file_tolerance) {
  std::ifstream in(file_);
  if (!in) fail("{}: cannot open box file", file_.string());
  std::vector<std::string> names;
  if (!params.names.empty()) names = readClassNames(params.names);

  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::string class_token;
    double timestamp = 0.0;
    float x = 0, y = 0, w = 0, h = 0;
    if (!(fields >> timestamp)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank or comment
      fail("{}:{}: expected 'timestamp class x y w h', found '{}'", file_.string(), line_number,
           line);
    }
    std::string extra;
    if (!(fields >> class_token >> x >> y >> w >> h) || (fields >> extra)) {
      fail("{}:{}: expected 'timestamp class x y w h', found '{}'", file_.string(), line_number,
           line);
    }
    if (!std::isfinite(timestamp) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(w) ||
        !std::isfinite(h) || w < 0 || h < 0) {
      fail("{}:{}: box needs finite values and w, h >= 0, found '{}'", file_.string(), line_number,
           line);
    }
    Detection detection;
    detection.score = 1.0f;
    detection.box = {x, y, w, h};
    if (isInteger(class_token)) {
      // from_chars, not stoi: an id beyond int range is the same error as any unlisted id.
      const char* end = class_token.data() + class_token.size();
      const auto [parsed_end, error] = std::from_chars(class_token.data(), end, detection.class_id);
      if (error != std::errc() || parsed_end != end ||
          detection.class_id >= static_cast<int>(names.size())) {
        fail("{}:{}: class id {} needs a names file (Detector.names) listing it", file_.string(),
             line_number, class_token);
      }
      detection.class_name = names[detection.class_id];
    } else {
      detection.class_name = class_token;
      const auto it = std::find(names.begin(), names.end(), class_token);
      if (it != names.end()) detection.class_id = static_cast<int>(it - names.begin());
    }
    auto& frame =
        frames_[timestamp];  // a listed timestamp is a frame even if its class is filtered out
    if (std::find(params.classes.begin(), params.classes.end(), detection.class_name) !=
        params.classes.end()) {
      frame.push_back(std::move(detection));
    }
  }
}

Detections BoxFileDetector::detect(const cv::Mat& /*image*/, double timestamp) {
  if (frames_.empty()) return {};
  auto after = frames_.lower_bound(timestamp);
  auto nearest = after;
  if (after == frames_.end() || (after != frames_.begin() &&
                                 timestamp - std::prev(after)->first < after->first - timestamp)) {
    nearest = std::prev(after);
  }
  if (std::abs(nearest->first - timestamp) > tolerance_) return {};
  return nearest->second;
}

std::string BoxFileDetector::describe() const {
  return fmt::format("box file {} ({} frames)", file_.string(), frames_.size());
}

}  // namespace lumaslam::detect
