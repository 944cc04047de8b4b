// `lumaslam synth OUT --preset NAME [--frames N] [--seed S] ...`: write a synthetic sequence
// with ground truth in TUM RGB-D or EuRoC layout (docs/synthetic.md).
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "command_registry.h"
#include "lumaslam/core/error.h"
#include "lumaslam/detect/box_labels.h"
#include "lumaslam/synth/dataset_writer.h"
#include "lumaslam/synth/person_image.h"
#include "lumaslam/synth/preset.h"
#include "lumaslam/synth/sequence.h"
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
  std::filesystem::path people;
};

// An image named in a box list, relative to the list's folder or one of its ancestors
// (shared/data/labels/person_boxes.txt names its images relative to shared/data).
std::filesystem::path resolveListedImage(const std::filesystem::path& list,
                                         const std::string& image) {
  for (auto dir = std::filesystem::absolute(list).parent_path(); !dir.empty();
       dir = dir.parent_path()) {
    if (std::filesystem::exists(dir / image)) return dir / image;
    if (dir == dir.parent_path()) break;
  }
  lumaslam::fail("{}: image '{}' not found next to the list or in a folder above it", list.string(),
                 image);
}

// --people-images: a box list (*.txt, "image class x1 y1 x2 y2") whose "person" boxes are
// cropped, or an image file / folder of images used whole.
std::vector<lumaslam::synth::PersonImage> loadPeople(const std::filesystem::path& path) {
  if (path.extension() != ".txt") return lumaslam::synth::loadPersonImages(path);
  std::vector<lumaslam::synth::PersonImage> people;
  for (const auto& [image, labels] : lumaslam::detect::readBoxList(path)) {
    std::vector<cv::Rect> boxes;
    for (const auto& label : labels)
      if (label.class_name == "person") boxes.push_back(label.box);
    if (boxes.empty()) continue;
    const auto file = resolveListedImage(path, image);
    const cv::Mat bgr = cv::imread(file.string(), cv::IMREAD_COLOR);
    if (bgr.empty()) lumaslam::fail("{}: cannot read this image", file.string());
    const auto crops = lumaslam::synth::cropPersonImages(bgr, boxes);
    people.insert(people.end(), crops.begin(), crops.end());
  }
  if (people.empty()) lumaslam::fail("{}: no person box in this list", path.string());
  return people;
}

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
  if (!o.people.empty()) options.people = loadPeople(o.people);
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
                     "Texture the walkers from person photos: an image, a folder of person "
                     "crops, or a box list (*.txt: image class x1 y1 x2 y2) whose person "
                     "boxes are cropped");
      return [o] { return runSynth(*o); };
    });

}  // namespace
