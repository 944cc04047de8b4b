// DetectionWorker: results belong to their frame, stride + optical-flow propagation on a real
// video of walking people (vtest.avi), errors, and clean shutdown while a job runs.
#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/detect/detection_worker.h"
#include "lumaslam/detect/yolo_detector.h"
#include "test_detection_iou.h"
#include "test_paths.h"

namespace lumaslam::detect {
namespace {

std::vector<cv::Mat> videoFrames(int count) {
  const auto path = test::dataDir() / "opencv_samples/vtest/vtest.avi";
  cv::VideoCapture capture(path.string());
  EXPECT_TRUE(capture.isOpened()) << path;
  std::vector<cv::Mat> frames;
  cv::Mat frame;
  while (static_cast<int>(frames.size()) < count && capture.read(frame))
    frames.push_back(frame.clone());
  EXPECT_EQ(static_cast<int>(frames.size()), count);
  return frames;
}

std::unique_ptr<YoloDetector> yolo(const std::string& model_file) {
  DetectorParams params;
  params.model = test::modelsDir() / model_file;
  return std::make_unique<YoloDetector>(params);
}

WorkerParams workerParams(int stride, int queue_capacity) {
  WorkerParams params;
  params.stride = stride;
  params.queue_capacity = queue_capacity;
  return params;
}

Detections stampBox(double timestamp) {
  return {{0, "person", 1.0f, cv::Rect2f(static_cast<float>(timestamp), 0, 10, 10)}};
}

// Answers with one box whose x is the frame's timestamp; optionally slow, optionally failing.
class StampDetector : public Detector {
 public:
  explicit StampDetector(std::chrono::milliseconds delay = {}, double failing_timestamp = -1.0)
      : delay_(delay), failing_timestamp_(failing_timestamp) {}
  Detections detect(const cv::Mat&, double timestamp) override {
    std::this_thread::sleep_for(delay_);  // inference time, not synchronisation
    if (timestamp == failing_timestamp_) fail("stamp detector: failing at {}", timestamp);
    return stampBox(timestamp);
  }
  std::string describe() const override { return "stamp"; }

 private:
  std::chrono::milliseconds delay_;
  double failing_timestamp_;
};

// Counts its detections, and each waits until the test opens the gate: an inference that lasts
// exactly as long as the test needs.
class GatedDetector : public Detector {
 public:
  GatedDetector(std::atomic<int>& started, std::shared_future<void> gate)
      : started_(started), gate_(std::move(gate)) {}
  Detections detect(const cv::Mat&, double timestamp) override {
    ++started_;
    gate_.wait();
    return stampBox(timestamp);
  }
  std::string describe() const override { return "gated"; }

 private:
  std::atomic<int>& started_;
  std::shared_future<void> gate_;
};

TEST(DetectionWorker, EachResultIsThatFramesOwnDetection) {
  const auto frames = videoFrames(40);
  auto reference = yolo("yolov5n-320.onnx");
  DetectionWorker worker(yolo("yolov5n-320.onnx"), workerParams(1, 3));

  // Like a tracker that overlaps detection with its own work: push frame i, then take the
  // frame pushed two frames earlier, so several frames are in flight at once.
  constexpr int kLag = 2;
  int with_people = 0;
  const auto check = [&](int i) {
    const FrameDetections result = worker.take(100 + i);
    EXPECT_EQ(result.frame_index, 100 + i);
    EXPECT_DOUBLE_EQ(result.timestamp, 0.1 * i);
    EXPECT_FALSE(result.propagated);
    if (i % 8 == 0) {  // same boxes as detecting that very frame directly
      const auto direct = reference->detect(frames[i], 0.0);
      ASSERT_EQ(result.detections.size(), direct.size()) << "frame " << i;
      for (std::size_t k = 0; k < direct.size(); ++k)
        EXPECT_EQ(result.detections[k].box, direct[k].box);
    }
    with_people += result.detections.empty() ? 0 : 1;
  };
  for (int i = 0; i < 40; ++i) {
    worker.push(100 + i, 0.1 * i, frames[i]);
    if (i >= kLag) check(i - kLag);
  }
  for (int i = 40 - kLag; i < 40; ++i) check(i);
  EXPECT_GE(with_people, 30);  // people walk through the whole clip
}

TEST(DetectionWorker, StridePropagatesBoxesAlongTheMotion) {
  constexpr int kFrames = 25;
  constexpr int kStride = 5;
  const auto frames = videoFrames(kFrames);
  auto direct_detector = yolo("yolov5n-320.onnx");
  DetectionWorker worker(yolo("yolov5n-320.onnx"), workerParams(kStride, 4));
  for (int i = 0; i < kFrames; ++i) worker.push(i, 0.1 * i, frames[i]);

  Detections last_detected;
  double propagated_iou = 0.0;
  double stale_iou = 0.0;
  int compared = 0;
  for (int i = 0; i < kFrames; ++i) {
    const auto result = worker.take(i);
    ASSERT_EQ(result.frame_index, i);
    EXPECT_EQ(result.propagated, i % kStride != 0) << "frame " << i;
    if (!result.propagated) {
      last_detected = result.detections;
      continue;
    }
    if (i % kStride < 3) continue;  // compare where the people had time to move
    const auto direct = direct_detector->detect(frames[i], 0.0);
    propagated_iou += test::meanBestIou(direct, result.detections);
    stale_iou += test::meanBestIou(direct, last_detected);
    ++compared;
  }
  ASSERT_GT(compared, 0);
  propagated_iou /= compared;
  stale_iou /= compared;
  RecordProperty("propagated_iou", std::to_string(propagated_iou));
  RecordProperty("stale_iou", std::to_string(stale_iou));
  std::printf("mean IoU with direct detections: propagated %.3f, not propagated %.3f\n",
              propagated_iou, stale_iou);
  EXPECT_GT(propagated_iou, stale_iou + 0.1);  // measured: 0.66 vs 0.41
}

TEST(DetectionWorker, TakeWaitsForItsFrameAndRejectsUnknownFrames) {
  DetectionWorker worker(std::make_unique<StampDetector>(std::chrono::milliseconds(20)), {});
  EXPECT_THROW(worker.take(0), Error);  // never pushed
  worker.push(0, 0.0, cv::Mat());
  worker.push(1, 1.0, cv::Mat());
  worker.push(2, 2.0, cv::Mat());
  // Taken out of order: each still gets its own box.
  EXPECT_EQ(worker.take(2).detections.at(0).box.x, 2.0f);
  EXPECT_EQ(worker.take(0).detections.at(0).box.x, 0.0f);
  EXPECT_THROW(worker.take(0), Error);           // already taken
  EXPECT_THROW(worker.push(1, 5.0, {}), Error);  // index must increase
  EXPECT_EQ(worker.take(1).detections.at(0).box.x, 1.0f);
}

TEST(DetectionWorker, DetectorErrorReachesThatFrameOnly) {
  DetectionWorker worker(std::make_unique<StampDetector>(std::chrono::milliseconds(0), 1.0), {});
  for (int i = 0; i < 3; ++i) worker.push(i, i, cv::Mat());
  EXPECT_EQ(worker.take(0).detections.size(), 1u);
  // The failing frame returns no result.
  const std::string message = test::errorOf([&] { worker.take(1); });
  EXPECT_NE(message.find("failing at 1"), std::string::npos) << message;
  EXPECT_EQ(worker.take(2).detections.at(0).box.x, 2.0f);
}

// stop() while frame 0 is mid-inference and frames 1 and 2 are queued, under any scheduling
// (no sleep): the inference ends only once stop() has dropped the queue. Two threads push frame
// 3 onto the full queue; one gets in and waits for room, the other is refused (the index must
// increase), so it knows the first waits, and calls stop(). The waiting push is refused once
// stop() has dropped the queue (both under the queue's lock); only then is the gate opened.
TEST(DetectionWorker, StopsCleanlyWhileAJobRunsAndWakesWaiters) {
  std::atomic<int> started{0};
  std::promise<void> gate;
  std::once_flag gate_opened;
  const auto open_gate = [&] { std::call_once(gate_opened, [&] { gate.set_value(); }); };
  auto worker = std::make_unique<DetectionWorker>(
      std::make_unique<GatedDetector>(started, gate.get_future().share()), workerParams(1, 2));
  worker->push(0, 0.0, cv::Mat());
  worker->push(1, 1.0, cv::Mat());
  worker->push(2, 2.0, cv::Mat());  // returns once frame 0 is taken: 1 and 2 fill the queue
  std::atomic<bool> waiter_saw_error{false};
  std::thread waiter([&] {
    try {
      worker->take(1);
    } catch (const Error&) {
      waiter_saw_error = true;
    }
  });
  std::atomic<int> refused_after_stop{0};
  const auto push_or_stop = [&] {
    try {
      worker->push(3, 3.0, cv::Mat());
      ADD_FAILURE() << "frame 3 was queued: its push neither waited for room nor was refused";
    } catch (const Error& e) {
      const std::string message = e.what();
      if (message.find("indices must increase") != std::string::npos) {
        worker->stop();  // frame 0 is mid-inference, frames 1 and 2 still queued
        return;
      }
      EXPECT_NE(message.find("frame 3 pushed after stop()"), std::string::npos) << message;
      ++refused_after_stop;
    }
    open_gate();
  };
  std::thread first(push_or_stop);
  std::thread second(push_or_stop);
  first.join();
  second.join();
  waiter.join();
  EXPECT_TRUE(waiter_saw_error);
  EXPECT_EQ(refused_after_stop, 1);
  EXPECT_EQ(started, 1);  // the queued frames were dropped, not detected
  EXPECT_THROW(worker->push(4, 4.0, cv::Mat()), Error);
  worker.reset();  // destructor after stop(): no second join, no crash

  // Destroying without stop() while frames are in flight is safe too.
  const auto frames = videoFrames(6);
  auto busy = std::make_unique<DetectionWorker>(yolo("yolov5n-320.onnx"), workerParams(2, 4));
  for (int i = 0; i < 6; ++i) busy->push(i, 0.1 * i, frames[i]);
  EXPECT_EQ(busy->take(0).frame_index, 0);
  busy.reset();
}

// Records the thread and the timestamp of every detection; answers like StampDetector.
class RecordingDetector : public Detector {
 public:
  struct Call {
    std::thread::id thread;
    double timestamp = 0.0;
  };
  explicit RecordingDetector(std::vector<Call>& calls) : calls_(calls) {}
  Detections detect(const cv::Mat&, double timestamp) override {
    calls_.push_back({std::this_thread::get_id(), timestamp});
    return {{0, "person", 1.0f, cv::Rect2f(static_cast<float>(timestamp), 0, 10, 10)}};
  }
  std::string describe() const override { return "recording"; }

 private:
  std::vector<Call>& calls_;
};

// Sequential mode (System.sequential): no worker thread. A frame is detected in the caller's
// thread when it is taken, or when a push finds the queue full (the oldest frame first), in
// push order either way.
TEST(DetectionWorker, WithoutAThreadDetectsInTheCallersThreadInPushOrder) {
  std::vector<RecordingDetector::Call> calls;
  WorkerParams params = workerParams(1, 2);
  params.threaded = false;
  DetectionWorker worker(std::make_unique<RecordingDetector>(calls), params);
  const cv::Mat image(48, 64, CV_8UC3, cv::Scalar(0));
  worker.push(10, 1.0, image);
  worker.push(11, 2.0, image);
  EXPECT_TRUE(calls.empty()) << "nothing is detected before it is needed";
  worker.push(12, 3.0, image);  // the queue holds 2: frame 10 is detected to make room
  ASSERT_EQ(calls.size(), 1U);
  EXPECT_EQ(worker.take(11).detections.at(0).box.x, 2.0f);  // detects 11
  EXPECT_EQ(worker.take(10).detections.at(0).box.x, 1.0f);  // already detected
  EXPECT_EQ(worker.take(12).detections.at(0).box.x, 3.0f);
  ASSERT_EQ(calls.size(), 3U);
  for (std::size_t i = 0; i < calls.size(); ++i) {
    EXPECT_EQ(calls[i].thread, std::this_thread::get_id()) << "detection " << i;
    EXPECT_EQ(calls[i].timestamp, 1.0 + static_cast<double>(i));
  }
  EXPECT_THROW(worker.take(12), Error);  // taken once, as with a thread
  worker.stop();
  EXPECT_THROW(worker.push(13, 4.0, image), Error);
}

}  // namespace
}  // namespace lumaslam::detect
