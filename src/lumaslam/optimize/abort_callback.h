#pragma once
// Stops a Ceres solve when another thread raises a flag (the mapper's "abort BA" flag, set
// when a new keyframe arrives). Ceres calls it after every iteration; terminating "successfully"
// keeps the best parameters reached so far.
#include <atomic>

#include <ceres/iteration_callback.h>

namespace lumaslam::optimize {

class AbortCallback final : public ceres::IterationCallback {
 public:
  explicit AbortCallback(const std::atomic<bool>* abort) : abort_(abort) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& /*summary*/) override {
    if (abort_ && abort_->load(std::memory_order_relaxed)) {
      aborted_ = true;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }
  bool aborted() const { return aborted_; }

 private:
  const std::atomic<bool>* abort_;
  bool aborted_ = false;
};

}  // namespace lumaslam::optimize
