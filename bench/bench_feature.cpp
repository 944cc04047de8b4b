// ORB extraction: ours (sequential and per-level parallel) vs cv::ORB with the same settings
// (1000 features, 8 levels, scale 1.2) on real and synthetic frames; counters report the
// feature count and the 8x8 grid coverage. Plus the matchers on a real frame pair.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/feature/descriptor_matcher.h"
#include "lumaslam/feature/grid_coverage.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/feature/projection_matcher.h"
#include "lumaslam/synth/sequence.h"

namespace {

namespace fs = std::filesystem;
using namespace lumaslam::feature;

fs::path eurocCam0(int index) {
  std::vector<fs::path> files;
  const fs::path folder =
      fs::path(LUMASLAM_SHARED_DIR) / "data/euroc/V1_01_easy_micro/mav0/cam0/data";
  for (const auto& entry : fs::directory_iterator(folder)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files.at(index);
}

// Frame 0 of a synthetic preset (640x480, rendered in memory), gray.
cv::Mat syntheticImage(const char* preset_name) {
  const lumaslam::synth::Preset& preset = lumaslam::synth::findPreset(preset_name);
  const lumaslam::synth::SequenceRenderer sequence(preset, preset.frames, 1);
  cv::Mat gray;
  cv::cvtColor(sequence.render(0).cam0.image, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

// 0: EuRoC 752x480, 1: its central 640x480 crop, 2: KITTI 1226x370, 3: synthetic xyz-rgbd
// 640x480, 4: synthetic dark-rgbd 640x480 (most FAST cells fall back to the low threshold).
cv::Mat benchImage(int which) {
  if (which == 3) return syntheticImage("xyz-rgbd");
  if (which == 4) return syntheticImage("dark-rgbd");
  if (which == 2) {
    return cv::imread((fs::path(LUMASLAM_SHARED_DIR) /
                       "data/kitti/odometry_07_first160/sequences/07/image_0/000000.png")
                          .string(),
                      cv::IMREAD_GRAYSCALE);
  }
  const cv::Mat euroc = cv::imread(eurocCam0(0).string(), cv::IMREAD_GRAYSCALE);
  if (which == 1 && !euroc.empty()) return euroc(cv::Rect(56, 0, 640, 480)).clone();
  return euroc;
}

void labelAndCount(benchmark::State& state, const cv::Mat& image,
                   const std::vector<cv::KeyPoint>& keypoints) {
  state.SetLabel(std::to_string(image.cols) + "x" + std::to_string(image.rows));
  state.counters["features"] = static_cast<double>(keypoints.size());
  state.counters["coverage8x8"] = gridCoverage(keypoints, image.size());
}

void BM_OrbOurs(benchmark::State& state) {
  const cv::Mat image = benchImage(static_cast<int>(state.range(0)));
  if (image.empty()) return state.SkipWithError("bench image missing (LUMASLAM_SHARED_DIR)");
  OrbSettings settings;
  settings.parallelLevels = state.range(1) != 0;
  const int previousThreads = cv::getNumThreads();
  if (!settings.parallelLevels) cv::setNumThreads(1);
  const OrbExtractor extractor(settings);
  OrbFeatures features;
  for (auto _ : state) {
    features = extractor.extract(image);
    benchmark::DoNotOptimize(features.descriptors.data);
  }
  cv::setNumThreads(previousThreads);
  labelAndCount(state, image, features.keypoints);
}
BENCHMARK(BM_OrbOurs)
    ->ArgNames({"image", "parallel"})
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

void BM_OrbOpenCv(benchmark::State& state) {
  const cv::Mat image = benchImage(static_cast<int>(state.range(0)));
  if (image.empty()) return state.SkipWithError("bench image missing (LUMASLAM_SHARED_DIR)");
  const int previousThreads = cv::getNumThreads();
  cv::setNumThreads(1);
  const auto orb = cv::ORB::create(1000, 1.2f, 8);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (auto _ : state) {
    orb->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
    benchmark::DoNotOptimize(descriptors.data);
  }
  cv::setNumThreads(previousThreads);
  labelAndCount(state, image, keypoints);
}
BENCHMARK(BM_OrbOpenCv)->ArgNames({"image"})->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

struct FramePair {
  OrbFeatures a, b;
  cv::Size size;
};

const FramePair& framePair() {
  static const FramePair pair = [] {
    const OrbExtractor extractor{OrbSettings{}};
    const cv::Mat first = cv::imread(eurocCam0(0).string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat second = cv::imread(eurocCam0(1).string(), cv::IMREAD_GRAYSCALE);
    FramePair p;
    if (first.empty() || second.empty()) return p;
    p.a = extractor.extract(first);
    p.b = extractor.extract(second);
    p.size = first.size();
    return p;
  }();
  return pair;
}

void BM_MatchBruteForce(benchmark::State& state) {
  const FramePair& pair = framePair();
  if (pair.a.keypoints.empty()) return state.SkipWithError("bench images missing");
  std::size_t matches = 0;
  for (auto _ : state) matches = matchBruteForce(pair.a.descriptors, pair.b.descriptors).size();
  state.counters["matches"] = static_cast<double>(matches);
}
BENCHMARK(BM_MatchBruteForce)->Unit(benchmark::kMillisecond);

void BM_MatchByProjection(benchmark::State& state) {
  const FramePair& pair = framePair();
  if (pair.a.keypoints.empty()) return state.SkipWithError("bench images missing");
  std::vector<ProjectedPoint> points;
  for (int i = 0; i < static_cast<int>(pair.a.keypoints.size()); ++i) {
    const cv::KeyPoint& k = pair.a.keypoints[i];
    points.push_back({k.pt, k.octave, descriptorAt(pair.a.descriptors, i), k.angle});
  }
  const OrbExtractor extractor{OrbSettings{}};
  ProjectionSearchOptions options;
  options.radius = 15.0f;
  options.checkRotation = true;
  std::size_t matches = 0;
  for (auto _ : state) {
    const FeatureGrid grid(pair.b.keypoints, pair.size);  // built per frame by the tracker
    matches =
        matchByProjection(points, grid, pair.b.descriptors, extractor.levels(), options).size();
  }
  state.counters["matches"] = static_cast<double>(matches);
}
BENCHMARK(BM_MatchByProjection)->Unit(benchmark::kMillisecond);

}  // namespace
