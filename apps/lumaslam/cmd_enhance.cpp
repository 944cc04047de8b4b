// `lumaslam enhance`: enhance an image, a folder or a dataset (writes enhanced images and
// previews, prints per-frame decisions), calibrate sigma_max / d_max over a sequence, and run
// the measurements behind docs/enhancement.md (--evaluate-pairs, --evaluate-darkened,
// --evaluate-stereo).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_checks.h"
#include "command_registry.h"
#include "image_inputs.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/enhance/evaluation.h"
#include "lumaslam/enhance/stereo_enhancement.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/track/stereo_match_counter.h"

namespace lumaslam::cli {
namespace {

namespace fs = std::filesystem;
using enhance::EnhancerParams;

struct EnhanceOptions {
  std::string input;
  std::string out;
  std::string preset;
  std::string settings;
  std::string calibrate;
  std::string evaluate_pairs;
  std::string evaluate_darkened;
  std::string evaluate_stereo;
  std::vector<std::string> extra;  // settings files scored as extra candidates
  int max_frames = 0;
  int stride = 1;
};

EnhancerParams loadParams(const EnhanceOptions& options) {
  EnhancerParams params =
      options.settings.empty()
          ? EnhancerParams::forPreset("best")
          : EnhancerParams::fromSettings(core::SettingsFile::open(options.settings));
  if (!options.preset.empty()) {
    if (!options.settings.empty()) fail("give either --preset or --settings, not both");
    params = EnhancerParams::forPreset(options.preset);
  }
  return params;
}

cv::Mat toBgr(const cv::Mat& image) {
  cv::Mat bgr;
  if (image.channels() == 1)
    cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  else if (image.channels() == 4)
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  else
    bgr = image;
  return bgr;
}

// Gray-level histogram drawn in a width x height panel.
cv::Mat histogramPanel(const cv::Mat& image, int width, int height) {
  cv::Mat gray;
  cv::cvtColor(toBgr(image), gray, cv::COLOR_BGR2GRAY);
  cv::Mat hist;
  const int channels[] = {0};
  const int bins[] = {256};
  const float range[] = {0, 256};
  const float* ranges[] = {range};
  cv::calcHist(&gray, 1, channels, cv::Mat(), hist, 1, bins, ranges);
  double max_count = 0.0;
  cv::minMaxLoc(hist, nullptr, &max_count);
  cv::Mat panel(height, width, CV_8UC3, cv::Scalar(30, 30, 30));
  for (int g = 0; g < 256; ++g) {
    const int x0 = g * width / 256;
    const int x1 = std::max((g + 1) * width / 256, x0 + 1);
    const int bar = static_cast<int>(hist.at<float>(g) / std::max(max_count, 1.0) * (height - 2));
    cv::rectangle(panel, {x0, height - 1 - bar}, {x1 - 1, height - 1}, cv::Scalar(200, 200, 200),
                  cv::FILLED);
  }
  return panel;
}

cv::Mat preview(const cv::Mat& original, const cv::Mat& enhanced) {
  const cv::Mat before = toBgr(original);
  const cv::Mat after = toBgr(enhanced);
  const int hist_height = std::max(before.rows / 4, 40);
  cv::Mat top;
  cv::Mat bottom;
  cv::hconcat(before, after, top);
  cv::hconcat(histogramPanel(before, before.cols, hist_height),
              histogramPanel(after, after.cols, hist_height), bottom);
  cv::Mat result;
  cv::vconcat(top, bottom, result);
  return result;
}

std::string describe(const enhance::FrameReport& r) {
  std::string text = fmt::format("Q={} Lmean={:.3f} Lstd={:.3f}", r.compensated ? 1 : 0,
                                 r.brightness.mean, r.brightness.std);
  text += r.contrast ? fmt::format(" sigma={:.2f} d={:.1f}", r.contrast->sigma, r.contrast->d)
                     : std::string(" sigma=- d=-");
  text += r.limit ? fmt::format(" limit={:.3f}", *r.limit) : std::string(" limit=-");
  return text;
}

void writeImage(const fs::path& path, const cv::Mat& image) {
  if (!cv::imwrite(path.string(), image)) fail("{}: cannot write image", path.string());
}

int runEnhance(const EnhanceOptions& options) {
  if (options.input.empty()) fail("INPUT is required (an image, a folder or a dataset spec)");
  enhance::Enhancer enhancer(loadParams(options));
  if (!options.out.empty()) fs::create_directories(options.out);
  std::printf("# preset %s\n", enhancer.params().preset.c_str());
  forEachInputImage(options.input, options.max_frames, options.stride,
                    [&](const std::string& name, const cv::Mat& image) {
                      enhance::EnhancedFrame frame;
                      try {
                        frame = enhancer.enhance(image);
                      } catch (const Error& e) {
                        fail("{}: {}", name, e.what());
                      }
                      std::printf("%s %s\n", name.c_str(), describe(frame.report).c_str());
                      if (options.out.empty()) return;
                      writeImage(fs::path(options.out) / (name + ".png"), frame.colour);
                      writeImage(fs::path(options.out) / (name + "_preview.jpg"),
                                 preview(image, frame.colour));
                    });
  return 0;
}

int runCalibrate(const EnhanceOptions& options) {
  const enhance::Enhancer enhancer(loadParams(options));
  enhance::ContrastMaxima maxima;
  int frames = 0;
  forEachInputImage(options.calibrate, options.max_frames, options.stride,
                    [&](const std::string&, const cv::Mat& image) {
                      for (const auto& stats : enhancer.contrastOf(image)) maxima.observe(stats);
                      ++frames;
                    });
  EnhancerParams calibrated = enhancer.params();
  calibrated.clahe.sigma_max = maxima.sigma_max;
  calibrated.clahe.d_max = maxima.d_max;
  calibrated.clahe.maxima = enhance::MaximaSource::kFixed;
  const std::string text = "%YAML:1.0\n# enhance --calibrate " + options.calibrate + " (" +
                           std::to_string(frames) + " frames)\n" + calibrated.toSettingsText();
  std::fputs(text.c_str(), stdout);
  if (!options.out.empty()) {
    fs::create_directories(options.out);
    const fs::path file = fs::path(options.out) / "enhancement_calibrated.yaml";
    std::ofstream(file) << text;
    spdlog::info("wrote {}", file.string());
  }
  return 0;
}

std::vector<enhance::Candidate> candidates(const EnhanceOptions& options) {
  std::vector<enhance::Candidate> list = enhance::standardCandidates();
  for (const auto& file : options.extra) {
    list.push_back(
        enhance::enhancerCandidate(fs::path(file).stem().string(),
                                   EnhancerParams::fromSettings(core::SettingsFile::open(file))));
  }
  return list;
}

int runEvaluatePairs(const EnhanceOptions& options) {
  const auto pairs = enhance::findExposurePairs(options.evaluate_pairs);
  spdlog::info("{} exposure pairs under {}", pairs.size(), options.evaluate_pairs);
  const auto scores = enhance::evaluateExposurePairs(pairs, candidates(options));
  std::printf(
      "| candidate | correct matches | cross-checked matches | keypoints (dark) | "
      "pairs better than raw |\n|---|---:|---:|---:|---:|\n");
  for (const auto& score : scores) {
    int better = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      better += score.correct_per_pair[i] > scores.front().correct_per_pair[i];
    }
    std::printf("| %s | %ld | %ld | %ld | %d/%zu |\n", score.candidate.c_str(), score.correct,
                score.matches, score.keypoints, better, pairs.size());
  }
  return 0;
}

int runEvaluateDarkened(const EnhanceOptions& options) {
  std::vector<cv::Mat> frames;
  forEachInputImage(options.evaluate_darkened, options.max_frames > 0 ? options.max_frames : 20,
                    std::max(options.stride, 1), [&](const std::string&, const cv::Mat& image) {
                      frames.push_back(image.clone());
                    });
  const auto list = candidates(options);
  std::printf(
      "| level (A, gamma, noise) | candidate | keypoints | coverage 8x8 | "
      "correct matches vs original |\n|---|---|---:|---:|---:|\n");
  for (const enhance::DarkeningLevel level :
       {enhance::DarkeningLevel{0.5, 0.8, 0.01}, enhance::DarkeningLevel{0.25, 0.6, 0.01},
        enhance::DarkeningLevel{0.12, 0.5, 0.015}}) {
    for (const auto& score : enhance::evaluateDarkened(frames, level, list)) {
      std::printf("| %.2f, %.1f, %.3f | %s | %.0f | %.3f | %.1f |\n", level.gain, level.gamma,
                  level.noise_std, score.candidate.c_str(), score.keypoints, score.coverage,
                  score.inliers);
    }
  }
  return 0;
}

// Stereo matches per frame (ORB 1000, StereoMatcher) with the pair unenhanced, enhanced
// image by image, and enhanced with one shared plan, for a few presets.
int runEvaluateStereo(const EnhanceOptions& options) {
  auto reader = io::openDataset(options.evaluate_stereo);
  const auto calibration = reader->calibration();
  if (!calibration || !calibration->right || !calibration->T_left_right)
    fail("{}: no stereo calibration (right camera, T_left_right), cannot rectify",
         options.evaluate_stereo);
  const track::StereoMatchCounter counter(*calibration, feature::OrbSettings{});
  struct Mode {
    std::string name;
    std::optional<EnhancerParams> params;
    std::unique_ptr<enhance::Enhancer> left, right;
    long matches = 0;
  };
  std::vector<Mode> modes;
  modes.push_back({"off", std::nullopt, nullptr, nullptr});
  for (const std::string preset : {"best", "paper", "clahe"}) {
    for (const auto mapping :
         {enhance::StereoMapping::kIndependent, enhance::StereoMapping::kDecisions,
          enhance::StereoMapping::kShared}) {
      EnhancerParams params = EnhancerParams::forPreset(preset);
      params.stereo = mapping;
      const char* how = mapping == enhance::StereoMapping::kShared      ? "shared"
                        : mapping == enhance::StereoMapping::kDecisions ? "decisions"
                                                                        : "independent";
      modes.push_back({preset + " " + how, params, std::make_unique<enhance::Enhancer>(params),
                       std::make_unique<enhance::Enhancer>(params)});
    }
  }
  const int max_frames = options.max_frames > 0 ? options.max_frames : 20;
  const int stride = std::max(options.stride, 1);
  int frames = 0;
  for (int index = 0; frames < max_frames; ++index) {
    auto frame = reader->next();
    if (!frame) break;
    if (index % stride != 0) continue;
    if (frame->right.empty())
      fail("{}: frame {} has no right image", options.evaluate_stereo, index);
    auto [left, right] = counter.rectify(frame->image, frame->right);
    if (left.channels() == 3) {
      cv::cvtColor(left, left, cv::COLOR_BGR2GRAY);
      cv::cvtColor(right, right, cv::COLOR_BGR2GRAY);
    }
    for (auto& mode : modes) {
      if (!mode.left) {
        mode.matches += counter.matches(left, right);
        continue;
      }
      const auto [left_gray, right_gray] =
          enhance::enhanceStereoPair(*mode.left, *mode.right, left, right);
      mode.matches += counter.matches(left_gray, right_gray);
    }
    ++frames;
  }
  if (frames == 0) fail("{}: no frames", options.evaluate_stereo);
  std::printf("| enhancement | stereo matches per frame (%d frames) |\n|---|---:|\n", frames);
  for (const auto& mode : modes) {
    std::printf("| %s | %.1f |\n", mode.name.c_str(), static_cast<double>(mode.matches) / frames);
  }
  return 0;
}

int run(const EnhanceOptions& options) {
  if (!options.calibrate.empty()) return runCalibrate(options);
  if (!options.evaluate_pairs.empty()) return runEvaluatePairs(options);
  if (!options.evaluate_darkened.empty()) return runEvaluateDarkened(options);
  if (!options.evaluate_stereo.empty()) return runEvaluateStereo(options);
  return runEnhance(options);
}

const bool registered = registerCommand(
    "enhance", "Multi-level adaptive image enhancement (paper section 3.1)",
    [](CLI::App& cmd) -> Runner {
      auto options = std::make_shared<EnhanceOptions>();
      cmd.add_option("INPUT", options->input,
                     "Image, folder or dataset spec (euroc:PATH, kitti-mono:PATH, ...)");
      cmd.add_option("--out", options->out, "Folder for enhanced images and previews");
      cmd.add_option("--preset", options->preset, "Preset (default: best)")
          ->check(CLI::IsMember(EnhancerParams::presetNames()));
      cmd.add_option("--settings", options->settings, "Settings file with Enhancement.* keys");
      cmd.add_option(
          "--calibrate", options->calibrate,
          "Measure Enhancement.clahe.sigmaMax and dMax over this sequence; print them as settings");
      cmd.add_option("--evaluate-pairs", options->evaluate_pairs,
                     "Score every preset on <scene>_A/_B exposure pairs under this folder");
      cmd.add_option("--evaluate-darkened", options->evaluate_darkened,
                     "Score every preset on darkened frames of this sequence");
      cmd.add_option("--evaluate-stereo", options->evaluate_stereo,
                     "Stereo matches per frame of this stereo dataset, pair enhanced "
                     "independently or with one shared plan");
      cmd.add_option("--extra", options->extra, "Settings files scored as extra candidates");
      cmd.add_option("--max-frames", options->max_frames, "Use at most this many frames")
          ->check(lumaslam::cli::wholeNumber(0, 1'000'000'000));
      cmd.add_option("--stride", options->stride, "Use every Nth frame");
      return [options] { return run(*options); };
    });

}  // namespace
}  // namespace lumaslam::cli
