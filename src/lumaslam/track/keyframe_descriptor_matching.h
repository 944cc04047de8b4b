#pragma once
// Matches of a frame's features to a keyframe's map points by descriptor alone, with no pose
// prior: what ORB-SLAM's TrackReferenceKeyFrame gets from SearchByBoW, done by brute force
// (nearest neighbour, ratio test, cross check, rotation consistency) so that it needs no
// vocabulary. Used when the motion model fails (no velocity yet, fast rotation) and while lost.
#include <memory>
#include <vector>

#include "lumaslam/feature/hamming.h"
#include "lumaslam/map/feature_set.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map_point.h"

namespace lumaslam::track {

struct KeyFrameMatchParams {
  int max_distance = feature::kThLow;
  float ratio = 0.75F;  // ORB-SLAM's TrackReferenceKeyFrame: 0.7 within a BoW node; all
                        // features compete here, so a little looser
};

// Per feature of `frame`: the keyframe's map point it matches, or null.
std::vector<std::shared_ptr<map::MapPoint>> matchKeyFramePoints(const map::KeyFrame& keyframe,
                                                                const map::FeatureSet& frame,
                                                                const KeyFrameMatchParams& params);

}  // namespace lumaslam::track
