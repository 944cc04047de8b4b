#pragma once
// Configurations with `detector_classes:` (docs/experiments.md) run with a copy of the
// dataset's settings whose Detector.classes is replaced, written to
// DIR/settings/<dataset>/<config>.yaml and passed as `run --settings`: e.g. "person" for YOLO
// on synthetic data, whose settings name the generator's classes (person,box; YOLO knows no box).
#include <filesystem>
#include <string>

#include "experiment_plan.h"

namespace lumaslam::cli {

// DIR/settings/<dataset>/<config>.yaml
std::filesystem::path classSettingsFile(const std::filesystem::path& dir,
                                        const std::string& dataset, const std::string& config);

// Writes the copy for every dataset x configuration with detector_classes (after the synth data
// is prepared: its settings are the generator's). Relative paths in the copied file
// (System.datasetRoot, Loop.vocabulary, Detector.model, Detector.box_file, Detector.names) are
// made absolute from the original's folder.
void writeClassSettings(const Plan& plan, const std::filesystem::path& dir);

}  // namespace lumaslam::cli
