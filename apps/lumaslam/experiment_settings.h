#pragma once
// Configurations with `detector_classes:` or `sensor:` (docs/experiments.md) run with a copy of
// their settings (the configuration's `settings:`, else the dataset's) with Detector.classes /
// System.sensor set, written to DIR/settings/<dataset>/<config>.yaml and passed as `run
// --settings`: e.g. "person" for YOLO on synthetic data, whose settings name the generator's
// classes (person,box; YOLO knows no box), or "mono" for the rgb stream of an RGB-D dataset.
#include <filesystem>
#include <string>

#include "experiment_plan.h"

namespace lumaslam::cli {

// DIR/settings/<dataset>/<config>.yaml
std::filesystem::path configSettingsFile(const std::filesystem::path& dir,
                                         const std::string& dataset, const std::string& config);

// Writes the copy for every dataset x configuration with detector_classes or sensor (after the
// synth data is prepared: its settings are the generator's). Relative paths in the copied file
// (System.datasetRoot, Loop.vocabulary, Detector.model, Detector.boxFile, Detector.names) are
// made absolute from the original's folder.
void writeConfigSettings(const Plan& plan, const std::filesystem::path& dir);

}  // namespace lumaslam::cli
