#pragma once
// Trajectory errors as `lumaslam eval` computes them (evo's definitions, docs/evaluation.md),
// for callers of the public API: associate by timestamp, align, ATE and RPE.
#include <cstddef>

#include "lumaslam/camera_pose.h"
#include "lumaslam/export.h"

namespace lumaslam {

enum class Alignment { None, SE3, Sim3 };  // Sim3 for monocular estimates

struct ErrorOptions {
  Alignment alignment = Alignment::SE3;
  double max_dt = 0.02;    // seconds: association window
  double rpe_delta = 1.0;  // frames between the poses of an RPE pair
};

struct ErrorSummary {
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0;
  std::size_t count = 0;
};

struct TrajectoryErrors {
  ErrorSummary ate;               // metres
  ErrorSummary rpe_translation;   // metres
  ErrorSummary rpe_rotation_deg;  // degrees
  std::size_t matched_poses = 0;
  double coverage = 0.0;  // matched / ground-truth poses within the estimate's time span
  double scale = 1.0;     // the alignment's scale (1 unless Sim3)
};

// Throws std::runtime_error when the trajectories share no timestamps or a pose is not rigid.
LUMASLAM_API TrajectoryErrors evaluate(const CameraTrajectory& estimate,
                                       const CameraTrajectory& ground_truth,
                                       const ErrorOptions& options = {});

}  // namespace lumaslam
