#include "lumaslam/detect/detector_params.h"

#include <sstream>

#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_section.h"

namespace lumaslam::detect {
namespace {

using core::Range;

// The numeric Detector.* keys, each with its range (core::SectionReader / SectionPrinter).
template <typename Keys>
void visitDetectorNumberKeys(Keys& keys, DetectorParams& p) {
  keys("inputSize", p.input_size, Range::atLeast(0));  // and 0 or a multiple of 32
  keys("confidence", p.confidence_threshold, Range::between(0.0, 1.0));
  keys("nms", p.nms_threshold, Range::between(0.0, 1.0));
  keys("threads", p.threads, Range::atLeast(0));
  keys("boxFileTolerance", p.box_file_tolerance, Range::atLeast(0.0));
  keys("stride", p.stride, Range::atLeast(1));
  keys("queueCapacity", p.queue_capacity, Range::atLeast(1));
  keys("propagationFeatures", p.propagation.max_features, Range::atLeast(1));
  keys("propagationInnerFraction", p.propagation.inner_fraction, Range::between(0.1, 1.0));
  keys("maskMargin", p.mask.margin_px, Range::atLeast(0));
  keys("depthTolerance", p.mask.depth_tolerance_m, Range::atLeast(0.0));
  keys("depthEdge", p.mask.depth_edge_px, Range::atLeast(0));
  keys("depthPercentile", p.mask.depth_percentile, Range::between(0.0, 1.0));
  keys("memoryFrames", p.memory_frames, Range::atLeast(0));
  keys("memoryStrikes", p.memory_strikes, Range::atLeast(1));
}

void readDetectorStrings(const core::SettingsFile& settings, DetectorParams& p) {
  const core::SectionReader keys(settings, "Detector");
  keys("type", p.type);
  if (p.type != "yolo" && p.type != "box_file" && p.type != "none") {
    settings.invalid("Detector.type",
                     fmt::format("expected 'yolo', 'box_file' or 'none', found '{}'", p.type));
  }
  if (auto model = settings.find<std::string>("Detector.model")) p.model = *model;
  if (auto names = settings.find<std::string>("Detector.names")) p.names = *names;
  if (auto box_file = settings.find<std::string>("Detector.boxFile")) p.box_file = *box_file;
  if (auto classes = settings.find<std::string>("Detector.classes")) {
    p.classes = splitClassList(*classes);
    if (p.classes.empty()) settings.invalid("Detector.classes", "names no class");
  }
  keys("image", p.image);
  if (p.image != "raw" && p.image != "enhanced") {
    settings.invalid("Detector.image",
                     fmt::format("expected 'raw' or 'enhanced', found '{}'", p.image));
  }
}

void requireSource(const core::SettingsFile& settings, const DetectorParams& p) {
  if (p.type == "yolo" && p.model.empty())
    settings.invalid("Detector.model", "is required for Detector.type yolo");
  if (p.type == "box_file" && p.box_file.empty()) {
    settings.invalid("Detector.boxFile", "is required for Detector.type box_file");
  }
}

}  // namespace

std::vector<std::string> splitClassList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    const auto last = item.find_last_not_of(" \t");
    items.push_back(item.substr(first, last - first + 1));
  }
  return items;
}

DetectorParams DetectorParams::fromSettings(const core::SettingsFile& settings,
                                            bool require_source) {
  DetectorParams p;
  readDetectorStrings(settings, p);
  core::readSection(settings, "Detector", p,
                    [](auto& keys, auto& params) { visitDetectorNumberKeys(keys, params); });
  if (p.input_size != 0 && p.input_size % 32 != 0) {
    settings.invalid(
        "Detector.inputSize",
        fmt::format("must be 0 (from the model) or a multiple of 32, found {}", p.input_size));
  }
  if (require_source) requireSource(settings, p);
  return p;
}

std::string DetectorParams::settingsLines() const {
  core::SectionPrinter keys("Detector");
  keys("type", type);
  keys("model", model.string());
  keys("names", names.string());
  keys("boxFile", box_file.string());
  std::string class_list;
  for (const auto& name : classes) class_list += (class_list.empty() ? "" : ", ") + name;
  keys("classes", class_list);
  keys("image", image);
  DetectorParams copy = *this;
  visitDetectorNumberKeys(keys, copy);
  return keys.text();
}

std::filesystem::path DetectorParams::namesPath() const {
  if (!names.empty()) return names;
  return model.parent_path() / "coco80.names";
}

}  // namespace lumaslam::detect
