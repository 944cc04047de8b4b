#include <cstdio>
#include <memory>

#include "command_registry.h"
#include "lumaslam/synth/sequence.h"
#include "run_pipeline.h"

namespace lumaslam::cli {
namespace {

struct DemoOptions {
  std::filesystem::path out = "lumaslam_demo";
  std::string preset = "xyz-rgbd";
  int frames = 300;
  std::uint64_t seed = 1;
};

const bool registered = registerCommand(
    "demo", "Generate a synthetic RGB-D sequence with ground truth, run SLAM on it, evaluate",
    [](CLI::App& cmd) -> Runner {
      auto options = std::make_shared<DemoOptions>();
      cmd.add_option("--out", options->out, "Output folder")->capture_default_str();
      cmd.add_option("--preset", options->preset, "Synthetic preset (lumaslam synth --list)")
          ->capture_default_str();
      cmd.add_option("--frames", options->frames, "Frames to generate")->capture_default_str();
      cmd.add_option("--seed", options->seed, "Generator seed")->capture_default_str();
      return [options] {
        const auto data = options->out / "data";
        std::printf("generating %d frames of '%s' in %s ...\n", options->frames,
                    options->preset.c_str(), data.string().c_str());
        synth::writeSequence(data, options->preset, options->frames, options->seed);
        RunOptions run;
        run.dataset = "tum:" + data.string();
        run.out = options->out / "run";
        return runPipeline(run);
      };
    });

}  // namespace
}  // namespace lumaslam::cli
