#pragma once
// Timestamp association of an estimated trajectory with ground truth, as TUM's
// associate.py (and evo's sync): every estimate pose is paired with the nearest
// ground-truth stamp within max_dt, one-to-one, closest pairs first.
#include <cstddef>
#include <vector>

#include "lumaslam/core/pose.h"

namespace lumaslam::eval {

struct AssociatedTrajectories {
  Trajectory estimate;                        // matched estimate poses, in time order
  Trajectory ground_truth;                    // the ground-truth pose matched to each, same order
  std::vector<std::size_t> estimate_indices;  // index of each match in the input estimate
  std::vector<std::size_t> ground_truth_indices;  // index of each match in the input GT
  // Ground-truth poses inside the estimate's time span, widened on both sides by max_dt but
  // by at most the ground truth's median interval (a huge max_dt must not widen it to all).
  std::size_t ground_truth_in_span = 0;
  std::size_t matched_in_span = 0;  // matches whose ground-truth pose is inside that span

  std::size_t size() const { return estimate.size(); }
  // matched_in_span / ground_truth_in_span: the share of ground-truth frames the estimate
  // covers; 0 when the two trajectories do not overlap in time.
  double coverage() const;
};

// Inputs need not be sorted. Throws Error when either trajectory is empty, max_dt is
// negative or not finite, or no pair lies within max_dt (the message gives both time spans).
AssociatedTrajectories associate(const Trajectory& estimate, const Trajectory& ground_truth,
                                 double max_dt);

}  // namespace lumaslam::eval
