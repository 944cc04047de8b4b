#pragma once
// What the tracker needs of relocalization, so that track/ does not depend on loop/ (the
// Pipeline plugs in a BoW + PnP relocalizer when it has a vocabulary).
#include <memory>
#include <optional>
#include <vector>

#include "lumaslam/core/pose.h"
#include "lumaslam/map/map_point.h"
#include "lumaslam/track/frame.h"

namespace lumaslam::track {

struct Relocalization {
  SE3 T_c_w = SE3::Identity();
  std::vector<std::shared_ptr<map::MapPoint>> points;  // per feature of the frame, inliers only
  int inliers = 0;
};

class FrameRelocalizer {
 public:
  virtual ~FrameRelocalizer() = default;
  // A pose of `frame` in the current map found with no pose prior, or nullopt. Called by the
  // tracker while lost, with Map::updateMutex() held; must not write to the map.
  virtual std::optional<Relocalization> relocalize(const Frame& frame) const = 0;
};

}  // namespace lumaslam::track
