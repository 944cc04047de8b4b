#include "lumaslam/eval/rpe.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "lumaslam/core/error.h"

namespace lumaslam::eval {

namespace {

PosePairs pairsByIndex(std::size_t size, std::size_t delta, bool all_pairs) {
  PosePairs pairs;
  const std::size_t step = all_pairs ? 1 : delta;
  for (std::size_t i = 0; i + delta < size; i += step) pairs.emplace_back(i, i + delta);
  return pairs;
}

// evo's filter_pairs_by_path.
PosePairs pairsByPath(const Trajectory& ground_truth, double delta, bool all_pairs) {
  std::vector<double> travelled(ground_truth.size(), 0.0);
  for (std::size_t i = 1; i < ground_truth.size(); ++i) {
    travelled[i] =
        travelled[i - 1] +
        (ground_truth[i].T_w_c.translation() - ground_truth[i - 1].T_w_c.translation()).norm();
  }
  PosePairs pairs;
  if (all_pairs) {
    // For every start, the later pose whose travelled distance is closest to delta, kept
    // within evo's default relative tolerance (--delta_tol 0.1).
    const double tolerance = 0.1 * delta;
    for (std::size_t i = 0; i + 1 < ground_truth.size(); ++i) {
      const auto first = travelled.begin() + static_cast<std::ptrdiff_t>(i) + 1;
      auto best = std::lower_bound(first, travelled.end(), travelled[i] + delta);
      if (best == travelled.end() ||
          (best != first && travelled[i] + delta - *(best - 1) < *best - travelled[i] - delta)) {
        --best;
      }
      if (std::abs(*best - travelled[i] - delta) > tolerance) continue;
      pairs.emplace_back(i, static_cast<std::size_t>(best - travelled.begin()));
    }
    return pairs;
  }
  std::vector<std::size_t> ids;
  double since_last = 0.0;
  for (std::size_t i = 0; i < ground_truth.size(); ++i) {
    if (i > 0) since_last += travelled[i] - travelled[i - 1];
    if (since_last >= delta) {
      ids.push_back(i);
      since_last = 0.0;
    }
  }
  for (std::size_t k = 0; k + 1 < ids.size(); ++k) pairs.emplace_back(ids[k], ids[k + 1]);
  return pairs;
}

}  // namespace

DeltaUnit parseDeltaUnit(std::string_view name) {
  if (name == "frames" || name == "f") return DeltaUnit::Frames;
  if (name == "m" || name == "meters" || name == "metres") return DeltaUnit::Meters;
  fail("RPE delta unit '{}' is not one of frames, m", name);
}

std::string toString(DeltaUnit unit) {
  return unit == DeltaUnit::Frames ? "frames" : "m";
}

PosePairs rpePairs(const Trajectory& ground_truth, const RpeSettings& settings) {
  if (!std::isfinite(settings.delta) || settings.delta <= 0.0) {
    fail("RPE: delta must be > 0, got {}", settings.delta);
  }
  if (settings.unit == DeltaUnit::Meters) {
    return pairsByPath(ground_truth, settings.delta, settings.all_pairs);
  }
  if (settings.delta != std::round(settings.delta)) {
    fail("RPE: a delta in frames must be a whole number, got {}", settings.delta);
  }
  return pairsByIndex(ground_truth.size(), static_cast<std::size_t>(settings.delta),
                      settings.all_pairs);
}

RelativePoseError computeRpe(const Trajectory& aligned_estimate, const Trajectory& ground_truth,
                             const RpeSettings& settings) {
  if (aligned_estimate.size() != ground_truth.size()) {
    fail("RPE: {} estimate poses but {} ground-truth poses (associate them first)",
         aligned_estimate.size(), ground_truth.size());
  }
  RelativePoseError rpe;
  rpe.pairs = rpePairs(ground_truth, settings);
  if (rpe.pairs.empty()) {
    fail("RPE: no pose pairs {} {} apart among {} associated poses", settings.delta,
         toString(settings.unit), ground_truth.size());
  }
  for (const auto& [i, j] : rpe.pairs) {
    const SE3 Q_ij = ground_truth[i].T_w_c.inverse() * ground_truth[j].T_w_c;
    const SE3 P_ij = aligned_estimate[i].T_w_c.inverse() * aligned_estimate[j].T_w_c;
    const SE3 E = Q_ij.inverse() * P_ij;
    rpe.translation_errors.push_back(E.translation().norm());
    const double angle = Eigen::AngleAxisd(Eigen::Matrix3d(E.linear())).angle();
    rpe.rotation_errors_deg.push_back(angle * 180.0 / std::numbers::pi);
  }
  rpe.translation = computeStats(rpe.translation_errors);
  rpe.rotation = computeStats(rpe.rotation_errors_deg);
  return rpe;
}

}  // namespace lumaslam::eval
