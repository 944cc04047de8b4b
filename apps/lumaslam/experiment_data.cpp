#include "experiment_data.h"

#include <spdlog/spdlog.h>

#include "lumaslam/synth/sequence.h"

namespace lumaslam::cli {

void pointAtSynthData(Plan& plan, const std::filesystem::path& data_dir) {
  for (auto& dataset : plan.datasets) {
    if (!dataset.synth) continue;
    const auto folder = data_dir / dataset.synth->folder;
    dataset.spec = (dataset.synth->stereo ? "euroc:" : "tum:") + folder.string();
  }
}

void prepareSynthData(Plan& plan, const std::filesystem::path& data_dir) {
  pointAtSynthData(plan, data_dir);
  for (auto& dataset : plan.datasets) {
    if (!dataset.synth) continue;
    const auto& synth = *dataset.synth;
    const auto folder = data_dir / synth.folder;
    // synth writes settings.yaml last: a folder with it is complete, one without is redone.
    if (std::filesystem::is_regular_file(folder / "settings.yaml")) {
      spdlog::info("experiment: reusing {}", folder.string());
      continue;
    }
    synth::writeSequence(folder, synth.preset, synth.frames, synth.seed);
  }
}

}  // namespace lumaslam::cli
