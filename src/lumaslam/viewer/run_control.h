#pragma once
// Pause / step / resume from the viewer's page: the tracking thread waits here between frames.
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>

namespace lumaslam::viewer {

class RunControl {
 public:
  explicit RunControl(bool start_paused = false) : paused_(start_paused) {}

  void pause();
  void resume();
  void step();  // while paused: let one more frame through
  bool paused() const;
  // The tracking thread, before each frame: returns at once unless paused; while paused,
  // returns for each step() or on resume(), or when stop_requested() turns true (polled).
  void waitWhilePaused(const std::function<bool()>& stop_requested);
  // Called when anything above changes (the viewer republishes its status).
  void onChange(std::function<void()> callback);

 private:
  void changed();

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool paused_ = false;
  int steps_ = 0;
  std::function<void()> on_change_;
};

}  // namespace lumaslam::viewer
