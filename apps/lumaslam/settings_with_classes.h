#pragma once
// A settings file's text with Detector.classes replaced: e.g. "person" for YOLO on synthetic
// data, whose settings name the generator's classes (person,box; YOLO knows no box). Used by
// `experiment` (detector_classes:) and `demo` (its YOLO row).
#include <filesystem>
#include <string>

namespace lumaslam::cli {

// The text of `source` with its Detector.classes line (added when missing) set to `classes`.
// Relative paths (System.datasetRoot, Loop.vocabulary, Detector.model, Detector.box_file,
// Detector.names) are made absolute from `source`'s folder, so the copy works from anywhere.
// Throws Error naming `source` when it cannot be read.
std::string settingsWithClasses(const std::filesystem::path& source, const std::string& classes);

}  // namespace lumaslam::cli
