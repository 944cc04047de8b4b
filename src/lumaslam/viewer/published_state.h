#pragma once
// What the viewer's HTTP routes serve: the newest encoded pictures, the frame's numbers, the
// map snapshot and the trajectory, with a version that grows on every change (server-sent
// events wait on it). Written by the encoder thread, read by the HTTP threads.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace lumaslam::viewer {

struct EncodedFrame {
  std::vector<unsigned char> raw_jpeg;
  std::vector<unsigned char> enhanced_jpeg;
  nlohmann::json info;  // frame number, state, counts, timing (see Viewer's status)
};

class PublishedState {
 public:
  void setFrame(EncodedFrame frame, const std::vector<Eigen::Vector3d>& new_centres);
  void setMap(std::string map_json);
  void setPaused(bool paused);
  void setStatus(const std::string& status);  // "running", "complete", "partial", ...
  void setCounts(std::size_t frames_shown, std::size_t frames_dropped);

  std::uint64_t version() const;
  // Blocks until version() > `seen` or the timeout passes; returns the version.
  std::uint64_t waitForChange(std::uint64_t seen, std::chrono::milliseconds timeout) const;
  // Nothing before the first frame.
  std::optional<std::vector<unsigned char>> picture(bool enhanced) const;
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
  std::optional<EncodedFrame> frame_;
  std::string map_json_ = "null";
  std::vector<float> trajectory_;
  std::deque<nlohmann::json> history_;
  bool paused_ = false;
  std::string status_ = "starting";
  std::size_t frames_shown_ = 0;
  std::size_t frames_dropped_ = 0;
};

}  // namespace lumaslam::viewer
