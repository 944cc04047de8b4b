#pragma once
// One call from two trajectories to the full report (associate, align, ATE, RPE), plus its
// JSON form and a human-readable table. Used by `lumaslam eval` and `lumaslam run`.
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "lumaslam/core/pose.h"
#include "lumaslam/eval/alignment.h"
#include "lumaslam/eval/ate.h"
#include "lumaslam/eval/rpe.h"

namespace lumaslam::eval {

struct EvaluationOptions {
  AlignMode align = AlignMode::SE3;
  double max_dt = 0.02;  // seconds, association window
  RpeSettings rpe;
};

struct EvaluationReport {
  EvaluationOptions options;
  std::size_t estimate_poses = 0;
  std::size_t ground_truth_poses = 0;
  std::size_t matched_poses = 0;
  std::size_t ground_truth_in_span = 0;
  double coverage = 0.0;  // matched / ground_truth_in_span
  Alignment alignment;
  AbsoluteTrajectoryError ate;
  RelativePoseError rpe;
  Trajectory aligned_estimate;  // the matched estimate poses after alignment
  Trajectory ground_truth;      // the matched ground-truth poses, same order
};

// Throws Error (from association, alignment or RPE) with a message saying what is missing.
EvaluationReport evaluate(const Trajectory& estimate, const Trajectory& ground_truth,
                          const EvaluationOptions& options);

// {"ate": {rmse, mean, median, std, min, max, count, coverage},
//  "rpe": {"trans": {...}, "rot": {...}, delta, unit, all_pairs},
//  "alignment": {mode, scale, rotation (3 rows), translation},
//  "association": {max_dt, estimate_poses, ground_truth_poses, matched, ground_truth_in_span}}
// Units: metres for ATE and RPE translation, degrees for RPE rotation.
nlohmann::json toJson(const EvaluationReport& report);

std::string formatTable(const EvaluationReport& report);

}  // namespace lumaslam::eval
