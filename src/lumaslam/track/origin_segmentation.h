#pragma once
// The map-start case of issue 16 (docs/dynamic.md "Map start"): a thing that moves from the
// first frame on is in the map before any point is confirmed static, and a close, textured one
// (the crate) pulls the pose along while a compensating turn keeps the far wall in place; the
// pose optimisation prefers that pose even from static-looking points. In a map's first frames
// the frame's matches to the origin keyframe's points (those the motion model or the reference
// keyframe found) are compared, with depth, with where the origin measured them: two rigid
// motions are found by RANSAC over these 3D-3D pairs. A motion that follows the mover also fits
// the far static scene, so the two are told apart by the points only each explains: the
// mover's form a compact region, the static scene's are spread over the image. The static
// motion gives the frame its pose and its trusted points; the other motion's points are broken.
// RGB-D and stereo. Tracking thread only.
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/track/frame.h"
#include "lumaslam/track/rigid_consensus.h"

namespace lumaslam::track {

struct OriginSegmentationParams {
  // Off by default until two behaviour changes it causes are understood (docs/dynamic.md).
  bool enabled = false;
  // Frames after a map's first during which the test runs; it ends earlier, for good, at the
  // first frame with fewer than min_points pairs (the origin is out of view) or the first
  // lost frame (what follows is recovery, not the map's start).
  int window_frames = 150;
  int min_points = 30;  // pairs needed for a verdict
  int min_mover_points = 12;
  double min_static_fraction = 0.5;  // of the pairs, for the static motion to give the pose
  int iterations = 128;              // RANSAC samples per motion
  // A pair fits a motion while its distance is within max(min_tolerance_m, sigmas * sigma);
  // sigma as in rigid_consensus.h (depth noise * z^2, both readings).
  double depth_noise = 0.0025;
  double tolerance_sigmas = 3.0;
  double min_tolerance_m = 0.01;
  // Across the ray: this many pixels (times the feature's pyramid scale) at the point's depth.
  double lateral_tolerance_px = 3.0;
  int cell_px = 40;  // image coverage is counted in cells of this size
};

struct OriginSegmentation {
  int pairs = 0;  // matched points with depth in both the origin and the current frame
  // Holds: on the static motion; Broken: on the other one; Untested: neither, or no pair.
  // Empty unless a static motion or two motions were found.
  RigidVerdict verdict;
  // The static motion, origin camera -> current camera, when it has enough points.
  std::optional<SE3> T_current_origin;
  // Per current feature: its match to an origin point when on the static motion, else null.
  // Empty when there were fewer than min_points pairs.
  std::vector<std::shared_ptr<map::MapPoint>> static_matches;
};

// `image_width/height` bound the coverage grid.
OriginSegmentation segmentAgainstOrigin(const Frame& current, const map::KeyFrame& origin,
                                        const CameraIntrinsics& k, int image_width,
                                        int image_height,
                                        const OriginSegmentationParams& params = {});

}  // namespace lumaslam::track
