#pragma once
// Second line of defence against moving people when the detector misses them (fast rotation,
// motion blur, occlusion): a short memory of the recent dynamic-object boxes, and of the map
// points that failed the chi-square test of pose optimisation near them. A point that fails
// repeatedly near a recent box is declared dynamic: the tracker stops using it for pose
// estimation and culls it from the map. Tracking thread only.
#include <cstddef>
#include <deque>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/map/ids.h"

namespace lumaslam::track {

struct DynamicMemoryParams {
  int frames = 15;       // boxes stay "recent" for this many frames (0.5 s at 30 Hz)
  float margin_px = 16;  // "near" a box: within this many pixels of it
  int strikes = 2;       // consecutive chi-square failures near a box before a point is dynamic
};

class DynamicPointMemory {
 public:
  explicit DynamicPointMemory(const DynamicMemoryParams& params = {});

  // Starts frame `frame_index` with its dynamic-object boxes (empty: none seen, or a missed
  // detection). Boxes older than params.frames frames are forgotten, and with them the
  // strikes of points that never became dynamic.
  void beginFrame(std::size_t frame_index, const std::vector<cv::Rect2f>& boxes);

  // Whether `pixel` lies within params.margin_px of a box of the remembered frames.
  bool nearRecentBox(const cv::Point2f& pixel) const;

  // The current frame has fewer boxes than a remembered one: someone is likely in view but
  // missed by the detector. The tracker then makes no new map point near a recent box.
  bool likelyMissedDetection() const { return current_boxes_ < recent_max_boxes_; }

  // The pose-optimisation verdict on map point `point` observed at `pixel`. A failure near a
  // recent box is a strike, a success clears its strikes. Returns true when this verdict makes
  // the point dynamic.
  bool recordOutcome(map::Id point, const cv::Point2f& pixel, bool outlier);

  bool isDynamic(map::Id point) const { return dynamic_.count(point) != 0; }
  std::size_t dynamicCount() const { return dynamic_.size(); }

 private:
  struct RecentBoxes {
    std::size_t frame_index = 0;
    std::vector<cv::Rect2f> boxes;
  };

  DynamicMemoryParams params_;
  std::deque<RecentBoxes> recent_;
  std::size_t current_boxes_ = 0;
  std::size_t recent_max_boxes_ = 0;
  std::unordered_map<map::Id, int> strikes_;
  std::unordered_set<map::Id> dynamic_;
};

}  // namespace lumaslam::track
