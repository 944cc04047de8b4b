#include "lumaslam/evaluate.h"

#include "lumaslam/camera_pose_conversion.h"
#include "lumaslam/core/error.h"
#include "lumaslam/eval/evaluation.h"

namespace lumaslam {

namespace {

eval::AlignMode toAlignMode(Alignment alignment) {
  switch (alignment) {
    case Alignment::None:
      return eval::AlignMode::None;
    case Alignment::SE3:
      return eval::AlignMode::SE3;
    case Alignment::Sim3:
      return eval::AlignMode::Sim3;
  }
  return eval::AlignMode::SE3;
}

ErrorSummary toSummary(const eval::ErrorStats& stats) {
  return {stats.rmse, stats.mean, stats.median, stats.std, stats.min, stats.max, stats.count};
}

Trajectory checkedTrajectory(const CameraTrajectory& trajectory, const char* what) {
  try {
    return toTrajectory(trajectory);
  } catch (const Error& e) {
    fail("evaluate: {}: {}", what, e.what());
  }
}

}  // namespace

TrajectoryErrors evaluate(const CameraTrajectory& estimate, const CameraTrajectory& ground_truth,
                          const ErrorOptions& options) {
  eval::EvaluationOptions eval_options;
  eval_options.align = toAlignMode(options.alignment);
  eval_options.max_dt = options.max_dt;
  eval_options.rpe.delta = options.rpe_delta;
  const eval::EvaluationReport report =
      eval::evaluate(checkedTrajectory(estimate, "estimate"),
                     checkedTrajectory(ground_truth, "ground truth"), eval_options);
  TrajectoryErrors errors;
  errors.ate = toSummary(report.ate.stats);
  errors.rpe_translation = toSummary(report.rpe.translation);
  errors.rpe_rotation_deg = toSummary(report.rpe.rotation);
  errors.matched_poses = report.matched_poses;
  errors.coverage = report.coverage;
  errors.scale = report.alignment.scale;
  return errors;
}

}  // namespace lumaslam
