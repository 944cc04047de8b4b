#include "lumaslam/viewer/run_control.h"

namespace lumaslam::viewer {

void RunControl::pause() {
  {
    const std::lock_guard lock(mutex_);
    paused_ = true;
  }
  changed();
}

void RunControl::resume() {
  {
    const std::lock_guard lock(mutex_);
    paused_ = false;
    steps_ = 0;
  }
  wake_.notify_all();
  changed();
}

void RunControl::step() {
  {
    const std::lock_guard lock(mutex_);
    paused_ = true;
    ++steps_;
  }
  wake_.notify_all();
  changed();
}

bool RunControl::paused() const {
  const std::lock_guard lock(mutex_);
  return paused_;
}

void RunControl::waitWhilePaused(const std::function<bool()>& stop_requested) {
  std::unique_lock lock(mutex_);
  while (paused_ && steps_ == 0) {
    if (stop_requested && stop_requested()) return;
    wake_.wait_for(lock, std::chrono::milliseconds(50));
  }
  if (steps_ > 0) --steps_;
}

void RunControl::onChange(std::function<void()> callback) {
  const std::lock_guard lock(mutex_);
  on_change_ = std::move(callback);
}

void RunControl::changed() {
  std::function<void()> callback;
  {
    const std::lock_guard lock(mutex_);
    callback = on_change_;
  }
  if (callback) callback();
}

}  // namespace lumaslam::viewer
