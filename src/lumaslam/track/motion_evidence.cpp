#include "lumaslam/track/motion_evidence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lumaslam/feature/hamming.h"

namespace lumaslam::track {
namespace {

constexpr double kChi2Mono = 5.991;    // 2 dof, 95 %
constexpr double kChi2Stereo = 7.815;  // 3 dof, 95 %
constexpr double kChi2Line = 3.841;    // 1 dof, 95 % (epipolar distance)

int clampedOctave(int octave, const feature::ScaleLevels& pyramid) {
  return std::clamp(octave, 0, pyramid.count() - 1);
}

// A chi-square value and its 95 % threshold for the residual's degrees of freedom.
struct Residual {
  double chi2 = 0.0;
  double threshold = kChi2Mono;
};

// Reprojection chi-square of a world point at feature i of `frame` (its pose set), with the
// right coordinate when the feature has one; `inverse_sigma2` weighs the pixel error.
std::optional<Residual> reprojectionResidual(const Frame& frame, std::size_t i,
                                             const Eigen::Vector3d& X_w, const FrameCamera& camera,
                                             double inverse_sigma2) {
  const Eigen::Vector3d X_c = *frame.T_c_w * X_w;
  if (X_c.z() <= 1e-6) return std::nullopt;
  const Eigen::Vector2d uv = camera.pinhole.project(X_c);
  const auto& measured = frame.features->undistorted[i];
  const double du = uv.x() - measured.x;
  const double dv = uv.y() - measured.y;
  Residual residual;
  residual.chi2 = (du * du + dv * dv) * inverse_sigma2;
  if (camera.bf > 0.0 && frame.features->hasStereo(i)) {
    const double dr = (uv.x() - camera.bf / X_c.z()) - frame.features->u_right[i];
    residual.chi2 += dr * dr * inverse_sigma2;
    residual.threshold = kChi2Stereo;
  }
  return residual;
}

// The viewing ray of feature i on the z = 1 plane.
Eigen::Vector3d ray(const map::FeatureSet& features, std::size_t i, const FrameCamera& camera) {
  const auto& p = features.undistorted[i];
  return camera.pinhole.unproject({p.x, p.y}, 1.0);
}

// Epipolar distance (pixels², weighed) of current feature i from the line of previous feature
// j; nullopt when the camera did not translate (no epipolar geometry).
std::optional<Residual> epipolarResidual(const Frame& current, std::size_t i, const Frame& previous,
                                         std::size_t j, const FrameCamera& camera,
                                         double inverse_sigma2) {
  const SE3 T_c_p = *current.T_c_w * previous.T_c_w->inverse();
  const Eigen::Vector3d t = T_c_p.translation();
  if (t.norm() < 1e-6) return std::nullopt;
  const Eigen::Vector3d x_p = ray(*previous.features, j, camera);
  const Eigen::Vector3d x_c = ray(*current.features, i, camera);
  const Eigen::Vector3d line = t.cross(T_c_p.rotation() * x_p);  // E x_p, E = [t]x R
  const double norm = std::hypot(line.x(), line.y());
  if (norm < 1e-12) return std::nullopt;
  const double distance_px = std::abs(line.dot(x_c)) / norm * camera.pinhole.fx();
  return Residual{distance_px * distance_px * inverse_sigma2, kChi2Line};
}

// Where current feature i would be in the previous frame if it were static: its 3D point
// moved by the relative pose, or (no depth) its ray rotated.
std::optional<cv::Point2f> staticPositionInPrevious(const Frame& current, std::size_t i,
                                                    const SE3& T_p_c, const FrameCamera& camera) {
  const Eigen::Vector3d X_p = current.features->depth[i] > 0
                                  ? T_p_c * current.unprojectCamera(i, camera.intrinsics())
                                  : T_p_c.rotation() * ray(*current.features, i, camera);
  if (X_p.z() <= 1e-6) return std::nullopt;
  const Eigen::Vector2d uv = camera.pinhole.project(X_p);
  return cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
}

// The previous frame's feature that is the same physical point as current feature i, by
// descriptor alone within a window around where it would be if static (a moving point is
// found anywhere in the window); -1 if none is clear.
int flowMatch(const Frame& current, std::size_t i, const Frame& previous, const SE3& T_p_c,
              const FrameCamera& camera, const MotionEvidenceParams& params) {
  const auto& grid = previous.features->grid;
  if (!grid) return -1;
  const auto center = staticPositionInPrevious(current, i, T_p_c, camera);
  if (!center) return -1;
  const int octave = current.features->keypoints[i].octave;
  const auto candidates =
      grid->featuresInArea(*center, params.flow_radius_px, std::max(0, octave - 1), octave + 1);
  const auto* descriptor = current.features->descriptors.ptr<std::uint8_t>(static_cast<int>(i));
  int best = std::numeric_limits<int>::max();
  int second = std::numeric_limits<int>::max();
  int best_index = -1;
  for (const std::size_t j : candidates) {
    const int distance = feature::hammingDistance(
        descriptor, previous.features->descriptors.ptr<std::uint8_t>(static_cast<int>(j)));
    if (distance < best) {
      second = best;
      best = distance;
      best_index = static_cast<int>(j);
    } else if (distance < second) {
      second = distance;
    }
  }
  if (best > params.flow_max_distance) return -1;
  if (second != std::numeric_limits<int>::max() &&
      static_cast<float>(best) > params.flow_ratio * static_cast<float>(second)) {
    return -1;
  }
  return best_index;
}

// Residual of feature i's map point against the frame's pose.
std::optional<Residual> mapPointResidual(const Frame& frame, std::size_t i,
                                         const FrameCamera& camera,
                                         const feature::ScaleLevels& pyramid) {
  const int octave = clampedOctave(frame.features->keypoints[i].octave, pyramid);
  return reprojectionResidual(frame, i, frame.points[i]->position(), camera,
                              pyramid.inverseSigma2(octave));
}

}  // namespace

double staticEvidence(double chi2, double chi2_threshold) {
  const double s = chi2 / chi2_threshold;
  return std::clamp(0.5 * (1.0 - s), -1.5, 0.5);
}

MotionEvidence::MotionEvidence(const MotionEvidenceParams& params) : params_(params) {
  // forget^n for the frames since a belief's last update (pow per lookup cost ~10 % of tracking)
  double factor = 1.0;
  for (std::size_t n = 0; n < kDecaySteps; ++n) {
    decay_[n] = static_cast<float>(factor);
    factor *= params_.forget;
  }
}

bool MotionEvidence::isDynamic(map::Id point, std::size_t frame) const {
  const auto it = points_.find(point);
  return it != points_.end() && decayed(it->second, frame) < params_.dynamic_below;
}

std::size_t MotionEvidence::dynamicCount(std::size_t frame) const {
  return static_cast<std::size_t>(std::count_if(points_.begin(), points_.end(), [&](const auto& p) {
    return decayed(p.second, frame) < params_.dynamic_below;
  }));
}

bool MotionEvidence::isConfirmedStatic(map::Id point, std::size_t frame) const {
  const auto it = points_.find(point);
  return it != points_.end() && decayed(it->second, frame) >= params_.confirmed_above;
}

bool MotionEvidence::fitsPose(const Frame& frame, std::size_t i, const FrameCamera& camera,
                              const feature::ScaleLevels& pyramid) const {
  const auto& point = frame.points[i];
  if (!point || !frame.T_c_w) return false;
  const auto residual = mapPointResidual(frame, i, camera, pyramid);
  return residual && residual->chi2 <= residual->threshold;
}

float MotionEvidence::decayed(const Belief& belief, std::size_t frame) const {
  const std::size_t frames = frame > belief.frame ? frame - belief.frame : 0;
  return frames < kDecaySteps ? belief.log_odds * decay_[frames] : 0.0F;
}

MotionVerdict MotionEvidence::update(Frame& current, const Frame& previous,
                                     const FrameCamera& camera, const feature::ScaleLevels& pyramid,
                                     const RigidVerdict& rigidity) {
  MotionVerdict verdict;
  if (!params_.enabled || !current.T_c_w || current.size() == 0) return verdict;
  verdict.evidence_used = poseTrusted(current);
  current.static_log_odds.assign(current.size(), 0.0F);
  current.features->moving.assign(current.size(), 0);
  updatePointBeliefs(current, camera, pyramid, verdict.evidence_used, rigidity, verdict);
  if (previous.T_c_w && previous.features && previous.features->descriptors.rows > 0) {
    updateFeatureBeliefs(current, previous, camera, pyramid, verdict.evidence_used);
  }
  const auto in_moving_region = movingRegions(current, camera);
  for (std::size_t i = 0; i < current.size(); ++i) {
    const float log_odds = current.static_log_odds[i];
    if (log_odds < params_.dynamic_below || (in_moving_region[i] && log_odds <= 0.0F)) {
      current.features->moving[i] = 1;
      ++verdict.moving_features;
    }
  }
  return verdict;
}

// Moving things are regions: a cell of a coarse grid where features with evidence of motion
// are at least as many as those with evidence of rest (and at least region_min_moving) marks
// every feature in it, so the features of a person that no test reached yet (no map point, no
// match in the previous frame) make no map point either.
std::vector<bool> MotionEvidence::movingRegions(const Frame& current,
                                                const FrameCamera& camera) const {
  const auto size = camera.size();
  const int cell = std::max(8, params_.region_cell_px);
  const int columns = (size.width + cell - 1) / cell;
  const int rows = (size.height + cell - 1) / cell;
  std::vector<int> moving(static_cast<std::size_t>(columns * rows), 0);
  std::vector<int> resting(moving.size(), 0);
  auto cell_of = [&](std::size_t i) {
    const auto& p = current.features->undistorted[i];
    const int c = std::clamp(static_cast<int>(p.x) / cell, 0, columns - 1);
    const int r = std::clamp(static_cast<int>(p.y) / cell, 0, rows - 1);
    return static_cast<std::size_t>(r * columns + c);
  };
  for (std::size_t i = 0; i < current.size(); ++i) {
    const float log_odds = current.static_log_odds[i];
    if (log_odds <= params_.region_moving_below) ++moving[cell_of(i)];
    if (log_odds >= params_.region_resting_above) ++resting[cell_of(i)];
  }
  std::vector<bool> in_region(current.size(), false);
  for (std::size_t i = 0; i < current.size(); ++i) {
    const std::size_t c = cell_of(i);
    in_region[i] = moving[c] >= params_.region_min_moving && moving[c] >= resting[c];
  }
  return in_region;
}

bool MotionEvidence::poseTrusted(const Frame& current) const {
  std::size_t matched = 0;
  std::size_t failed = 0;
  for (std::size_t i = 0; i < current.size(); ++i) {
    const auto& point = current.points[i];
    if (!point || point->observationCount() < 1) continue;
    ++matched;
    if (current.outliers[i]) ++failed;
  }
  // No map point matched (a frame tracked by other means, or a test): nothing contradicts it.
  return static_cast<double>(failed) <= params_.max_outlier_fraction * static_cast<double>(matched);
}

// Map points: the residual against the frame's pose, whether or not pose optimisation kept it.
void MotionEvidence::updatePointBeliefs(Frame& current, const FrameCamera& camera,
                                        const feature::ScaleLevels& pyramid, bool moving_evidence,
                                        const RigidVerdict& rigidity, MotionVerdict& verdict) {
  constexpr double kBroken = -1.5;  // as a residual at 4x its threshold
  for (std::size_t i = 0; i < current.size(); ++i) {
    const auto& point = current.points[i];
    if (!point || point->isBad() || point->observationCount() < 1) continue;
    const auto residual = mapPointResidual(current, i, camera, pyramid);
    if (!residual) continue;
    double evidence = staticEvidence(residual->chi2, residual->threshold);
    if (!moving_evidence) evidence = std::max(evidence, 0.0);
    if (rigidity.brokenAt(i))
      evidence = kBroken;  // pose-free: holds also when the pose is in doubt
    auto& belief = points_[point->id()];
    belief.log_odds = static_cast<float>(std::clamp(decayed(belief, current.index) + evidence,
                                                    -params_.max_log_odds, params_.max_log_odds));
    belief.frame = current.index;
    current.static_log_odds[i] = belief.log_odds;
    if (belief.log_odds < params_.dynamic_below) verdict.dynamic_points.push_back(i);
  }
}

// Features without a map point: their belief follows them from the previous frame (their
// descriptor match there), updated with the residual of that match under the two poses.
void MotionEvidence::updateFeatureBeliefs(Frame& current, const Frame& previous,
                                          const FrameCamera& camera,
                                          const feature::ScaleLevels& pyramid,
                                          bool moving_evidence) {
  const SE3 T_w_p = previous.T_c_w->inverse();
  const SE3 T_p_c = *previous.T_c_w * current.T_c_w->inverse();
  const auto k = camera.intrinsics();
  for (std::size_t i = 0; i < current.size(); ++i) {
    const auto& point = current.points[i];
    if (point && point->observationCount() > 0) continue;  // the map point's belief holds
    const int j_signed = flowMatch(current, i, previous, T_p_c, camera, params_);
    if (j_signed < 0) continue;
    const auto j = static_cast<std::size_t>(j_signed);
    const int octave_i = clampedOctave(current.features->keypoints[i].octave, pyramid);
    const int octave_j = clampedOctave(previous.features->keypoints[j].octave, pyramid);
    const double inverse_sigma2 = 1.0 / (pyramid.sigma2(octave_i) + pyramid.sigma2(octave_j));
    std::optional<Residual> residual;
    if (previous.features->depth[j] > 0) {
      residual = reprojectionResidual(current, i, T_w_p * previous.unprojectCamera(j, k), camera,
                                      inverse_sigma2);
    } else {
      residual = epipolarResidual(current, i, previous, j, camera, inverse_sigma2);
    }
    const float prior = j < previous.static_log_odds.size()
                            ? static_cast<float>(previous.static_log_odds[j] * params_.forget)
                            : 0.0F;
    double evidence = residual ? staticEvidence(residual->chi2, residual->threshold) : 0.0;
    if (!moving_evidence) evidence = std::max(evidence, 0.0);
    current.static_log_odds[i] = static_cast<float>(
        std::clamp(prior + evidence, -params_.max_log_odds, params_.max_log_odds));
  }
}

}  // namespace lumaslam::track
