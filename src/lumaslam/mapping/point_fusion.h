#pragma once
// Projects map points into a keyframe and merges each with the feature it lands on
// (ORB-SLAM's ORBmatcher::Fuse): an unmatched feature gains the observation, a feature that
// already has a point keeps whichever of the two is observed more often.
#include <memory>
#include <vector>

#include "lumaslam/map/map.h"

namespace lumaslam::mapping {

int fusePointsInto(map::Map& map, const std::shared_ptr<map::KeyFrame>& target,
                   const std::vector<std::shared_ptr<map::MapPoint>>& points, float radius = 3.0F);

}  // namespace lumaslam::mapping
