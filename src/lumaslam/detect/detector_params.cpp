#include "lumaslam/detect/detector_params.h"

#include <sstream>

#include "lumaslam/core/error.h"

namespace lumaslam::detect {
namespace {

template <typename T>
void read(const core::SettingsFile& settings, const char* key, T& value) {
  value = settings.get<T>(key, value);
}

template <typename T>
void requireAtLeast(const core::SettingsFile& settings, const char* key, T value, T minimum) {
  if (value < minimum)
    settings.invalid(key, fmt::format("must be >= {}, found {}", minimum, value));
}

template <typename T>
void requireInRange(const core::SettingsFile& settings, const char* key, T value, T low, T high) {
  if (value < low || value > high) {
    settings.invalid(key, fmt::format("must be in [{}, {}], found {}", low, high, value));
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
  read(settings, "Detector.type", p.type);
  if (p.type != "yolo" && p.type != "box_file" && p.type != "none") {
    settings.invalid("Detector.type",
                     fmt::format("expected 'yolo', 'box_file' or 'none', found '{}'", p.type));
  }
  if (auto model = settings.find<std::string>("Detector.model")) p.model = *model;
  if (auto names = settings.find<std::string>("Detector.names")) p.names = *names;
  if (auto box_file = settings.find<std::string>("Detector.box_file")) p.box_file = *box_file;
  if (auto classes = settings.find<std::string>("Detector.classes")) {
    p.classes = splitClassList(*classes);
    if (p.classes.empty()) settings.invalid("Detector.classes", "names no class");
  }
  read(settings, "Detector.input_size", p.input_size);
  read(settings, "Detector.confidence", p.confidence_threshold);
  read(settings, "Detector.nms", p.nms_threshold);
  read(settings, "Detector.threads", p.threads);
  read(settings, "Detector.box_file_tolerance", p.box_file_tolerance);
  read(settings, "Detector.stride", p.stride);
  read(settings, "Detector.queue_capacity", p.queue_capacity);
  read(settings, "Detector.propagation_features", p.propagation.max_features);
  read(settings, "Detector.propagation_inner_fraction", p.propagation.inner_fraction);
  read(settings, "Detector.mask_margin", p.mask.margin_px);
  read(settings, "Detector.depth_tolerance", p.mask.depth_tolerance_m);
  read(settings, "Detector.depth_edge", p.mask.depth_edge_px);
  read(settings, "Detector.depth_percentile", p.mask.depth_percentile);
  read(settings, "Detector.image", p.image);
  read(settings, "Detector.memory_frames", p.memory_frames);
  read(settings, "Detector.memory_strikes", p.memory_strikes);
  requireAtLeast(settings, "Detector.memory_frames", p.memory_frames, 0);
  requireAtLeast(settings, "Detector.memory_strikes", p.memory_strikes, 1);
  if (p.image != "raw" && p.image != "enhanced") {
    settings.invalid("Detector.image",
                     fmt::format("expected 'raw' or 'enhanced', found '{}'", p.image));
  }

  if (p.input_size != 0 && (p.input_size < 32 || p.input_size % 32 != 0)) {
    settings.invalid(
        "Detector.input_size",
        fmt::format("must be 0 (from the model) or a multiple of 32, found {}", p.input_size));
  }
  requireInRange(settings, "Detector.confidence", p.confidence_threshold, 0.0f, 1.0f);
  requireInRange(settings, "Detector.nms", p.nms_threshold, 0.0f, 1.0f);
  requireAtLeast(settings, "Detector.threads", p.threads, 0);
  requireAtLeast(settings, "Detector.box_file_tolerance", p.box_file_tolerance, 0.0);
  requireAtLeast(settings, "Detector.stride", p.stride, 1);
  requireAtLeast(settings, "Detector.queue_capacity", p.queue_capacity, 1);
  requireAtLeast(settings, "Detector.propagation_features", p.propagation.max_features, 1);
  requireInRange(settings, "Detector.propagation_inner_fraction", p.propagation.inner_fraction,
                 0.1f, 1.0f);
  requireAtLeast(settings, "Detector.mask_margin", p.mask.margin_px, 0);
  requireAtLeast(settings, "Detector.depth_tolerance", p.mask.depth_tolerance_m, 0.0);
  requireAtLeast(settings, "Detector.depth_edge", p.mask.depth_edge_px, 0);
  requireInRange(settings, "Detector.depth_percentile", p.mask.depth_percentile, 0.0, 1.0);
  if (!require_source) return p;
  if (p.type == "yolo" && p.model.empty())
    settings.invalid("Detector.model", "is required for Detector.type yolo");
  if (p.type == "box_file" && p.box_file.empty()) {
    settings.invalid("Detector.box_file", "is required for Detector.type box_file");
  }
  return p;
}

std::filesystem::path DetectorParams::namesPath() const {
  if (!names.empty()) return names;
  return model.parent_path() / "coco80.names";
}

}  // namespace lumaslam::detect
