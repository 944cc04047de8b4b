#pragma once
// Which detector a SLAM run uses: the settings' Detector.* keys, optionally overridden by a
// one-word spec from the command line ("yolo:MODEL.onnx", "boxes:FILE" or "none").
#include <optional>
#include <string>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/detect/detector_params.h"

namespace lumaslam::detect {

// The detector's parameters, or nullopt for no detection. Without a spec, detection is on when
// the settings name a detector (Detector.type yolo|box_file, or Detector.model /
// Detector.boxFile present) and off when they name none (no such key, or Detector.type none).
// A spec replaces the type and its model / box file; the tuning keys (thresholds, stride,
// mask) still come from the settings. `settings` may be null. Throws Error for a malformed
// spec ("--detector 'x': expected ...") or a named detector without its file.
std::optional<DetectorParams> detectorParamsFor(const core::SettingsFile* settings,
                                                const std::optional<std::string>& spec);

// "yolo model.onnx", "box_file detections.txt" or "none", for logs and summaries.
std::string describeChoice(const std::optional<DetectorParams>& params);

}  // namespace lumaslam::detect
