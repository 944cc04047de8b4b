#include "lumaslam/detect/detection_worker.h"

#include <chrono>

#include <spdlog/spdlog.h>

#include "lumaslam/core/error.h"
#include "lumaslam/detect/box_propagation.h"

namespace lumaslam::detect {

WorkerParams WorkerParams::from(const DetectorParams& params) {
  return {params.stride, params.queue_capacity, params.propagation};
}

DetectionWorker::DetectionWorker(std::unique_ptr<Detector> detector, WorkerParams params)
    : detector_(std::move(detector)), params_(params) {
  if (!detector_) fail("DetectionWorker: no detector");
  if (params_.stride < 1) fail("DetectionWorker: stride must be >= 1, found {}", params_.stride);
  if (params_.queue_capacity < 1) {
    fail("DetectionWorker: queue capacity must be >= 1, found {}", params_.queue_capacity);
  }
  if (params_.threaded) thread_ = std::thread([this] { run(); });
}

DetectionWorker::~DetectionWorker() {
  stop();
}

void DetectionWorker::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    queue_.clear();
  }
  work_available_.notify_all();
  space_available_.notify_all();
  result_ready_.notify_all();
  if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
}

void DetectionWorker::push(std::int64_t frame_index, double timestamp, const cv::Mat& image) {
  // Copy outside the lock: callers often reuse their frame buffer (cv::VideoCapture does).
  Job job{frame_index, timestamp, image.clone(), 0};
  std::unique_lock lock(mutex_);
  if (last_pushed_ && frame_index <= *last_pushed_) {
    fail("DetectionWorker: frame index {} pushed after {}; indices must increase", frame_index,
         *last_pushed_);
  }
  const auto has_room = [&] { return static_cast<int>(queue_.size()) < params_.queue_capacity; };
  if (params_.threaded) {
    space_available_.wait(lock, [&] { return stopping_ || has_room(); });
  } else {
    while (!stopping_ && !has_room()) processNextJob(lock);
  }
  if (stopping_) fail("DetectionWorker: frame {} pushed after stop()", frame_index);
  job.sequence = pushed_count_++;
  last_pushed_ = frame_index;
  pending_.insert(frame_index);
  queue_.push_back(std::move(job));
  lock.unlock();
  work_available_.notify_one();
}

FrameDetections DetectionWorker::take(std::int64_t frame_index) {
  std::unique_lock lock(mutex_);
  if (pending_.count(frame_index) == 0) {
    fail("DetectionWorker: frame {} was never pushed or was already taken", frame_index);
  }
  const auto ready = [&] { return stopping_ || results_.count(frame_index) != 0; };
  if (!params_.threaded) {
    while (!ready() && !queue_.empty()) processNextJob(lock);
  }
  result_ready_.wait(lock, ready);
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

void DetectionWorker::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    work_available_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (stopping_) return;
    processNextJob(lock);
  }
}

void DetectionWorker::processNextJob(std::unique_lock<std::mutex>& lock) {
  Job job = std::move(queue_.front());
  queue_.pop_front();
  lock.unlock();
  space_available_.notify_one();
  Outcome outcome = process(job);
  lock.lock();
  if (stopping_) return;
  results_.emplace(job.frame_index, std::move(outcome));
  result_ready_.notify_all();
}

DetectionWorker::Outcome DetectionWorker::process(const Job& job) {
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
