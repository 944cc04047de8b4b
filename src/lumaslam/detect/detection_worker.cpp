#include "lumaslam/detect/detection_worker.h"

#include <chrono>

#include <spdlog/spdlog.h>

#include "lumaslam/core/error.h"
#include "lumaslam/detect/box_propagation.h"

namespace lumaslam::detect {

WorkerParams WorkerParams::from(const DetectorParams& params) {
  return {params.stride, params.queue_capacity, params.propagation};
}

WorkerParams DetectionWorker::validated(WorkerParams params) {
  if (params.stride < 1) fail("DetectionWorker: stride must be >= 1, found {}", params.stride);
  if (params.queue_capacity < 1) {
    fail("DetectionWorker: queue capacity must be >= 1, found {}", params.queue_capacity);
  }
  return params;
}

std::unique_ptr<Detector> DetectionWorker::nonNull(std::unique_ptr<Detector> detector) {
  if (!detector) fail("DetectionWorker: no detector");
  return detector;
}

DetectionWorker::DetectionWorker(std::unique_ptr<Detector> detector, WorkerParams params)
    : detector_(nonNull(std::move(detector))),
      params_(validated(params)),
      stage_([this](Job& job) { return process(job); },
             [this](Outcome&& outcome) { store(std::move(outcome)); },
             {.threaded = params_.threaded,
              .capacity = static_cast<std::size_t>(params_.queue_capacity),
              .when_full = core::WhenFull::block}) {}

DetectionWorker::~DetectionWorker() {
  stop();
}

void DetectionWorker::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  stage_.stop();
  result_ready_.notify_all();
}

void DetectionWorker::push(std::int64_t frame_index, double timestamp, const cv::Mat& image) {
  // Copy outside the lock: callers often reuse their frame buffer (cv::VideoCapture does).
  Job job{frame_index, timestamp, image.clone(), 0};
  {
    std::lock_guard lock(mutex_);
    if (stopping_) fail("DetectionWorker: frame {} pushed after stop()", frame_index);
    if (last_pushed_ && frame_index <= *last_pushed_) {
      fail("DetectionWorker: frame index {} pushed after {}; indices must increase", frame_index,
           *last_pushed_);
    }
    job.sequence = pushed_count_++;
    last_pushed_ = frame_index;
    pending_.insert(frame_index);
  }
  if (!stage_.push(std::move(job))) {  // stopped while waiting for room
    std::lock_guard lock(mutex_);
    pending_.erase(frame_index);
    fail("DetectionWorker: frame {} pushed after stop()", frame_index);
  }
}

bool DetectionWorker::readyLocked(std::int64_t frame_index) const {
  return stopping_ || results_.count(frame_index) != 0;
}

FrameDetections DetectionWorker::take(std::int64_t frame_index) {
  std::unique_lock lock(mutex_);
  if (pending_.count(frame_index) == 0) {
    fail("DetectionWorker: frame {} was never pushed or was already taken", frame_index);
  }
  if (!params_.threaded) {
    while (!readyLocked(frame_index)) {
      lock.unlock();
      const bool processed = stage_.processOne();
      lock.lock();
      if (!processed) break;
    }
  }
  result_ready_.wait(lock, [&] { return readyLocked(frame_index); });
  const auto it = results_.find(frame_index);
  if (it == results_.end())
    fail("DetectionWorker: stopped before frame {} was detected", frame_index);
  Outcome outcome = std::move(it->second);
  results_.erase(it);
  pending_.erase(frame_index);
  lock.unlock();
  if (outcome.error) std::rethrow_exception(outcome.error);
  return std::move(outcome.result);
}

void DetectionWorker::store(Outcome&& outcome) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_) return;
    results_.emplace(outcome.result.frame_index, std::move(outcome));
  }
  result_ready_.notify_all();
}

DetectionWorker::Outcome DetectionWorker::process(Job& job) {
  Outcome outcome;
  outcome.result.frame_index = job.frame_index;
  outcome.result.timestamp = job.timestamp;
  const auto start = std::chrono::steady_clock::now();
  try {
    const bool detect_now = !last_frame_ || job.sequence % params_.stride == 0;
    if (detect_now) {
      outcome.result.detections = detector_->detect(job.image, job.timestamp);
    } else {
      outcome.result.detections = propagateDetections(last_frame_->image, job.image,
                                                      last_frame_->detections, params_.propagation);
      outcome.result.propagated = true;
    }
    last_frame_ = LastFrame{job.image, outcome.result.detections};
  } catch (...) {
    outcome.error = std::current_exception();
    last_frame_.reset();  // the next frame is detected afresh
  }
  outcome.result.compute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

}  // namespace lumaslam::detect
