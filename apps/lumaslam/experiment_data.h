#pragma once
// The synthetic datasets of an experiment plan, generated once into DIR/data/ with the code
// `lumaslam synth` uses and reused when a complete one is already there.
#include <filesystem>

#include "experiment_plan.h"

namespace lumaslam::cli {

// Points each synth dataset's spec at its folder under data_dir, generating nothing.
void pointAtSynthData(Plan& plan, const std::filesystem::path& data_dir);

// Generates what is missing and points each synth dataset's spec at its folder.
void prepareSynthData(Plan& plan, const std::filesystem::path& data_dir);

}  // namespace lumaslam::cli
