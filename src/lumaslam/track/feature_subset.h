#pragma once
// Dropping features from a frame after extraction: detection runs while ORB features are
// extracted (paper section 3.2), so the features on people are removed afterwards, before
// matching and pose estimation (no map point is ever created from them).
#include <vector>

#include "lumaslam/track/frame.h"

namespace lumaslam::track {

// Keeps the features at `kept` (strictly increasing indices) of a frame without matches:
// keypoints, undistorted points, depth, right coordinates and descriptors are subset and the
// feature grid is rebuilt over the same bounds. Throws Error for an index out of range.
void keepFeatures(Frame& frame, const std::vector<int>& kept);

}  // namespace lumaslam::track
