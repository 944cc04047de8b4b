#pragma once
// Class-free evidence that a feature or a map point moves (issue 16; docs/dynamic.md "Motion
// evidence"): after a frame's pose, every matched map point's reprojection residual (with the
// right coordinate for stereo / RGB-D, i.e. a 3D test) and, for every feature, the residual of
// its match in the previous frame (that feature's 3D point reprojected, or its epipolar
// distance without depth) are turned into log-odds that the thing is static, accumulated over
// frames and slowly forgotten. Points that turn dynamic leave pose estimation; moving features
// (and the features of a grid cell where motion evidence dominates) make no map point.
// Tracking thread only.
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/map/ids.h"
#include "lumaslam/track/frame.h"
#include "lumaslam/track/frame_camera.h"
#include "lumaslam/track/origin_segmentation.h"
#include "lumaslam/track/rigid_consensus.h"

namespace lumaslam::track {

struct MotionEvidenceParams {
  bool enabled = true;
  // Window for a feature's match in the previous frame, around where it would be if static.
  float flow_radius_px = 24.0F;
  int flow_max_distance = 50;    // Hamming (ORB-SLAM's TH_LOW): matching without a position prior
  float flow_ratio = 0.8F;       // best / second best
  double forget = 0.95;          // per frame, log-odds decay toward 0 (unknown)
  double max_log_odds = 4.0;     // how sure "static" can get (a standing person may walk off)
  double dynamic_below = -2.0;   // log-odds under which a point or feature counts as moving
  double confirmed_above = 0.9;  // log-odds over which a point is trusted for the first pose
  // Moving regions: grid cells of region_cell_px where at least region_min_moving features have
  // log-odds <= region_moving_below, and no fewer than those with >= region_resting_above.
  int region_cell_px = 40;
  int region_min_moving = 2;
  double region_moving_below = -1.0;
  double region_resting_above = 0.25;
  // A frame where more of its matched map points fail than this gives no "moving" evidence:
  // its pose is in doubt, and a wrong pose would make the static scene look as if it moved.
  double max_outlier_fraction = 0.5;
  // Pose-free test of matched points with depth (rigid_consensus.h; RGB-D and stereo only),
  // Dynamic.rigidConsensus. Off by default until measured on real data (docs/dynamic.md).
  bool rigidity = false;
  RigidConsensusParams rigid;
  // A map's first frames against its origin keyframe (origin_segmentation.h; RGB-D, stereo).
  OriginSegmentationParams origin;
};

// Log-likelihood ratio static : moving of one residual, from its chi-square value over the
// 95 % threshold of its degrees of freedom: +0.5 for a perfect fit, 0 at the threshold,
// falling linearly to -1.5 at 4x the threshold.
double staticEvidence(double chi2, double chi2_threshold);

struct MotionVerdict {
  std::vector<std::size_t> dynamic_points;  // features whose map point is dynamic now
  std::size_t moving_features = 0;          // features now flagged moving (incl. the above)
  bool evidence_used = false;               // false: pose in doubt, only static evidence taken
};

class MotionEvidence {
 public:
  explicit MotionEvidence(const MotionEvidenceParams& params = {});

  // After `current`'s pose: updates the beliefs of its matched map points and of its features
  // (carried over from their match in `previous`, which has a pose), and flags the moving
  // features in current.features->moving. Map points that are dynamic now are returned; the
  // caller leaves them out of the pose. `rigidity` (the frame's rigid consensus, may be empty)
  // overrules the residuals of the points it found broken: they count as moving.
  MotionVerdict update(Frame& current, const Frame& previous, const FrameCamera& camera,
                       const feature::ScaleLevels& pyramid, const RigidVerdict& rigidity = {});

  bool enabled() const { return params_.enabled; }
  // Static beyond doubt: log-odds at least params.confirmed_above at frame `frame`.
  bool isConfirmedStatic(map::Id point, std::size_t frame) const;
  // Whether the match at feature i of `frame` (any point, also a visual-odometry one) passes
  // the chi-square test against the frame's current pose.
  bool fitsPose(const Frame& frame, std::size_t i, const FrameCamera& camera,
                const feature::ScaleLevels& pyramid) const;
  // Not sticky: a point is dynamic while its evidence says so (a person who stops and stands
  // becomes static again; a static point that failed a few matches in a row comes back).
  bool isDynamic(map::Id point, std::size_t frame) const;
  std::size_t dynamicCount(std::size_t frame) const;  // points dynamic at `frame`

 private:
  struct Belief {
    float log_odds = 0.0F;
    std::size_t frame = 0;  // frame of the last update (decay is applied lazily)
  };
  float decayed(const Belief& belief, std::size_t frame) const;
  void updatePointBeliefs(Frame& current, const FrameCamera& camera,
                          const feature::ScaleLevels& pyramid, bool moving_evidence,
                          const RigidVerdict& rigidity, MotionVerdict& verdict);
  void updateFeatureBeliefs(Frame& current, const Frame& previous, const FrameCamera& camera,
                            const feature::ScaleLevels& pyramid, bool moving_evidence);
  bool poseTrusted(const Frame& current) const;
  std::vector<bool> movingRegions(const Frame& current, const FrameCamera& camera) const;

  static constexpr std::size_t kDecaySteps = 128;  // forget^128 < 1 % for forget <= 0.96

  MotionEvidenceParams params_;
  std::array<float, kDecaySteps> decay_{};
  std::unordered_map<map::Id, Belief> points_;
};

}  // namespace lumaslam::track
