// `lumaslam synth OUT --preset NAME [--frames N] [--seed S] ...`: write a synthetic sequence
// with ground truth in TUM RGB-D or EuRoC layout (docs/synthetic.md).
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "command_registry.h"
#include "lumaslam/core/error.h"
#include "lumaslam/synth/dataset_writer.h"
#include "lumaslam/synth/preset.h"
#include "lumaslam/synth/sequence.h"
#include "people_sources.h"
#include "progress_line.h"

namespace {

struct SynthCommandOptions {
  std::filesystem::path out;
  std::string preset;
  int frames = 0;
  std::uint64_t seed = 1;
  int walkers = -1;
  int moving_boxes = -1;
  int dark_level = -1;
  bool no_blur = false;
  bool no_noise = false;
  bool global_shutter = false;
  bool synced_depth = false;
  bool list = false;
  std::vector<std::filesystem::path> textures;
  std::vector<std::filesystem::path> people;
  std::vector<std::filesystem::path> people_image_folders;
};

int runSynth(const SynthCommandOptions& o) {
  using namespace lumaslam::synth;
  if (o.list) {
    for (const auto& p : allPresets())
      std::cout << p.name << " (" << p.frames << " frames): " << p.description << "\n";
    return 0;
  }
  if (o.out.empty() || o.preset.empty())
    lumaslam::fail("synth needs OUT and --preset (see --list)");
  SynthOptions options;
  if (o.walkers >= 0) options.walkers = o.walkers;
  if (o.moving_boxes >= 0) options.moving_boxes = o.moving_boxes;
  if (o.dark_level >= 0) options.dark_level = o.dark_level;
  options.motion_blur = !o.no_blur;
  options.sensor_noise = !o.no_noise;
  options.rolling_shutter = !o.global_shutter;
  options.depth_misalignment = !o.synced_depth;
  options.texture_images = o.textures;
  if (!o.people.empty())
    options.people = lumaslam::cli::loadPeople(o.people, o.people_image_folders);
  std::optional<lumaslam::cli::ProgressLine> progress;
  writeSequence(o.out, o.preset, o.frames, o.seed, options, [&](int done, int total) {
    if (!progress) progress.emplace("frame", static_cast<std::size_t>(total));
    progress->update(static_cast<std::size_t>(done), "rendered");
  });
  return 0;
}

const bool registered = lumaslam::cli::registerCommand(
    "synth", "Write a synthetic sequence with ground truth (TUM RGB-D or EuRoC layout)",
    [](CLI::App& cmd) -> lumaslam::cli::Runner {
      auto o = std::make_shared<SynthCommandOptions>();
      cmd.add_option("OUT", o->out, "Output dataset folder");
      cmd.add_option("--preset", o->preset, "Sequence preset (see --list)");
      cmd.add_flag("--list", o->list, "List the presets and exit");
      cmd.add_option("--frames", o->frames, "Number of frames (default: the preset's)")
          ->check(CLI::NonNegativeNumber);
      cmd.add_option("--seed", o->seed, "Random seed (same seed, same bytes)");
      cmd.add_option("--walkers", o->walkers, "Override the number of walking people")
          ->check(CLI::Range(0, 20));
      cmd.add_option("--moving-boxes", o->moving_boxes, "Override the number of moving boxes")
          ->check(CLI::Range(0, 20));
      cmd.add_option("--dark-level", o->dark_level,
                     "Override the dark level V_out = A*V_in^(1/gamma), 0..5")
          ->check(CLI::Range(0, 5));
      cmd.add_flag("--no-blur", o->no_blur, "Disable motion blur");
      cmd.add_flag("--no-noise", o->no_noise, "Disable sensor noise");
      cmd.add_flag("--global-shutter", o->global_shutter,
                   "Render the preset's rolling-shutter cameras with a global shutter");
      cmd.add_flag("--synced-depth", o->synced_depth,
                   "Depth registered exactly to colour and captured at the colour stamp "
                   "(no misregistration, no stream time offsets)");
      cmd.add_option("--texture", o->textures, "Image file(s) to use as posters in the scene");
      cmd.add_option("--people-images", o->people,
                     "Texture the walkers from person photos (repeatable, sources combined): an "
                     "image, a folder of person crops, a box list (*.txt: image class x1 y1 x2 "
                     "y2) or Pascal VOC annotations (*.xml or a folder of them, e.g. LLVIP's "
                     "Annotations) whose person boxes are cut out");
      cmd.add_option("--people-image-folder", o->people_image_folders,
                     "Where the images of VOC annotations are (repeatable; default: the "
                     "annotation folder's sibling JPEGImages)");
      return [o] { return runSynth(*o); };
    });

}  // namespace
