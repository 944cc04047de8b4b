#include "moving_features_file.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "lumaslam/core/error.h"

namespace lumaslam::cli {
namespace {

constexpr const char* kHeader =
    "# lumaslam moving_features.txt (docs/results.md): one line per frame, FRAME FEATURES BOXES "
    "DROPPED MOVING, then x y w h of each box, x y of each dropped and of each moving feature\n";

// Whole pixels: enough to draw, and a third of the bytes of two decimals.
long rounded(float value) {
  return std::lround(value);
}

std::string lineOf(const FrameMarks& marks) {
  std::string line = fmt::format("{} {} {} {} {}", marks.frame, marks.features, marks.boxes.size(),
                                 marks.dropped.size(), marks.moving.size());
  for (const cv::Rect2f& box : marks.boxes) {
    line += fmt::format(" {} {} {} {}", rounded(box.x), rounded(box.y), rounded(box.width),
                        rounded(box.height));
  }
  for (const auto* points : {&marks.dropped, &marks.moving}) {
    for (const cv::Point2f& point : *points) {
      line += fmt::format(" {} {}", rounded(point.x), rounded(point.y));
    }
  }
  return line + '\n';
}

// The numbers of a line; throws Error naming the field that is not one.
std::vector<double> numbersOf(const std::string& line, const std::string& where) {
  std::vector<double> numbers;
  std::istringstream fields(line);
  for (std::string field; fields >> field;) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (ec != std::errc() || end != field.data() + field.size() || !std::isfinite(value)) {
      fail("{}: '{}' is not a number", where, field);
    }
    numbers.push_back(value);
  }
  return numbers;
}

std::size_t countAt(const std::vector<double>& numbers, std::size_t i, const std::string& where) {
  const double value = numbers[i];
  if (value < 0 || value != std::floor(value) || value > 1e9) {
    fail("{}: field {} must be a count, not {}", where, i + 1, value);
  }
  return static_cast<std::size_t>(value);
}

std::vector<cv::Point2f> pointsAt(const std::vector<double>& numbers, std::size_t& at,
                                  std::size_t count) {
  std::vector<cv::Point2f> points;
  for (std::size_t k = 0; k < count; ++k, at += 2) {
    points.emplace_back(static_cast<float>(numbers[at]), static_cast<float>(numbers[at + 1]));
  }
  return points;
}

FrameMarks frameOf(const std::vector<double>& numbers, const std::string& where) {
  if (numbers.size() < 5) fail("{}: {} fields, at least 5 expected", where, numbers.size());
  FrameMarks marks;
  marks.frame = countAt(numbers, 0, where);
  marks.features = countAt(numbers, 1, where);
  const std::size_t boxes = countAt(numbers, 2, where);
  const std::size_t dropped = countAt(numbers, 3, where);
  const std::size_t moving = countAt(numbers, 4, where);
  const std::size_t expected = 5 + 4 * boxes + 2 * (dropped + moving);
  if (numbers.size() != expected) {
    fail("{}: {} fields, {} expected for {} boxes, {} dropped and {} moving features", where,
         numbers.size(), expected, boxes, dropped, moving);
  }
  if (dropped + moving > marks.features) {
    fail("{}: {} dropped and {} moving of {} features", where, dropped, moving, marks.features);
  }
  std::size_t at = 5;
  for (std::size_t k = 0; k < boxes; ++k, at += 4) {
    marks.boxes.emplace_back(static_cast<float>(numbers[at]), static_cast<float>(numbers[at + 1]),
                             static_cast<float>(numbers[at + 2]),
                             static_cast<float>(numbers[at + 3]));
  }
  marks.dropped = pointsAt(numbers, at, dropped);
  marks.moving = pointsAt(numbers, at, moving);
  return marks;
}

cv::Size imageSizeOf(const std::string& line, const std::string& where) {
  if (!line.starts_with("image ")) fail("{}: expected 'image WIDTH HEIGHT'", where);
  const auto numbers = numbersOf(line.substr(6), where);
  if (numbers.size() != 2) fail("{}: expected 'image WIDTH HEIGHT'", where);
  const cv::Size size(static_cast<int>(countAt(numbers, 0, where)),
                      static_cast<int>(countAt(numbers, 1, where)));
  if (size.empty()) fail("{}: an image of {}x{} pixels", where, size.width, size.height);
  return size;
}

}  // namespace

MovingFeaturesWriter::MovingFeaturesWriter(const std::filesystem::path& file, cv::Size image)
    : file_(file) {
  file_.stream() << kHeader << "image " << image.width << ' ' << image.height << '\n';
}

void MovingFeaturesWriter::add(const FrameMarks& marks) {
  file_.stream() << lineOf(marks);
  file_.flush();
}

void MovingFeaturesWriter::commit() {
  file_.commit();
}

std::optional<MovingFeatures> readMovingFeatures(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  std::ifstream in(file);
  if (!in) fail("{}: cannot open", file.string());
  std::optional<MovingFeatures> result;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line.starts_with('#')) continue;
    const std::string where = fmt::format("{}: line {}", file.string(), number);
    if (!result) {
      result = MovingFeatures{imageSizeOf(line, where), {}};
      continue;
    }
    FrameMarks marks = frameOf(numbersOf(line, where), where);
    const std::size_t frame = marks.frame;
    if (!result->frames.emplace(frame, std::move(marks)).second) {
      fail("{}: frame {} a second time", where, frame);
    }
  }
  if (in.bad()) fail("{}: cannot read", file.string());
  if (!result) fail("{}: no 'image WIDTH HEIGHT' line", file.string());
  return result;
}

}  // namespace lumaslam::cli
