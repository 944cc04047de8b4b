// `lumaslam perturb IN OUT --model dark|flash|flicker|spotlight|noise --level L`: copy a TUM
// RGB-D or EuRoC dataset with its camera images under synth's lighting models.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "command_registry.h"
#include "lumaslam/synth/perturb.h"
#include "progress_line.h"

namespace {

struct PerturbCommandOptions {
  std::filesystem::path in;
  std::filesystem::path out;
  std::string model;
  int level = 0;
  std::uint64_t seed = 1;
};

const bool registered = lumaslam::cli::registerCommand(
    "perturb",
    "Copy a TUM/EuRoC dataset with darkened, flashing, flickering, spotlit or noisy images",
    [](CLI::App& cmd) -> lumaslam::cli::Runner {
      auto o = std::make_shared<PerturbCommandOptions>();
      cmd.add_option("IN", o->in, "Input dataset folder (TUM RGB-D or EuRoC)")->required();
      cmd.add_option("OUT", o->out, "Output dataset folder")->required();
      cmd.add_option("--model", o->model, "Lighting model")
          ->required()
          ->check(CLI::IsMember({"dark", "flash", "flicker", "spotlight", "noise"}));
      cmd.add_option("--level", o->level, "Strength 0..5 (0 = unchanged copy)")
          ->check(CLI::Range(0, 5));
      cmd.add_option("--seed", o->seed, "Noise seed");
      return [o] {
        using namespace lumaslam::synth;
        std::optional<lumaslam::cli::ProgressLine> progress;
        perturbDataset(o->in, o->out, perturbModelFromName(o->model), o->level, o->seed,
                       [&progress](std::size_t done, std::size_t total) {
                         if (!progress) progress.emplace("image", total);
                         progress->update(done, "perturbing");
                       });
        return 0;
      };
    });

}  // namespace
