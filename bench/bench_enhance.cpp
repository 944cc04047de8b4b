// Our CLAHE against cv::CLAHE (same grid, same limit) and the whole enhancement per frame,
// single-threaded. Run: ./lumaslam_bench --benchmark_filter=Enhance
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/enhance/clahe.h"
#include "lumaslam/enhance/enhancer.h"

namespace {

// A dark, textured, noisy 8-bit frame of the given size.
cv::Mat benchFrame(int width, int height, int channels) {
  cv::Mat frame(height, width, CV_8UC(channels));
  cv::RNG rng(42);
  rng.fill(frame, cv::RNG::UNIFORM, 0, 60);
  for (int i = 0; i < 60; ++i) {
    cv::circle(frame, {rng.uniform(0, width), rng.uniform(0, height)}, rng.uniform(5, 60),
               cv::Scalar::all(rng.uniform(0, 90)), cv::FILLED);
  }
  return frame;
}

void BM_EnhanceOurClahe(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat gray = benchFrame(static_cast<int>(state.range(0)), 480, 1);
  const lumaslam::enhance::Clahe clahe(8, 8);
  for (auto _ : state) benchmark::DoNotOptimize(clahe.apply(gray, 2.0).data);
}

void BM_EnhanceOpenCvClahe(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat gray = benchFrame(static_cast<int>(state.range(0)), 480, 1);
  const auto clahe = cv::createCLAHE(2.0, {8, 8});
  cv::Mat out;
  for (auto _ : state) {
    clahe->apply(gray, out);
    benchmark::DoNotOptimize(out.data);
  }
}

// Full pipeline on a 640x480 frame; range(0): 1 gray, 3 BGR; preset by index.
void BM_EnhancePipeline(benchmark::State& state, const std::string& preset) {
  cv::setNumThreads(1);
  const cv::Mat frame = benchFrame(640, 480, static_cast<int>(state.range(0)));
  lumaslam::enhance::Enhancer enhancer(lumaslam::enhance::EnhancerParams::forPreset(preset));
  for (auto _ : state) benchmark::DoNotOptimize(enhancer.enhance(frame).gray.data);
}

}  // namespace

BENCHMARK(BM_EnhanceOurClahe)->Arg(640)->Arg(752)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_EnhanceOpenCvClahe)->Arg(640)->Arg(752)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EnhancePipeline, paper, std::string("paper"))
    ->Arg(1)
    ->Arg(3)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EnhancePipeline, best, std::string("best"))
    ->Arg(1)
    ->Arg(3)
    ->Unit(benchmark::kMicrosecond);
