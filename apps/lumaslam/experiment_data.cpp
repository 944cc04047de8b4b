#include "experiment_data.h"

#include <spdlog/spdlog.h>

#include "lumaslam/core/error.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/synth/perturb.h"
#include "lumaslam/synth/sequence.h"

namespace lumaslam::cli {
namespace {

namespace fs = std::filesystem;

// The dataset a perturbed copy is made from: the generated folder of a synth dataset, else the
// plan's own dataset.
fs::path perturbSource(const PlanDataset& dataset, const fs::path& data_dir) {
  if (dataset.synth) return data_dir / dataset.synth->folder;
  return io::datasetPathOf(dataset.perturb->source_spec);
}

void prepareSynthFolder(const PlanDataset::Synth& synth, const fs::path& data_dir) {
  const auto folder = data_dir / synth.folder;
  // synth writes settings.yaml last: a folder with it is complete, one without is redone.
  if (fs::is_regular_file(folder / "settings.yaml")) {
    spdlog::info("experiment: reusing {}", folder.string());
    return;
  }
  synth::writeSequence(folder, synth.preset, synth.frames, synth.seed);
}

// perturbDataset writes its output folder whole (a temporary folder renamed into place).
void preparePerturbedFolder(const PlanDataset& dataset, const fs::path& data_dir) {
  const auto& perturb = *dataset.perturb;
  const auto folder = data_dir / perturb.folder;
  if (fs::is_directory(folder)) {
    spdlog::info("experiment: reusing {}", folder.string());
    return;
  }
  synth::perturbDataset(perturbSource(dataset, data_dir), folder,
                        synth::perturbModelFromName(perturb.model), perturb.level, 1);
}

std::string kindOf(const std::string& spec) {
  return spec.substr(0, spec.find(':') + 1);
}

}  // namespace

void checkPerturbModels(const Plan& plan) {
  for (const auto& dataset : plan.datasets) {
    if (!dataset.perturb) continue;
    try {
      synth::perturbModelFromName(dataset.perturb->model);
    } catch (const Error& e) {
      fail("{}: {}: {}", plan.file.string(), dataset.perturb->key, e.what());
    }
  }
}

void pointAtSynthData(Plan& plan, const fs::path& data_dir) {
  for (auto& dataset : plan.datasets) {
    if (dataset.synth) {
      const auto folder = data_dir / dataset.synth->folder;
      dataset.spec = (dataset.synth->stereo ? "euroc:" : "tum:") + folder.string();
    }
    if (dataset.perturb) {
      dataset.spec = kindOf(dataset.spec) + (data_dir / dataset.perturb->folder).string();
    }
  }
}

void prepareSynthData(Plan& plan, const fs::path& data_dir) {
  for (const auto& dataset : plan.datasets) {
    if (dataset.synth) prepareSynthFolder(*dataset.synth, data_dir);
  }
  for (const auto& dataset : plan.datasets) {
    if (dataset.perturb) preparePerturbedFolder(dataset, data_dir);
  }
  pointAtSynthData(plan, data_dir);
}

}  // namespace lumaslam::cli
