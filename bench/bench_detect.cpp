// Person detection cost: YOLOv5n inference per frame (640 and 320 models, 1 and 2 OpenCV
// threads), optical-flow propagation per frame, and DetectionWorker push->take latency on
// vtest.avi with stride 1 and 3. Numbers are in docs/dynamic.md.
#include <filesystem>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "lumaslam/detect/box_propagation.h"
#include "lumaslam/detect/detection_worker.h"
#include "lumaslam/detect/yolo_detector.h"

namespace {

using namespace lumaslam::detect;
namespace fs = std::filesystem;

const fs::path kShared = LUMASLAM_SHARED_DIR;

std::unique_ptr<YoloDetector> yolo(int input_size) {
  DetectorParams params;
  params.model = kShared / "models" / (input_size == 640 ? "yolov5n.onnx" : "yolov5n-320.onnx");
  return std::make_unique<YoloDetector>(params);
}

const std::vector<cv::Mat>& videoFrames() {
  static const std::vector<cv::Mat> frames = [] {
    cv::VideoCapture capture((kShared / "data/opencv_samples/vtest/vtest.avi").string());
    std::vector<cv::Mat> out;
    cv::Mat frame;
    while (out.size() < 40 && capture.read(frame)) out.push_back(frame.clone());
    return out;
  }();
  return frames;
}

// Args: model input size, OpenCV threads.
void BM_YoloInference(benchmark::State& state) {
  const int previous_threads = cv::getNumThreads();
  cv::setNumThreads(static_cast<int>(state.range(1)));
  auto detector = yolo(static_cast<int>(state.range(0)));
  const cv::Mat image =
      cv::imread((kShared / "data/ultralytics_yolov5/data/images/bus.jpg").string());
  for (auto _ : state) benchmark::DoNotOptimize(detector->detect(image, 0.0));
  cv::setNumThreads(previous_threads);
}
BENCHMARK(BM_YoloInference)
    ->ArgNames({"input", "threads"})
    ->Args({640, 1})
    ->Args({640, 2})
    ->Args({320, 1})
    ->Args({320, 2})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

void BM_Propagation(benchmark::State& state) {
  const auto& frames = videoFrames();
  const Detections people = yolo(640)->detect(frames[0], 0.0);
  std::size_t i = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(propagateDetections(frames[i - 1], frames[i], people, {}));
    i = i + 1 < frames.size() ? i + 1 : 1;
  }
  state.counters["boxes"] = static_cast<double>(people.size());
}
BENCHMARK(BM_Propagation)->Unit(benchmark::kMillisecond);

// One iteration = one camera frame pushed and its result taken (the tracker's wait).
// Arg: stride.
void BM_WorkerLatency(benchmark::State& state) {
  const auto& frames = videoFrames();
  WorkerParams params;
  params.stride = static_cast<int>(state.range(0));
  DetectionWorker worker(yolo(320), params);
  std::int64_t index = 0;
  double detect_ms = 0.0;
  double propagate_ms = 0.0;
  int propagated = 0;
  for (auto _ : state) {
    const auto& frame = frames[static_cast<std::size_t>(index) % frames.size()];
    worker.push(index, 0.1 * static_cast<double>(index), frame);
    const FrameDetections result = worker.take(index);
    (result.propagated ? propagate_ms : detect_ms) += result.compute_ms;
    propagated += result.propagated ? 1 : 0;
    ++index;
  }
  const int detected = static_cast<int>(index) - propagated;
  state.counters["detect_ms"] = detected > 0 ? detect_ms / detected : 0.0;
  state.counters["propagate_ms"] = propagated > 0 ? propagate_ms / propagated : 0.0;
}
BENCHMARK(BM_WorkerLatency)
    ->ArgName("stride")
    ->Arg(1)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();  // the caller mostly waits: its CPU time says nothing

}  // namespace
