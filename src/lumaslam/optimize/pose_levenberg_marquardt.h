#pragma once
// One round of pose-only optimisation without Ceres: Levenberg-Marquardt on the 6x6 normal
// equations, with the model Ceres builds for ceres::HuberLoss on one residual block per
// observation (Triggs' corrector: Hessian sum rho'(s) J^T J, gradient sum rho'(s) J^T r, cost
// sum rho(s)) and Ceres' trust-region rules (radius 1e4, LM diagonal diag(H) clamped to
// [1e-6, 1e32], step accepted above 1e-3 relative decrease, function tolerance 1e-6, parameter
// tolerance 1e-8). Ceres spends ~100 ns of bookkeeping per residual block and evaluation; the
// tracker's problems (300-900 observations, ~2 per frame) spent 90% of the tracking time there.
// Pose update as se3_parameter.h: T' = [Exp(omega) | upsilon] * T.
#include <vector>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/optimize/pose_only.h"

namespace lumaslam::optimize {

struct PoseRoundResult {
  SE3 T_c_w = SE3::Identity();
  int iterations = 0;  // accepted or rejected steps taken
};

// Minimises sum_i rho(invSigma2_i |e_i|^2) over the observations with active[i], starting at
// T_c_w. huberDelta* <= 0 gives plain least squares. Every active point must be in front of
// T_c_w; a trial step that puts one behind the camera is rejected.
PoseRoundResult minimizePoseLevenbergMarquardt(const CameraIntrinsics& camera,
                                               const std::vector<PoseObservation>& observations,
                                               const std::vector<char>& active, const SE3& T_c_w,
                                               double huberDeltaMono, double huberDeltaStereo,
                                               int maxIterations);

}  // namespace lumaslam::optimize
