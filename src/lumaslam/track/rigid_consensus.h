#pragma once
// Pose-free motion evidence for matched map points with a depth reading (RGB-D, stereo;
// issue 16): the distance between two static points is the same in the map and in the current
// frame whatever the camera did, while the distance between a static point and a point on a
// moving thing changes by as much as the thing moved since it was mapped. The static scene is
// taken to be the largest set whose pairwise distances hold. Unlike residuals against a pose,
// this cannot be fooled by a pose that follows the mover (a sideways move with a compensating
// turn keeps a far wall in place while a close crate pulls the pose along; docs/dynamic.md).
// Tracking thread only.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/track/frame.h"

namespace lumaslam::track {

struct RigidConsensusParams {
  // Depth reading's standard deviation: depth_noise * z^2 metres (Kinect v1: 1.4e-3 z^2 by
  // Khoshelham & Elberink 2012; more here for colour/depth misregistration at edges).
  double depth_noise = 0.0025;
  double tolerance_sigmas = 3.0;  // a pair holds while its distance changed by less than this
  double min_tolerance_m = 0.01;
  int anchors = 32;     // points whose distances to all others are tested
  int min_points = 30;  // matched points with depth needed for a verdict
  // Anchors that vote: those that agree with the best-supported one and have at least this
  // fraction of its support; a point is static if it holds with at least min_agreement of them.
  double voter_support = 0.8;
  double min_agreement = 0.5;
};

enum class Rigidity : std::int8_t { Untested = 0, Holds = 1, Broken = -1 };

struct RigidVerdict {
  std::vector<Rigidity> per_feature;  // empty when there was too little to test
  int holds = 0;
  int broken = 0;
  bool informative() const { return broken > 0 && holds > 0; }
  bool brokenAt(std::size_t i) const {
    return i < per_feature.size() && per_feature[i] == Rigidity::Broken;
  }
  bool holdsAt(std::size_t i) const {
    return i < per_feature.size() && per_feature[i] == Rigidity::Holds;
  }
};

// The frame's matched map points (with at least one observation) whose features have depth.
RigidVerdict rigidConsensus(const Frame& frame, const CameraIntrinsics& k,
                            const RigidConsensusParams& params = {});

}  // namespace lumaslam::track
