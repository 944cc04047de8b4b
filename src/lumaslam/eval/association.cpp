#include "lumaslam/eval/association.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "lumaslam/core/error.h"

namespace lumaslam::eval {

namespace {

std::vector<std::size_t> timeOrder(const Trajectory& trajectory) {
  std::vector<std::size_t> order(trajectory.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return trajectory[a].timestamp < trajectory[b].timestamp;
  });
  return order;
}

struct Candidate {
  double dt;
  std::size_t estimate_index;
  std::size_t ground_truth_index;
};

double medianInterval(const std::vector<double>& sorted_stamps) {
  if (sorted_stamps.size() < 2) return 0.0;
  std::vector<double> intervals(sorted_stamps.size() - 1);
  for (std::size_t k = 0; k + 1 < sorted_stamps.size(); ++k) {
    intervals[k] = sorted_stamps[k + 1] - sorted_stamps[k];
  }
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  return intervals[intervals.size() / 2];
}

}  // namespace

double AssociatedTrajectories::coverage() const {
  if (ground_truth_in_span == 0) return 0.0;
  return static_cast<double>(matched_in_span) / static_cast<double>(ground_truth_in_span);
}

AssociatedTrajectories associate(const Trajectory& estimate, const Trajectory& ground_truth,
                                 double max_dt) {
  if (estimate.empty()) fail("association: the estimated trajectory has no poses");
  if (ground_truth.empty()) fail("association: the ground-truth trajectory has no poses");
  if (!std::isfinite(max_dt) || max_dt < 0.0) {
    fail("association: max_dt must be a finite number >= 0 s, got {}", max_dt);
  }

  const std::vector<std::size_t> gt_order = timeOrder(ground_truth);
  std::vector<double> gt_stamps(gt_order.size());
  for (std::size_t k = 0; k < gt_order.size(); ++k) {
    gt_stamps[k] = ground_truth[gt_order[k]].timestamp;
  }

  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const double stamp = estimate[i].timestamp;
    auto it = std::lower_bound(gt_stamps.begin(), gt_stamps.end(), stamp - max_dt);
    for (; it != gt_stamps.end() && *it <= stamp + max_dt; ++it) {
      const auto k = static_cast<std::size_t>(it - gt_stamps.begin());
      candidates.push_back({std::abs(*it - stamp), i, gt_order[k]});
    }
  }
  // Greedy one-to-one matching, closest pairs first (TUM associate.py).
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.dt, a.estimate_index, a.ground_truth_index) <
           std::tie(b.dt, b.estimate_index, b.ground_truth_index);
  });
  std::vector<bool> estimate_used(estimate.size(), false);
  std::vector<bool> ground_truth_used(ground_truth.size(), false);
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  for (const Candidate& c : candidates) {
    if (estimate_used[c.estimate_index] || ground_truth_used[c.ground_truth_index]) continue;
    estimate_used[c.estimate_index] = true;
    ground_truth_used[c.ground_truth_index] = true;
    matches.emplace_back(c.estimate_index, c.ground_truth_index);
  }

  const auto [est_min, est_max] = std::minmax_element(
      estimate.begin(), estimate.end(),
      [](const StampedPose& a, const StampedPose& b) { return a.timestamp < b.timestamp; });
  if (matches.empty()) {
    fail(
        "association: no estimate pose is within {} s of a ground-truth pose (estimate spans "
        "{:.6f}..{:.6f} s, ground truth {:.6f}..{:.6f} s)",
        max_dt, est_min->timestamp, est_max->timestamp, gt_stamps.front(), gt_stamps.back());
  }
  std::sort(matches.begin(), matches.end(), [&](const auto& a, const auto& b) {
    return estimate[a.first].timestamp < estimate[b.first].timestamp;
  });

  AssociatedTrajectories result;
  for (const auto& [i, j] : matches) {
    result.estimate.push_back(estimate[i]);
    result.ground_truth.push_back(ground_truth[j]);
    result.estimate_indices.push_back(i);
    result.ground_truth_indices.push_back(j);
  }
  // The span is widened by max_dt for stamp offsets, but by no more than one ground-truth
  // interval: a large max_dt must not count ground truth from before or after the estimate.
  const double widen = std::min(max_dt, medianInterval(gt_stamps));
  const double span_first = est_min->timestamp - widen;
  const double span_last = est_max->timestamp + widen;
  const auto span_begin = std::lower_bound(gt_stamps.begin(), gt_stamps.end(), span_first);
  const auto span_end = std::upper_bound(gt_stamps.begin(), gt_stamps.end(), span_last);
  result.ground_truth_in_span = static_cast<std::size_t>(span_end - span_begin);
  result.matched_in_span = static_cast<std::size_t>(std::count_if(
      result.ground_truth.begin(), result.ground_truth.end(), [&](const StampedPose& pose) {
        return pose.timestamp >= span_first && pose.timestamp <= span_last;
      }));
  return result;
}

}  // namespace lumaslam::eval
