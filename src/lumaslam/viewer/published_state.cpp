#include "lumaslam/viewer/published_state.h"

namespace lumaslam::viewer {

void PublishedState::setFrame(ShownFrame frame, const std::vector<Eigen::Vector3d>& new_centres) {
  const std::lock_guard lock(mutex_);
  nlohmann::json entry;
  for (const char* key : {"frame", "state", "inliers", "timing"}) {
    if (frame.info.contains(key)) entry[key] = frame.info[key];
  }
  history_.push_back(std::move(entry));
  if (history_.size() > kHistory) history_.pop_front();
  frame_ = std::move(frame);
  for (const auto& centre : new_centres) {
    for (int i = 0; i < 3; ++i) trajectory_.push_back(static_cast<float>(centre(i)));
  }
  ++frame_version_;
  bump();
}

void PublishedState::setMap(std::string map_json) {
  const std::lock_guard lock(mutex_);
  map_json_ = std::move(map_json);
  ++map_version_;
  bump();
}

void PublishedState::setPaused(bool paused) {
  const std::lock_guard lock(mutex_);
  paused_ = paused;
  bump();
}

void PublishedState::setStatus(const std::string& status) {
  const std::lock_guard lock(mutex_);
  status_ = status;
  bump();
}

void PublishedState::setCounts(std::size_t frames_shown, std::size_t frames_dropped) {
  const std::lock_guard lock(mutex_);
  frames_shown_ = frames_shown;
  frames_dropped_ = frames_dropped;
}

void PublishedState::bump() {
  ++version_;
  changed_.notify_all();
}

std::uint64_t PublishedState::version() const {
  const std::lock_guard lock(mutex_);
  return version_;
}

std::uint64_t PublishedState::waitForChange(std::uint64_t seen,
                                            std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [&] { return version_ > seen; });
  return version_;
}

std::optional<std::vector<unsigned char>> PublishedState::picture(FramePicture which) const {
  std::shared_ptr<const FrameView> view;
  std::uint64_t version = 0;
  {
    const std::lock_guard lock(mutex_);
    if (!frame_) return std::nullopt;
    const auto cached = encoded_.find(which);
    if (cached != encoded_.end() && cached->second.frame_version == frame_version_) {
      return cached->second.jpeg;
    }
    view = frame_->view;
    version = frame_version_;
  }
  // Drawn and encoded outside the lock: new frames are not held up by a page.
  auto jpeg = encodeJpeg(drawFramePicture(*view, which));
  const std::lock_guard lock(mutex_);
  if (version == frame_version_) encoded_[which] = {version, jpeg};
  return jpeg;
}

std::string PublishedState::statusJson() const {
  const std::lock_guard lock(mutex_);
  nlohmann::json status = frame_ ? frame_->info : nlohmann::json::object();
  status["version"] = version_;
  status["frame_version"] = frame_version_;
  status["map_version"] = map_version_;
  status["paused"] = paused_;
  status["status"] = status_;
  status["frames_shown"] = frames_shown_;
  status["frames_dropped"] = frames_dropped_;
  return status.dump();
}

std::string PublishedState::mapJson() const {
  const std::lock_guard lock(mutex_);
  return "{\"map\":" + map_json_ + ",\"trajectory\":" + nlohmann::json(trajectory_).dump() + "}";
}

std::string PublishedState::historyJson() const {
  const std::lock_guard lock(mutex_);
  nlohmann::json history = nlohmann::json::array();
  for (const auto& entry : history_) history.push_back(entry);
  return history.dump();
}

}  // namespace lumaslam::viewer
