// Stereo front end on the real EuRoC V1_01 pair (752x480, rectified once with the dataset's
// calibration; rectification itself is BM_StereoRectifyPair in bench_camera.cpp):
// StereoMatcher alone (1000 features per image, after each enhancement preset), and a whole stereo
// frame (FrameBuilder::buildStereo: both extractions concurrently + matching).
#include <algorithm>
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <tuple>

#include <benchmark/benchmark.h>

#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/feature/stereo_matcher.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/track/frame_builder.h"

namespace {

using namespace lumaslam;

struct RectifiedPair {
  std::optional<camera::StereoRectifier> rectifier;
  cv::Mat rawLeft, rawRight, left, right;
};

const RectifiedPair& eurocPair() {
  static const RectifiedPair pair = [] {
    RectifiedPair p;
    const auto root = std::filesystem::path(LUMASLAM_SHARED_DIR) / "data/euroc/V1_01_easy_micro";
    if (!std::filesystem::exists(root)) return p;
    auto reader = io::openDataset("euroc:" + root.string());
    const auto calibration = reader->calibration();
    const auto frame = reader->next();
    if (!calibration || !calibration->right || !calibration->T_left_right || !frame) return p;
    p.rectifier.emplace(camera::PinholeCamera::fromSettings(calibration->left),
                        camera::PinholeCamera::fromSettings(*calibration->right),
                        *calibration->T_left_right);
    p.rawLeft = frame->image;
    p.rawRight = frame->right;
    std::tie(p.left, p.right) = p.rectifier->rectify(frame->image, frame->right);
    return p;
  }();
  return pair;
}

track::FrameCamera frameCameraOf(const camera::StereoRectifier& rectifier) {
  return {rectifier.rectifiedCamera(), rectifier.bf(), 35.0 * rectifier.baseline()};
}

// Argument: enhancement preset applied to both images first (each with its own Enhancer, as
// Pipeline does), to count what it does to the number of stereo matches.
const char* const kPresets[] = {"off", "best", "clahe", "paper"};

cv::Mat enhanced(const cv::Mat& image, const char* preset) {
  if (std::string(preset) == "off") return image;
  enhance::Enhancer enhancer(enhance::EnhancerParams::forPreset(preset));
  return enhancer.enhance(image).gray;
}

void BM_StereoMatch(benchmark::State& state) {
  const auto& pair = eurocPair();
  if (!pair.rectifier) return state.SkipWithError("EuRoC micro excerpt missing");
  const char* preset = kPresets[state.range(0)];
  const feature::OrbExtractor extractor{feature::OrbSettings{}};
  const auto left = extractor.extract(enhanced(pair.left, preset));
  const auto right = extractor.extract(enhanced(pair.right, preset));
  feature::StereoMatcherParams params;
  params.bf = pair.rectifier->bf();
  params.minDepth = pair.rectifier->baseline();
  const feature::StereoMatcher matcher(params, extractor.levels());
  feature::StereoMatches matches;
  for (auto _ : state) {
    matches = matcher.match(left, right);
    benchmark::DoNotOptimize(matches.depth.data());
  }
  state.SetLabel(std::string("752x480, enhancement ") + preset);
  state.counters["features"] = static_cast<double>(left.keypoints.size());
  state.counters["matched"] = matches.matched;
}
BENCHMARK(BM_StereoMatch)->ArgNames({"enhance"})->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_StereoFrame(benchmark::State& state) {
  const auto& pair = eurocPair();
  if (!pair.rectifier) return state.SkipWithError("EuRoC micro excerpt missing");
  const track::FrameBuilder builder(frameCameraOf(*pair.rectifier), feature::OrbSettings{});
  std::size_t index = 0;
  for (auto _ : state) {
    auto frame = builder.buildStereo(index++, 0.0, pair.left, pair.right);
    benchmark::DoNotOptimize(frame.features.get());
  }
}
BENCHMARK(BM_StereoFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
