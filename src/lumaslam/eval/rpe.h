#pragma once
// Relative pose error as evo's RPE: for a pair (i, j) with ground truth Q and estimate P,
// E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j); translation error |trans(E)|, rotation error the angle
// of rot(E) in degrees.
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lumaslam/core/pose.h"
#include "lumaslam/eval/error_stats.h"

namespace lumaslam::eval {

enum class DeltaUnit {
  Frames,  // j = i + delta among the associated poses
  Meters,  // j is where the ground truth has travelled delta metres further (evo --delta_unit m)
};

// "frames" or "m"; throws Error naming the value otherwise.
DeltaUnit parseDeltaUnit(std::string_view name);
std::string toString(DeltaUnit unit);

struct RpeSettings {
  double delta = 1.0;  // a whole number of frames, or metres
  DeltaUnit unit = DeltaUnit::Frames;
  // evo's default (false) uses consecutive, non-overlapping pairs; true uses every start pose.
  bool all_pairs = false;
};

using PosePairs = std::vector<std::pair<std::size_t, std::size_t>>;

// The (i, j) pairs evo forms on the ground truth; throws Error on a bad delta.
PosePairs rpePairs(const Trajectory& ground_truth, const RpeSettings& settings);

struct RelativePoseError {
  ErrorStats translation;  // metres
  ErrorStats rotation;     // degrees
  PosePairs pairs;
  std::vector<double> translation_errors;
  std::vector<double> rotation_errors_deg;
};

// Inputs are associated pose for pose. Throws Error when sizes differ or no pair exists
// (trajectory shorter than delta).
RelativePoseError computeRpe(const Trajectory& aligned_estimate, const Trajectory& ground_truth,
                             const RpeSettings& settings);

}  // namespace lumaslam::eval
