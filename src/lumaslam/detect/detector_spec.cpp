#include "lumaslam/detect/detector_spec.h"

#include <spdlog/fmt/fmt.h>

#include "lumaslam/core/error.h"

namespace lumaslam::detect {
namespace {

bool settingsNameADetector(const core::SettingsFile& settings) {
  return settings.has("Detector.type") || settings.has("Detector.model") ||
         settings.has("Detector.boxFile");
}

// Applies "yolo:MODEL", "boxes:FILE"; returns false for "none".
bool applySpec(const std::string& spec, DetectorParams& params) {
  if (spec == "none") return false;
  const auto colon = spec.find(':');
  const std::string kind = colon == std::string::npos ? spec : spec.substr(0, colon);
  const std::string path = colon == std::string::npos ? std::string() : spec.substr(colon + 1);
  if ((kind != "yolo" && kind != "boxes") || path.empty()) {
    fail("--detector '{}': expected yolo:MODEL.onnx, boxes:FILE or none", spec);
  }
  if (kind == "yolo") {
    params.type = "yolo";
    params.model = path;
  } else {
    params.type = "box_file";
    params.box_file = path;
  }
  return true;
}

}  // namespace

std::optional<DetectorParams> detectorParamsFor(const core::SettingsFile* settings,
                                                const std::optional<std::string>& spec) {
  if (!spec) {
    if (!settings || !settingsNameADetector(*settings)) return std::nullopt;
    auto params = DetectorParams::fromSettings(*settings);
    if (params.type == "none") return std::nullopt;
    return params;
  }
  auto params = settings ? DetectorParams::fromSettings(*settings, /*require_source=*/false)
                         : DetectorParams{};
  if (!applySpec(*spec, params)) return std::nullopt;
  return params;
}

std::string describeChoice(const std::optional<DetectorParams>& params) {
  if (!params) return "none";
  if (params->type == "box_file") return fmt::format("box_file {}", params->box_file.string());
  return fmt::format("{} {}", params->type, params->model.string());
}

}  // namespace lumaslam::detect
