#pragma once
// Even spatial distribution of keypoints (ORB-SLAM's octree/quadtree): split the area into
// quadrants until there are about `target` non-empty nodes, then keep the strongest keypoint
// (highest response) of each node.
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::feature {

// Keypoints outside `area` are clamped into the border nodes. Returns at most `target`
// keypoints (if more nodes than `target` result, the weakest node winners are dropped).
std::vector<cv::KeyPoint> distributeByQuadtree(const std::vector<cv::KeyPoint>& candidates,
                                               const cv::Rect2f& area, int target);

}  // namespace lumaslam::feature
