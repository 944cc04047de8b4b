// Enhancement speed, single-threaded (cv::setNumThreads(1)), on 640x480 (and 752x480) dark
// synthetic frames: our CLAHE against cv::CLAHE (same grid, same limit), each stage of the
// pipeline, and the whole pipeline against the stage-by-stage ReferenceEnhancer.
// Run: ./lumaslam_bench --benchmark_filter=Enhance --benchmark_repetitions=9
//      --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/enhance/adaptive_limit.h"
#include "lumaslam/enhance/brightness_compensation.h"
#include "lumaslam/enhance/clahe.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/enhance/quality_gate.h"
#include "lumaslam/enhance/reference_pipeline.h"
#include "lumaslam/enhance/value_channel.h"

namespace {

using namespace lumaslam::enhance;

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

const cv::Mat& bgrFrame() {
  static const cv::Mat frame = benchFrame(640, 480, 3);
  return frame;
}

const cv::Mat& grayFrame() {
  static const cv::Mat gray = [] {
    cv::Mat g;
    cv::cvtColor(bgrFrame(), g, cv::COLOR_BGR2GRAY);
    return g;
  }();
  return gray;
}

void BM_EnhanceOurClahe(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat gray = benchFrame(static_cast<int>(state.range(0)), 480, 1);
  const Clahe clahe(8, 8);
  for (auto _ : state) benchmark::DoNotOptimize(clahe.apply(gray, 2.0).data);
}
BENCHMARK(BM_EnhanceOurClahe)->Arg(640)->Arg(752)->Unit(benchmark::kMicrosecond);

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
BENCHMARK(BM_EnhanceOpenCvClahe)->Arg(640)->Arg(752)->Unit(benchmark::kMicrosecond);

// ---- stages, 640x480 --------------------------------------------------------------------
void BM_EnhanceStageGate(benchmark::State& state) {  // Eq. 1-3: Lmean, Lstd
  cv::setNumThreads(1);
  for (auto _ : state) benchmark::DoNotOptimize(measureBrightness(grayFrame()).mean);
}
BENCHMARK(BM_EnhanceStageGate)->Unit(benchmark::kMicrosecond);

void BM_EnhanceStageBrightnessLut(benchmark::State& state) {  // Eq. 4: table + cv::LUT
  cv::setNumThreads(1);
  CompensationParams params;
  params.weights = CompensationWeights::kSwapped;
  const BrightnessCompensation compensation(params);
  for (auto _ : state) benchmark::DoNotOptimize(compensation.apply(grayFrame(), 0.15).data);
}
BENCHMARK(BM_EnhanceStageBrightnessLut)->Unit(benchmark::kMicrosecond);

void BM_EnhanceStageValue(benchmark::State& state) {  // Eq. 5: V = max(B, G, R)
  cv::setNumThreads(1);
  cv::Mat value;
  for (auto _ : state) {
    valueChannel(bgrFrame(), value);
    benchmark::DoNotOptimize(value.data);
  }
}
BENCHMARK(BM_EnhanceStageValue)->Unit(benchmark::kMicrosecond);

void BM_EnhanceStageValueSplitMax(benchmark::State& state) {  // the former cv::split + cv::max
  cv::setNumThreads(1);
  cv::Mat planes[3];
  cv::Mat value;
  for (auto _ : state) {
    cv::split(bgrFrame(), planes);
    cv::max(planes[0], planes[1], value);
    cv::max(value, planes[2], value);
    benchmark::DoNotOptimize(value.data);
  }
}
BENCHMARK(BM_EnhanceStageValueSplitMax)->Unit(benchmark::kMicrosecond);

void BM_EnhanceStageGray(benchmark::State& state) {  // the `gray` work channel
  cv::setNumThreads(1);
  cv::Mat gray;
  for (auto _ : state) {
    cv::cvtColor(bgrFrame(), gray, cv::COLOR_BGR2GRAY);
    benchmark::DoNotOptimize(gray.data);
  }
}
BENCHMARK(BM_EnhanceStageGray)->Unit(benchmark::kMicrosecond);

// Eq. 12-13 on the whole frame; arg 0: fused (measureContrast), 1: via the 16-bit Laplacian
// image (ContrastImages), 2: gradient sigma.
void BM_EnhanceStageContrast(benchmark::State& state) {
  cv::setNumThreads(1);
  for (auto _ : state) {
    ContrastStats stats;
    if (state.range(0) == 0) stats = measureContrast(grayFrame(), SigmaSource::kIntensity);
    if (state.range(0) == 1) stats = ContrastImages(grayFrame(), SigmaSource::kIntensity).stats();
    if (state.range(0) == 2) stats = measureContrast(grayFrame(), SigmaSource::kGradient);
    benchmark::DoNotOptimize(stats.d);
  }
}
BENCHMARK(BM_EnhanceStageContrast)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// CLAHE with the given grid (arg) and limit 9: ours, then cv::CLAHE.
void BM_EnhanceStageClahe(benchmark::State& state) {
  cv::setNumThreads(1);
  const int tiles = static_cast<int>(state.range(0));
  const Clahe clahe(tiles, tiles);
  for (auto _ : state) benchmark::DoNotOptimize(clahe.apply(grayFrame(), 9.0).data);
}
BENCHMARK(BM_EnhanceStageClahe)->Arg(1)->Arg(8)->Unit(benchmark::kMicrosecond);

void BM_EnhanceStageOpenCvClahe(benchmark::State& state) {
  cv::setNumThreads(1);
  const int tiles = static_cast<int>(state.range(0));
  const auto clahe = cv::createCLAHE(9.0, {tiles, tiles});
  cv::Mat out;
  for (auto _ : state) {
    clahe->apply(grayFrame(), out);
    benchmark::DoNotOptimize(out.data);
  }
}
BENCHMARK(BM_EnhanceStageOpenCvClahe)->Arg(1)->Arg(8)->Unit(benchmark::kMicrosecond);

// Eq. 8: BGR scaled by new/old; arg 1 adds the gray of the result (what the `value` channel
// needs for tracking).
void BM_EnhanceStageRebuild(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat value = valueChannel(bgrFrame());
  const cv::Mat brighter = Clahe(1, 1).apply(value, 9.0);
  cv::Mat colour;
  cv::Mat gray;
  for (auto _ : state) {
    rebuildColour(bgrFrame(), value, brighter, colour);
    if (state.range(0) == 1) cv::cvtColor(colour, gray, cv::COLOR_BGR2GRAY);
    benchmark::DoNotOptimize(colour.data);
  }
}
BENCHMARK(BM_EnhanceStageRebuild)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// ---- whole pipeline, 640x480; arg: 1 gray, 3 BGR ------------------------------------------
const cv::Mat& pipelineFrame(int channels) {
  return channels == 1 ? grayFrame() : bgrFrame();
}

void BM_EnhancePipeline(benchmark::State& state, const std::string& preset) {
  cv::setNumThreads(1);
  const cv::Mat& frame = pipelineFrame(static_cast<int>(state.range(0)));
  Enhancer enhancer(EnhancerParams::forPreset(preset));
  for (auto _ : state) benchmark::DoNotOptimize(enhancer.enhance(frame).gray.data);
}

void BM_EnhancePipelineReference(benchmark::State& state, const std::string& preset) {
  cv::setNumThreads(1);
  const cv::Mat& frame = pipelineFrame(static_cast<int>(state.range(0)));
  ReferenceEnhancer enhancer(EnhancerParams::forPreset(preset));
  for (auto _ : state) benchmark::DoNotOptimize(enhancer.enhance(frame).gray.data);
}

// A 752x480 gray stereo pair (the right image 10 % darker) with `best`; arg: 0 independent
// (two enhance calls), 1 decisions (left plan, right tables from its own histograms), 2 shared
// (left plan applied to both). Sequential here; the Pipeline runs the right image beside the left.
void BM_EnhanceStereoPair(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat left = benchFrame(752, 480, 1);
  cv::Mat right;
  left.convertTo(right, CV_8U, 0.9);
  const auto mode = state.range(0);
  Enhancer enhancer(EnhancerParams::forPreset("best"));
  Enhancer right_enhancer(EnhancerParams::forPreset("best"));
  for (auto _ : state) {
    if (mode == 0) {
      benchmark::DoNotOptimize(enhancer.enhance(left).gray.data);
      benchmark::DoNotOptimize(right_enhancer.enhance(right).gray.data);
      continue;
    }
    const EnhancementPlan plan = enhancer.plan(left);
    benchmark::DoNotOptimize(enhancer.apply(left, plan).gray.data);
    benchmark::DoNotOptimize(mode == 1 ? enhancer.enhanceWith(right, plan).gray.data
                                       : enhancer.apply(right, plan).gray.data);
  }
}
BENCHMARK(BM_EnhanceStereoPair)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

#define LUMASLAM_PIPELINE_BENCH(fn, preset) \
  BENCHMARK_CAPTURE(fn, preset, std::string(#preset))->Arg(1)->Arg(3)->Unit(benchmark::kMicrosecond)

LUMASLAM_PIPELINE_BENCH(BM_EnhancePipeline, best);
LUMASLAM_PIPELINE_BENCH(BM_EnhancePipeline, paper);
LUMASLAM_PIPELINE_BENCH(BM_EnhancePipeline, full);
LUMASLAM_PIPELINE_BENCH(BM_EnhancePipelineReference, best);
LUMASLAM_PIPELINE_BENCH(BM_EnhancePipelineReference, paper);
LUMASLAM_PIPELINE_BENCH(BM_EnhancePipelineReference, full);

}  // namespace
