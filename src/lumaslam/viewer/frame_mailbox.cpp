#include "lumaslam/viewer/frame_mailbox.h"

namespace lumaslam::viewer {

void FrameMailbox::put(FrameView view) {
  {
    const std::lock_guard lock(mutex_);
    if (slot_) ++dropped_;
    if (view.camera_centre) centres_.push_back(*view.camera_centre);
    slot_ = std::move(view);
    ++put_;
  }
  arrived_.notify_one();
}

std::optional<TakenFrames> FrameMailbox::take(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  if (!arrived_.wait_for(lock, timeout, [&] { return slot_.has_value(); })) return std::nullopt;
  TakenFrames taken{std::move(*slot_), std::move(centres_)};
  slot_.reset();
  centres_.clear();
  return taken;
}

std::size_t FrameMailbox::putCount() const {
  const std::lock_guard lock(mutex_);
  return put_;
}

std::size_t FrameMailbox::droppedCount() const {
  const std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace lumaslam::viewer
