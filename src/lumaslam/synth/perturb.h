#pragma once
// `lumaslam perturb`: the synth lighting models applied to real TUM RGB-D or EuRoC images, to
// make "dark EuRoC"-style benchmarks from real data. Level 0 is the identity for every model;
// docs/synthetic.md lists each level's parameters.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include <opencv2/core.hpp>

namespace lumaslam::synth {

enum class PerturbModel { Dark, Flash, Flicker, Spotlight, Noise };

PerturbModel perturbModelFromName(std::string_view name);  // throws Error on unknown names
std::string perturbModelName(PerturbModel model);

// What a model does at a level (for documentation and the provenance file).
std::string describePerturbation(PerturbModel model, int level);

// One image (CV_8UC1 or CV_8UC3) of frame `index` at `time_s` seconds; `noise_key` seeds
// the noise. Throws Error for a level outside 0..5.
cv::Mat perturbImage(const cv::Mat& image, PerturbModel model, int level, int index, double time_s,
                     std::uint64_t noise_key);

// Copies the dataset folder `in` (TUM RGB-D with rgb.txt, or EuRoC with mav0/) to `out` with
// every camera image perturbed; text, depth and ground-truth files are copied unchanged.
// Returns the number of images perturbed.
// `on_image(done, total)` is called after each image is written, one call at a time (images
// are perturbed in parallel), e.g. for a progress line.
using PerturbProgress = std::function<void(std::size_t done, std::size_t total)>;
int perturbDataset(const std::filesystem::path& in, const std::filesystem::path& out,
                   PerturbModel model, int level, std::uint64_t seed,
                   const PerturbProgress& on_image = {});

}  // namespace lumaslam::synth
