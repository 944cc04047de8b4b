#pragma once
// What the viewer's HTTP routes serve: the newest frame (its pictures drawn and encoded when a
// page asks for them, once per frame: with no page open they cost nothing), the frame's
// numbers, the map snapshot and the trajectory, with a version that grows on every change
// (server-sent events wait on it). Written by the viewer's thread, read by the HTTP threads.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "lumaslam/viewer/frame_drawing.h"
#include "lumaslam/viewer/frame_view.h"

namespace lumaslam::viewer {

struct ShownFrame {
  std::shared_ptr<const FrameView> view;
  nlohmann::json info;  // frame number, state, counts, timing (frame_info.h)
};

class PublishedState {
 public:
  void setFrame(ShownFrame frame, const std::vector<Eigen::Vector3d>& new_centres);
  void setMap(std::string map_json);
  void setPaused(bool paused);
  void setStatus(const std::string& status);  // "running", "complete", "partial", ...
  void setCounts(std::size_t frames_shown, std::size_t frames_dropped);

  std::uint64_t version() const;
  // Blocks until version() > `seen` or the timeout passes; returns the version.
  std::uint64_t waitForChange(std::uint64_t seen, std::chrono::milliseconds timeout) const;
  // The newest frame's picture as JPEG; nothing before the first frame.
  std::optional<std::vector<unsigned char>> picture(FramePicture which) const;
  std::string statusJson() const;
  std::string mapJson() const;  // {"map": snapshot or null, "trajectory": [x,y,z,...]}
  // The last kHistory frames' numbers (frame, state, inliers, timing), oldest first: a page
  // opened mid-run draws its plots from them.
  std::string historyJson() const;
  static constexpr std::size_t kHistory = 300;

 private:
  void bump();  // with mutex_ held

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::uint64_t version_ = 0;
  std::uint64_t frame_version_ = 0;
  std::uint64_t map_version_ = 0;
  std::optional<ShownFrame> frame_;
  struct EncodedPicture {
    std::uint64_t frame_version = 0;
    std::vector<unsigned char> jpeg;
  };
  mutable std::map<FramePicture, EncodedPicture> encoded_;  // newest frame's, when asked for
  std::string map_json_ = "null";
  std::vector<float> trajectory_;
  std::deque<nlohmann::json> history_;
  bool paused_ = false;
  std::string status_ = "starting";
  std::size_t frames_shown_ = 0;
  std::size_t frames_dropped_ = 0;
};

}  // namespace lumaslam::viewer
