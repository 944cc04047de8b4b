#pragma once
// Ground-truth boxes for detection evaluation, in the two formats shared/data uses:
// - a box list (shared/data/labels/person_boxes.txt): "image class x1 y1 x2 y2" per line,
//   image relative to a root folder, '#' comments;
// - Pascal VOC XML annotations (LLVIP Annotations/*.xml): one file per image.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::detect {

struct LabeledBox {
  std::string class_name;
  cv::Rect2f box;
};

// Image path (as written) -> its boxes, in file order. Throws Error "FILE:LINE: ..." for a
// malformed line, Error naming the file when it cannot be read.
std::map<std::string, std::vector<LabeledBox>> readBoxList(const std::filesystem::path& file);

struct VocAnnotation {
  std::string filename;  // <filename>
  std::vector<LabeledBox> boxes;
};

// Reads <filename> and every <object><name>/<bndbox> of a VOC file. Throws Error naming the
// file when it cannot be read or an object lacks a name or a complete box.
VocAnnotation readVocAnnotation(const std::filesystem::path& file);

}  // namespace lumaslam::detect
