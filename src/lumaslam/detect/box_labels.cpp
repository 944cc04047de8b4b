#include "lumaslam/detect/box_labels.h"

#include <fstream>
#include <regex>
#include <sstream>

#include "lumaslam/core/error.h"
#include "lumaslam/core/read_file.h"

namespace lumaslam::detect {
namespace {

// Text of the first <tag>...</tag> in `xml`, or empty.
std::string element(const std::string& xml, const std::string& tag) {
  const std::regex pattern("<" + tag + ">\\s*([^<]*?)\\s*</" + tag + ">");
  std::smatch match;
  return std::regex_search(xml, match, pattern) ? match[1].str() : std::string();
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
  const std::regex object_pattern("<object>([\\s\\S]*?)</object>");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), object_pattern);
       it != std::sregex_iterator(); ++it) {
    const std::string object = (*it)[1].str();
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
