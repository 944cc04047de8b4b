#pragma once
// The synthetic and perturbed datasets of an experiment plan, made once into DIR/data/ with the
// code `lumaslam synth` and `lumaslam perturb` use, and reused when a complete one is there.
#include <filesystem>

#include "experiment_plan.h"

namespace lumaslam::cli {

// Throws Error naming the plan file and key for a `perturb:` model that does not exist.
void checkPerturbModels(const Plan& plan);

// Points each synth or perturbed dataset's spec at its folder under data_dir, making nothing.
void pointAtSynthData(Plan& plan, const std::filesystem::path& data_dir);

// Generates the synth datasets and the perturbed copies that are missing (synth first: a copy
// may be of one), then points the specs at them.
void prepareSynthData(Plan& plan, const std::filesystem::path& data_dir);

}  // namespace lumaslam::cli
