#include "lumaslam/track/dynamic_point_memory.h"

#include <algorithm>

#include "lumaslam/core/error.h"

namespace lumaslam::track {

DynamicPointMemory::DynamicPointMemory(const DynamicMemoryParams& params) : params_(params) {
  if (params_.frames < 0) fail("DynamicPointMemory: frames must be >= 0, found {}", params_.frames);
  if (params_.strikes < 1)
    fail("DynamicPointMemory: strikes must be >= 1, found {}", params_.strikes);
}

void DynamicPointMemory::beginFrame(std::size_t frame_index, const std::vector<cv::Rect2f>& boxes) {
  if (!boxes.empty() && params_.frames > 0) recent_.push_back({frame_index, boxes});
  const auto window = static_cast<std::size_t>(params_.frames);
  while (!recent_.empty() && recent_.front().frame_index + window <= frame_index) {
    recent_.pop_front();
  }
  if (recent_.empty()) strikes_.clear();  // no person around any more
  current_boxes_ = boxes.size();
  recent_max_boxes_ = 0;
  for (const auto& frame : recent_)
    recent_max_boxes_ = std::max(recent_max_boxes_, frame.boxes.size());
}

bool DynamicPointMemory::nearRecentBox(const cv::Point2f& pixel) const {
  const float m = params_.margin_px;
  for (const auto& frame : recent_) {
    for (const auto& box : frame.boxes) {
      if (pixel.x >= box.x - m && pixel.x <= box.x + box.width + m && pixel.y >= box.y - m &&
          pixel.y <= box.y + box.height + m) {
        return true;
      }
    }
  }
  return false;
}

bool DynamicPointMemory::recordOutcome(map::Id point, const cv::Point2f& pixel, bool outlier) {
  if (isDynamic(point)) return false;
  if (!outlier) {
    strikes_.erase(point);
    return false;
  }
  if (!nearRecentBox(pixel)) return false;
  if (++strikes_[point] < params_.strikes) return false;
  strikes_.erase(point);
  dynamic_.insert(point);
  return true;
}

}  // namespace lumaslam::track
