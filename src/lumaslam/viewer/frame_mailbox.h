#pragma once
// The hand-over from the tracking thread to the viewer's thread: one slot, the newest frame
// wins (a frame the viewer has not taken yet is dropped), so the tracking thread never waits
// for the browser. Camera centres are kept for every frame, dropped or not.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <vector>

#include "lumaslam/viewer/frame_view.h"

namespace lumaslam::viewer {

struct TakenFrames {
  FrameView newest;
  std::vector<Eigen::Vector3d> camera_centres;  // of every frame put since the last take
};

class FrameMailbox {
 public:
  void put(FrameView view);
  // Waits up to `timeout` for a frame.
  std::optional<TakenFrames> take(std::chrono::milliseconds timeout);
  std::size_t putCount() const;
  std::size_t droppedCount() const;  // put, then replaced before the viewer took it

 private:
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::optional<FrameView> slot_;
  std::vector<Eigen::Vector3d> centres_;
  std::size_t put_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace lumaslam::viewer
