#include "lumaslam/detect/box_labels.h"

#include <fstream>
#include <sstream>
#include <string_view>

#include "lumaslam/core/error.h"
#include "lumaslam/core/read_file.h"

namespace lumaslam::detect {
namespace {

constexpr std::string_view kSpace = " \t\n\v\f\r";

// Text of the first <tag>...</tag> in `xml` whose text holds no '<', without surrounding
// whitespace; empty if there is none. A plain search: std::regex recurses once per character
// and overflowed the stack on a 40 KB element (fuzzing, fuzz/regressions/box_labels).
std::string element(const std::string& xml, const std::string& tag) {
  const std::string open = "<" + tag + ">";
  const std::string close = "</" + tag + ">";
  for (auto start = xml.find(open); start != std::string::npos; start = xml.find(open, start + 1)) {
    const auto text_begin = start + open.size();
    const auto text_end = xml.find('<', text_begin);
    if (text_end == std::string::npos) break;
    if (xml.compare(text_end, close.size(), close) != 0) continue;
    const std::string_view text(xml.data() + text_begin, text_end - text_begin);
    const auto first = text.find_first_not_of(kSpace);
    if (first == std::string_view::npos) return {};
    return std::string(text.substr(first, text.find_last_not_of(kSpace) - first + 1));
  }
  return {};
}

// The texts between each <object> and the next </object>, in file order.
std::vector<std::string> objects(const std::string& xml) {
  const std::string open = "<object>";
  const std::string close = "</object>";
  std::vector<std::string> found;
  for (auto start = xml.find(open); start != std::string::npos;) {
    const auto end = xml.find(close, start + open.size());
    if (end == std::string::npos) break;
    found.push_back(xml.substr(start + open.size(), end - start - open.size()));
    start = xml.find(open, end + close.size());
  }
  return found;
}

float coordinate(const std::string& object, const std::string& tag,
                 const std::filesystem::path& file) {
  const std::string text = element(object, tag);
  try {
    std::size_t used = 0;
    const float value = std::stof(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  fail("{}: object <{}> is '{}', not a number", file.string(), tag, text);
}

}  // namespace

std::map<std::string, std::vector<LabeledBox>> readBoxList(const std::filesystem::path& file) {
  std::istringstream in(core::readWholeFile(file, "label file"));
  std::map<std::string, std::vector<LabeledBox>> labels;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::string image;
    if (!(fields >> image)) continue;
    LabeledBox labeled;
    float x1 = 0, y1 = 0, x2 = 0, y2 = 0;
    std::string extra;
    if (!(fields >> labeled.class_name >> x1 >> y1 >> x2 >> y2) || (fields >> extra) || x2 < x1 ||
        y2 < y1) {
      fail("{}:{}: expected 'image class x1 y1 x2 y2' with x1 <= x2, y1 <= y2, found '{}'",
           file.string(), line_number, line);
    }
    labeled.box = cv::Rect2f(x1, y1, x2 - x1, y2 - y1);
    labels[image].push_back(labeled);
  }
  return labels;
}

VocAnnotation readVocAnnotation(const std::filesystem::path& file) {
  const std::string xml = core::readWholeFile(file, "label file");
  VocAnnotation annotation;
  annotation.filename = element(xml, "filename");
  if (annotation.filename.empty()) fail("{}: VOC annotation has no <filename>", file.string());
  for (const std::string& object : objects(xml)) {
    LabeledBox labeled;
    labeled.class_name = element(object, "name");
    if (labeled.class_name.empty()) fail("{}: an <object> has no <name>", file.string());
    const float x1 = coordinate(object, "xmin", file);
    const float y1 = coordinate(object, "ymin", file);
    const float x2 = coordinate(object, "xmax", file);
    const float y2 = coordinate(object, "ymax", file);
    if (x2 < x1 || y2 < y1) fail("{}: object box has xmax < xmin or ymax < ymin", file.string());
    labeled.box = cv::Rect2f(x1, y1, x2 - x1, y2 - y1);
    annotation.boxes.push_back(labeled);
  }
  return annotation;
}

}  // namespace lumaslam::detect
