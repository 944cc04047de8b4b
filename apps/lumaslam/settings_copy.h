#pragma once
// A settings file's text with some keys set to other values: e.g. Detector.classes "person" for
// YOLO on synthetic data, whose settings name the generator's classes (person,box; YOLO knows no
// box), or System.sensor "mono" to run the rgb stream of an RGB-D dataset. Used by `experiment`
// (detector_classes:, sensor:) and `demo` (its YOLO row).
#include <filesystem>
#include <map>
#include <string>

namespace lumaslam::cli {

// The text of `source` with each key of `values` set to its value (quoted; added at the end
// when the file lacks the key). Relative paths (System.datasetRoot, Loop.vocabulary,
// Detector.model, Detector.boxFile, Detector.names) are made absolute from `source`'s folder,
// so the copy works from anywhere. Throws Error naming `source` when it cannot be read.
std::string settingsWithValues(const std::filesystem::path& source,
                               const std::map<std::string, std::string>& values);

}  // namespace lumaslam::cli
