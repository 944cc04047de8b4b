#pragma once
// Runs a Detector on its own thread so the tracker can extract features meanwhile (paper
// section 3.2: the tracker pushes each frame into the detection queue; a detection thread
// answers with the boxes of that frame).
//
// The tracker calls push(i, t, image) for every frame and later take(i), which blocks (on
// a condition variable) until frame i's result is ready and never returns another frame's
// boxes. With stride k > 1 the detector runs on every k-th pushed frame only; the frames in
// between get the previous frame's boxes moved by optical flow (propagateDetections), so
// detection keeps the camera's pace as long as one inference takes less than k frames.
// Frames are processed in push order, so results are the same as running sequentially.
// The frames queue up in a core::Stage (blocking when full). Sequential mode
// (WorkerParams::threaded false, System.sequential) starts no thread: take(i) detects the
// queued frames up to i in the caller's thread, and a push onto a full queue first detects the
// oldest queued frame.
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include "lumaslam/core/stage.h"

#include "lumaslam/detect/detector.h"
#include "lumaslam/detect/detector_params.h"

namespace lumaslam::detect {

struct FrameDetections {
  std::int64_t frame_index = -1;
  double timestamp = 0.0;
  Detections detections;
  bool propagated = false;  // boxes moved from the previous frame, not detected on this one
  double compute_ms = 0.0;  // worker time spent on this frame (inference or propagation)
};

struct WorkerParams {
  int stride = 1;
  int queue_capacity = 4;
  PropagationParams propagation;
  bool threaded = true;  // false: no worker thread, frames are detected in the caller's thread

  static WorkerParams from(const DetectorParams& params);
};

class DetectionWorker {
 public:
  // Starts the worker thread (when threaded). Throws Error for a null detector or
  // stride/capacity < 1.
  DetectionWorker(std::unique_ptr<Detector> detector, WorkerParams params);
  // Stops and joins; safe while a frame is being detected (that inference finishes first).
  ~DetectionWorker();

  DetectionWorker(const DetectionWorker&) = delete;
  DetectionWorker& operator=(const DetectionWorker&) = delete;

  // Queues a copy of the frame; blocks while the queue is full (not threaded: detects the
  // oldest queued frame instead). Throws Error when the index does not increase or the worker
  // is stopped.
  void push(std::int64_t frame_index, double timestamp, const cv::Mat& image);

  // Blocks until frame_index's result is ready (not threaded: detects the queued frames up to
  // it first) and hands it over (once). Rethrows the detector's exception for that frame;
  // throws Error for a frame never pushed, already taken, or dropped by stop().
  FrameDetections take(std::int64_t frame_index);

  // Drops queued frames, lets the running inference finish, joins. Idempotent.
  void stop();

 private:
  struct Job {
    std::int64_t frame_index = -1;
    double timestamp = 0.0;
    cv::Mat image;
    std::int64_t sequence = 0;  // push count, decides detect vs propagate
  };
  struct Outcome {
    FrameDetections result;
    std::exception_ptr error;
  };
  struct LastFrame {
    cv::Mat image;
    Detections detections;
  };

  static std::unique_ptr<Detector> nonNull(std::unique_ptr<Detector> detector);
  static WorkerParams validated(WorkerParams params);
  // The stage's process step, in its thread (or the caller's, sequential).
  Outcome process(Job& job);
  // The stage's output: keeps the outcome for take() unless stopped meanwhile.
  void store(Outcome&& outcome);
  bool readyLocked(std::int64_t frame_index) const;

  std::unique_ptr<Detector> detector_;
  const WorkerParams params_;

  mutable std::mutex mutex_;
  std::condition_variable result_ready_;
  std::set<std::int64_t> pending_;           // pushed, not yet taken
  std::map<std::int64_t, Outcome> results_;  // ready, not yet taken
  std::optional<std::int64_t> last_pushed_;
  std::int64_t pushed_count_ = 0;
  bool stopping_ = false;

  std::optional<LastFrame> last_frame_;  // the stage's process step only
  core::Stage<Job, Outcome> stage_;      // last: its thread uses everything above
};

}  // namespace lumaslam::detect
