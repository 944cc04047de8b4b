// `lumaslam vocab`: train a place-recognition vocabulary from images, convert ORB-SLAM's
// DBoW2 text vocabulary (ORBvoc.txt) to our binary format, describe a vocabulary file, and
// measure its place recognition on a dataset with poses (vocab_eval.h).
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>
#include <opencv2/imgproc.hpp>

#include "command_registry.h"
#include "image_inputs.h"
#include "lumaslam/core/error.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "lumaslam/loop/vocabulary_training.h"
#include "progress_line.h"
#include "vocab_eval.h"

namespace lumaslam::cli {
namespace {

struct VocabOptions {
  std::vector<std::string> inputs;
  std::string out;
  std::string file;  // convert / info input
  loop::TrainingParams training;
  int features = 1000;
  int max_images = 0;
  int stride = 1;
};

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

cv::Mat toGray(const cv::Mat& image, const std::string& name) {
  cv::Mat gray;
  if (image.depth() != CV_8U) fail("{}: expected an 8-bit image for ORB", name);
  if (image.channels() == 1) return image;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

// "INPUT@N": every Nth frame of that input (overrides --stride); an existing path ending in
// "@digits" is taken as it is.
std::pair<std::string, int> inputAndStride(const std::string& input, int stride) {
  const std::size_t at = input.rfind('@');
  if (at == std::string::npos || at + 1 == input.size() || std::filesystem::exists(input)) {
    return {input, stride};
  }
  const std::string_view digits = std::string_view(input).substr(at + 1);
  if (digits.find_first_not_of("0123456789") != std::string_view::npos) return {input, stride};
  int own = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), own);
  if (ec != std::errc() || own < 1) fail("{}: the stride after '@' must be 1..2^31", input);
  return {input.substr(0, at), own};
}

void printSummary(const loop::Vocabulary& vocabulary) {
  std::size_t weighted = 0;
  for (loop::WordId w = 0; w < vocabulary.wordCount(); ++w) weighted += vocabulary.weight(w) > 0;
  std::printf("k %d\nL %d\nnodes %zu\nwords %zu\nwords with weight > 0 %zu\n",
              vocabulary.branching(), vocabulary.depth(), vocabulary.nodeCount(),
              vocabulary.wordCount(), weighted);
}

int runTrain(const VocabOptions& options) {
  if (options.features < 1) fail("--features must be >= 1 (got {})", options.features);
  feature::OrbSettings settings;
  settings.nFeatures = options.features;
  const feature::OrbExtractor extractor(settings);
  std::vector<cv::Mat> descriptors;
  std::size_t count = 0;
  const auto start = std::chrono::steady_clock::now();
  // Ended before the training's own log lines; the total is known only with --max-images.
  auto progress = std::make_optional<ProgressLine>(
      "image", options.max_images > 0 ? static_cast<std::size_t>(options.max_images) : 0);
  for (const auto& input : options.inputs) {
    const int remaining =
        options.max_images > 0 ? options.max_images - static_cast<int>(descriptors.size()) : 0;
    if (options.max_images > 0 && remaining <= 0) break;
    const auto [path, stride] = inputAndStride(input, options.stride);
    const std::size_t before = descriptors.size();
    forEachInputImage(path, remaining, stride, [&](const std::string& name, const cv::Mat& image) {
      descriptors.push_back(extractor.extract(toGray(image, name)).descriptors);
      count += static_cast<std::size_t>(descriptors.back().rows);
      progress->update(descriptors.size(), "extracting");
    });
    spdlog::info("{}: {} images (every {})", path, descriptors.size() - before, stride);
  }
  progress.reset();
  if (descriptors.empty()) fail("no images found in the inputs");
  spdlog::info("{} images, {} ORB descriptors in {:.1f} s", descriptors.size(), count,
               secondsSince(start));
  const auto train_start = std::chrono::steady_clock::now();
  std::optional<ProgressLine> clustering;
  const loop::Vocabulary vocabulary = loop::trainVocabulary(
      descriptors, options.training, [&clustering](std::size_t done, std::size_t total) {
        if (!clustering) clustering.emplace("descriptor", total);
        clustering->update(done, "clustering");
      });
  clustering.reset();
  const double train_seconds = secondsSince(train_start);
  loop::saveVocabulary(vocabulary, options.out);
  std::printf("images %zu\ndescriptors %zu\ntraining seconds %.2f\n", descriptors.size(), count,
              train_seconds);
  printSummary(vocabulary);
  std::printf("wrote %s\n", options.out.c_str());
  return 0;
}

int runConvert(const VocabOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const loop::Vocabulary vocabulary = loop::loadDbow2Text(options.file);
  const double read_seconds = secondsSince(start);
  loop::saveVocabulary(vocabulary, options.out);
  std::printf("text load seconds %.2f\n", read_seconds);
  printSummary(vocabulary);
  std::printf("wrote %s\n", options.out.c_str());
  return 0;
}

int runInfo(const VocabOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const bool binary = loop::isBinaryVocabulary(options.file);
  const loop::Vocabulary vocabulary = loop::loadAnyVocabulary(options.file);
  std::printf("format %s\nload seconds %.3f\n", binary ? "lumaslam-binary" : "dbow2-text",
              secondsSince(start));
  printSummary(vocabulary);
  return 0;
}

const bool registered = registerCommand(
    "vocab", "Place-recognition vocabulary: train, convert ORBvoc.txt, info, eval",
    [](CLI::App& cmd) -> Runner {
      auto options = std::make_shared<VocabOptions>();
      cmd.require_subcommand(1);
      CLI::App* train = cmd.add_subcommand("train", "Train a vocabulary tree from images");
      train
          ->add_option("INPUT", options->inputs,
                       "Images, image folders or dataset specs (tum:PATH, video:FILE, ...); "
                       "INPUT@N takes every Nth frame of that input")
          ->required();
      train->add_option("--out", options->out, "Binary vocabulary file to write")->required();
      train->add_option("--k", options->training.branching, "Branching factor (default 10)");
      train->add_option("--levels", options->training.depth, "Depth L (default 6)");
      train->add_option("--iterations", options->training.max_iterations,
                        "k-majority iterations per split (default 10)");
      train->add_option("--seed", options->training.seed, "Seed of the k-means++ seeding");
      train->add_option("--features", options->features, "ORB features per image (default 1000)");
      train->add_option("--max-images", options->max_images, "Use at most this many images");
      train->add_option("--stride", options->stride, "Use every Nth frame of each input");
      CLI::App* convert =
          cmd.add_subcommand("convert", "Convert a DBoW2 text vocabulary (ORBvoc.txt) to binary");
      convert->add_option("TEXT", options->file, "DBoW2 text vocabulary")->required();
      convert->add_option("--out", options->out, "Binary vocabulary file to write")->required();
      CLI::App* info = cmd.add_subcommand("info", "Describe a vocabulary file (binary or text)");
      info->add_option("FILE", options->file, "Vocabulary file")->required();
      auto eval_options = std::make_shared<VocabEvalOptions>();
      CLI::App* eval = cmd.add_subcommand(
          "eval", "Place-recognition recall / precision of a vocabulary on a dataset with poses");
      eval->add_option("FILE", eval_options->vocabulary, "Vocabulary file")->required();
      eval->add_option("--dataset", eval_options->dataset, "tum:PATH, kitti:PATH, ... with GT")
          ->required();
      eval->add_option("--keyframe-every", eval_options->keyframe_every,
                       "Every Nth frame is a keyframe, the others query")
          ->capture_default_str();
      eval->add_option("--max-distance", eval_options->max_distance,
                       "A keyframe within this many metres ...")
          ->capture_default_str();
      eval->add_option("--max-angle", eval_options->max_angle_deg,
                       "... and degrees of the query is a correct answer")
          ->capture_default_str();
      eval->add_option("--exclude-window", eval_options->exclude_window,
                       "Hide keyframes within N frames of the query (revisits only)")
          ->capture_default_str();
      eval->add_option("--features", eval_options->features, "ORB features per frame")
          ->capture_default_str();
      eval->add_option("--top", eval_options->top, "Also count a correct answer in the first N")
          ->capture_default_str();
      return [options, eval_options, train, convert, eval] {
        if (train->parsed()) return runTrain(*options);
        if (convert->parsed()) return runConvert(*options);
        if (eval->parsed()) return runVocabEval(*eval_options);
        return runInfo(*options);
      };
    });

}  // namespace
}  // namespace lumaslam::cli
