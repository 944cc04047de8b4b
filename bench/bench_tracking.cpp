// Per-frame cost of RGB-D tracking without enhancement and detection (issue 5's speed target:
// median <= 15 ms at 640x480 with 1000 features): Pipeline::track over frames of the synthetic
// xyz-rgbd sequence rendered in memory, local mapping in its own thread as `lumaslam run`
// does it. The reference in the same process is cv::ORB (1000 features) on the same frames.
// CPU time is the calling thread's (feature extraction + tracking); the counters give the
// median per-frame stage times that Pipeline reports (wall clock, so they include waiting for
// the cores under load).
#include <algorithm>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/synth/dataset_writer.h"
#include "lumaslam/synth/sequence.h"
#include "lumaslam/pipeline.h"

namespace {

using namespace lumaslam;

constexpr int kFrames = 100;

struct RenderedSequence {
  std::unique_ptr<synth::SequenceRenderer> renderer;
  std::vector<SensorFrame> frames;
  std::vector<cv::Mat> gray;
};

const RenderedSequence& xyzRgbd() {
  static const RenderedSequence sequence = [] {
    RenderedSequence s;
    s.renderer =
        std::make_unique<synth::SequenceRenderer>(synth::findPreset("xyz-rgbd"), kFrames, 1);
    for (int i = 0; i < kFrames; ++i) {
      const synth::Frame frame = s.renderer->render(i);
      SensorFrame input;
      input.index = static_cast<std::size_t>(i);
      input.timestamp = frame.timestamp();
      input.image = frame.cam0.image;
      input.depth = frame.sensor_depth;
      s.frames.push_back(input);
      cv::Mat gray;
      cv::cvtColor(frame.cam0.image, gray, cv::COLOR_BGR2GRAY);
      s.gray.push_back(gray);
    }
    return s;
  }();
  return sequence;
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// One iteration = the whole sequence through a fresh Pipeline; time is reported per frame.
void BM_TrackRgbdSequence(benchmark::State& state) {
  const RenderedSequence& sequence = xyzRgbd();
  const auto file = std::make_shared<const core::SettingsFile>(
      core::SettingsFile::fromString(synth::settingsYaml(*sequence.renderer), "xyz-rgbd.yaml"));
  const io::Settings settings = io::Settings::fromFile(file);
  PipelineOptions options;
  options.enhance_preset = "off";
  options.detector = "none";
  std::vector<double> features, tracking, total;
  std::size_t tracked = 0;
  for (auto _ : state) {
    state.PauseTiming();
    features.clear();
    tracking.clear();
    total.clear();
    tracked = 0;
    auto system = std::make_unique<Pipeline>(settings, options);
    state.ResumeTiming();
    for (const SensorFrame& frame : sequence.frames) {
      const FrameResult result = system->track(frame);
      features.push_back(result.timing.features);
      tracking.push_back(result.timing.tracking);
      total.push_back(result.timing.total);
      if (result.outcome.state == track::TrackingState::Ok) ++tracked;
    }
    state.PauseTiming();
    system->shutdown();
    system.reset();
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * kFrames);  // frames per second
  state.counters["tracked"] = static_cast<double>(tracked);
  state.counters["features_ms_median"] = median(features);
  state.counters["tracking_ms_median"] = median(tracking);
  state.counters["total_ms_median"] = median(total);
}
BENCHMARK(BM_TrackRgbdSequence)->Unit(benchmark::kMillisecond)->Iterations(1);

// The reference: cv::ORB with 1000 features on the same frames, one thread.
void BM_OrbOpenCvRgbdSequence(benchmark::State& state) {
  const RenderedSequence& sequence = xyzRgbd();
  const int previousThreads = cv::getNumThreads();
  cv::setNumThreads(1);
  const auto orb = cv::ORB::create(1000, 1.2f, 8);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (auto _ : state) {
    for (const cv::Mat& gray : sequence.gray) {
      orb->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
      benchmark::DoNotOptimize(descriptors.data);
    }
  }
  cv::setNumThreads(previousThreads);
  state.SetItemsProcessed(state.iterations() * kFrames);
}
BENCHMARK(BM_OrbOpenCvRgbdSequence)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
