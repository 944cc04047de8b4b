#include "lumaslam/track/tracker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_set>

#include <spdlog/spdlog.h>

#include "lumaslam/camera/pnp_ransac.h"
#include "lumaslam/feature/projection_matcher.h"
#include "lumaslam/optimize/pose_only.h"
#include "lumaslam/track/keyframe_descriptor_matching.h"

namespace lumaslam::track {

const char* toString(TrackingState state) {
  switch (state) {
    case TrackingState::NotInitialized:
      return "not initialized";
    case TrackingState::Ok:
      return "ok";
    case TrackingState::Lost:
      return "lost";
  }
  return "?";
}

const char* toString(TrackingStep step) {
  switch (step) {
    case TrackingStep::None:
      return "none";
    case TrackingStep::Initialization:
      return "initialization";
    case TrackingStep::MotionModel:
      return "motion model";
    case TrackingStep::ReferenceKeyFrame:
      return "reference keyframe";
    case TrackingStep::LastPose:
      return "last pose";
    case TrackingStep::Relocalization:
      return "relocalization";
  }
  return "?";
}

Tracker::Tracker(std::shared_ptr<map::Map> map, KeyFrameSink& mapper, const FrameCamera& camera,
                 std::shared_ptr<const feature::ScaleLevels> pyramid, const TrackerParams& params)
    : map_(std::move(map)),
      mapper_(mapper),
      camera_(camera),
      pyramid_(std::move(pyramid)),
      params_(params),
      bounds_(camera.pinhole.undistortedBounds()),
      dynamic_memory_(params.dynamic_memory),
      motion_evidence_(params.motion_evidence) {}

TrackingOutcome Tracker::track(Frame frame) {
  std::lock_guard map_lock(map_->updateMutex());
  current_ = std::move(frame);
  rigidity_ = {};
  rigidity_ms_ = 0.0;
  dynamic_memory_.beginFrame(current_.index, current_.dynamic_boxes);
  TrackingOutcome outcome;
  const TrackingState previous = state_;
  const bool ok = estimatePose(outcome);
  const bool map_started = ok && state_ == TrackingState::NotInitialized;
  if (ok) {
    recordTrackedFrame(previous, map_started, outcome);
  } else {
    recordLostFrame(previous);
  }
  if (outcome.new_map) {
    spdlog::info("new map {} started at frame {} (t = {:.3f} s)", active_map_, current_.index,
                 current_.timestamp);
  } else if (ok && previous == TrackingState::Lost) {
    spdlog::info("tracking recovered at frame {} (t = {:.3f} s)", current_.index,
                 current_.timestamp);
  }
  outcome.state = state_;
  outcome.inliers = inliers_;
  keepAsLastFrame(ok);
  return outcome;
}

// The pose of the current frame by the first step that works for the state (docs/tracking.md),
// then the keyframe decision; a new map when lost long enough. Returns whether it was tracked.
bool Tracker::estimatePose(TrackingOutcome& outcome) {
  if (state_ == TrackingState::NotInitialized) {
    if (localization_only_) return false;  // no map to localize in
    const bool ok = initialize();          // monocular: over several frames
    outcome.new_keyframe = ok;
    outcome.new_map = ok && active_map_ != 0;
    if (ok) outcome.step = TrackingStep::Initialization;
    return ok;
  }
  updateLastFrame();
  inliers_ = 0;
  bool ok = false;
  if (state_ == TrackingState::Ok) {
    // ORB-SLAM's order: motion model, then the reference keyframe by descriptors (no pose
    // prior needed: the first frame after initialisation has no velocity, and a fast
    // rotation leaves the predicted pose many pixels off), then the last pose's window.
    if (velocity_ && trackWithMotionModel()) {
      outcome.step = TrackingStep::MotionModel;
    } else if (trackReferenceKeyFrame()) {
      outcome.step = TrackingStep::ReferenceKeyFrame;
    } else if (last_.T_c_w && trackFromPose(*last_.T_c_w, params_.motion_search_radius * 2.0F)) {
      outcome.step = TrackingStep::LastPose;
    }
    ok = outcome.step != TrackingStep::None && trackLocalMap(outcome);
  } else {
    ok = recoverWhileLost(outcome);
    if (!ok && newMapDue()) {
      if (resetDue()) {
        spdlog::warn("frame {}: map {} lost with {} keyframes: reset", current_.index,
                     reference_->mapId(), map_->keyFrameCountOf(reference_->mapId()));
        map_->discardMap(reference_->mapId());
      }
      startNewMap();
      outcome.new_map = outcome.new_keyframe = ok = initialize();
      if (ok) outcome.step = TrackingStep::Initialization;
      return ok;
    }
  }
  state_ = ok ? TrackingState::Ok : TrackingState::Lost;
  if (!ok) outcome.step = TrackingStep::None;
  if (!ok) return false;
  const auto decision = needNewKeyFrame();
  if (decision == KeyFrameDecision::Now) {
    createNewKeyFrame();
    outcome.new_keyframe = true;
  }
  outcome.keyframe_waits_for_mapper = decision == KeyFrameDecision::WhenMapperIdle;
  return true;
}

void Tracker::recordTrackedFrame(TrackingState previous, bool map_started,
                                 TrackingOutcome& outcome) {
  if (last_.T_c_w && previous == TrackingState::Ok) {
    velocity_ = *current_.T_c_w * last_.T_c_w->inverse();
  } else {
    velocity_.reset();
  }
  if (map_started) state_ = TrackingState::Ok;
  lost_since_.reset();
  for (std::size_t i = 0; i < current_.size(); ++i) {
    if (current_.outliers[i]) current_.points[i] = nullptr;
  }
  if (!current_.reference) current_.reference = reference_;
  recorder_.recordTracked(current_.timestamp, *current_.T_c_w, current_.reference);
  // The map's first frame has no local-map inliers yet: the next tracked frame sets them.
  if (map_started) {
    recent_inliers_.clear();
  } else {
    recent_inliers_.push_back(inliers_);
    if (recent_inliers_.size() > static_cast<std::size_t>(params_.inlier_reference_frames)) {
      recent_inliers_.pop_front();
    }
  }
  last_tracked_frame_ = current_.index;
  last_T_l_r_ = *current_.T_c_w * current_.reference->T_w_c();
  outcome.T_w_c = current_.T_c_w->inverse();
  outcome.map = current_.reference->mapId();
}

void Tracker::recordLostFrame(TrackingState previous) {
  if (previous == TrackingState::Ok) {
    spdlog::warn("tracking lost at frame {} (t = {:.3f} s): {} inliers", current_.index,
                 current_.timestamp, inliers_);
  }
  if (!lost_since_ && previous != TrackingState::NotInitialized) {
    lost_since_ = current_.timestamp;
  }
  velocity_.reset();
  depth_map_origin_.reset();  // the map-start test ends at the map's first loss
  recorder_.recordLost(current_.timestamp);
  current_.T_c_w.reset();
}

// While lost, the last pose we had stays the prior for recovery.
void Tracker::keepAsLastFrame(bool tracked) {
  if (!tracked && last_.T_c_w) {
    const auto prior = last_.T_c_w;
    const auto reference = last_.reference;
    last_ = std::move(current_);
    last_.T_c_w = prior;
    last_.reference = reference;
    last_.clearMatches();
  } else {
    last_ = std::move(current_);
  }
}

// Lost: look for the map around the last pose we had (short blackouts), then anywhere in the
// atlas by place recognition (ORB-SLAM's Relocalization), then the last reference keyframe by
// descriptors (violent motion; what recovers without a vocabulary).
bool Tracker::recoverWhileLost(TrackingOutcome& outcome) {
  if (last_.T_c_w && trackFromPose(*last_.T_c_w, params_.lost_search_radius) &&
      trackLocalMap(outcome)) {
    outcome.step = TrackingStep::LastPose;
    return true;
  }
  if (relocalize() && trackLocalMap(outcome)) {
    outcome.step = TrackingStep::Relocalization;
    return outcome.relocalized = true;
  }
  outcome.step = TrackingStep::ReferenceKeyFrame;
  return trackReferenceKeyFrame() && trackLocalMap(outcome);
}

// Lost for new_map_after_s on a frame that could start a map by itself (the dark frames of a
// blackout cannot: the first lit frame still tries relocalization first).
bool Tracker::newMapDue() const {
  if (localization_only_) return false;
  if (params_.new_map_after_s < 0 || !lost_since_) return false;
  if (current_.timestamp - *lost_since_ < params_.new_map_after_s) return false;
  if (camera_.bf <= 0.0) {
    return static_cast<int>(current_.size()) >= params_.monocular.min_features;
  }
  const auto& depth = current_.features->depth;
  return std::count_if(depth.begin(), depth.end(), [](float z) { return z > 0; }) >=
         params_.min_initial_features;
}

bool Tracker::resetDue() const {
  return camera_.bf <= 0.0 && reference_ && reference_->mapId() != map::kDiscardedMap &&
         map_->keyFrameCountOf(reference_->mapId()) <
             static_cast<std::size_t>(params_.monocular_reset_below_keyframes);
}

void Tracker::startInLoadedMap() {
  state_ = TrackingState::Lost;
}

// The old map stays in the atlas (its frames keep their poses); tracking starts over in a new
// one, as from the first frame.
void Tracker::startNewMap() {
  active_map_ = map_->newMapId();
  state_ = TrackingState::NotInitialized;
  reference_.reset();
  last_keyframe_.reset();
  local_keyframes_.clear();
  local_points_.clear();
  temporary_points_.clear();
  velocity_.reset();
  lost_since_.reset();
  if (monocular_initializer_) monocular_initializer_->reset();
}

std::shared_ptr<map::MapPoint> Tracker::newPointFromDepth(
    std::size_t i, const std::shared_ptr<map::KeyFrame>& kf) {
  const Eigen::Vector3d X_c = current_.unprojectCamera(i, camera_.intrinsics());
  const Eigen::Vector3d X_w = current_.T_c_w->inverse() * X_c;
  auto point = std::make_shared<map::MapPoint>(map_->nextMapPointId(), X_w, kf);
  point->addObservation(kf, static_cast<int>(i));
  kf->setMapPoint(i, point);
  point->computeDistinctiveDescriptor();
  point->updateNormalAndDepth();
  map_->addMapPoint(point);
  current_.points[i] = point;
  return point;
}

bool Tracker::initialize() {
  if (camera_.bf <= 0.0) return initializeMonocular();
  const auto& depth = current_.features->depth;
  const auto with_depth = std::count_if(depth.begin(), depth.end(), [](float z) { return z > 0; });
  if (with_depth < params_.min_initial_features) {
    spdlog::debug("frame {}: {} features with depth, need {} to initialise", current_.index,
                  with_depth, params_.min_initial_features);
    return false;
  }
  current_.T_c_w = SE3::Identity();
  auto kf = std::make_shared<map::KeyFrame>(map_->nextKeyFrameId(), current_.index,
                                            current_.timestamp, *current_.T_c_w, current_.features,
                                            pyramid_, camera_.intrinsics());
  kf->setMapId(active_map_);
  map_->addKeyFrame(kf);
  for (std::size_t i = 0; i < current_.size(); ++i) {
    if (depth[i] > 0) newPointFromDepth(i, kf);
  }
  spdlog::info("map {} initialised at frame {} with {} points", active_map_, current_.index,
               with_depth);
  mapper_.insertKeyFrame(kf);
  reference_ = last_keyframe_ = kf;
  last_keyframe_frame_ = current_.index;
  current_.reference = kf;
  local_keyframes_ = {kf};
  depth_map_origin_ = kf;
  inliers_ = static_cast<int>(with_depth);
  return true;
}

void Tracker::updateLastFrame() {
  temporary_points_.clear();
  if (!last_.T_c_w || !last_.reference) return;
  // The reference keyframe may have moved in bundle adjustment since: follow it.
  if (!last_.reference->isBad()) last_.T_c_w = last_T_l_r_ * last_.reference->T_c_w();
  if (state_ != TrackingState::Ok) return;
  // Visual-odometry points: the last frame's close depth measurements that have no map
  // point help the motion-model search (ORB-SLAM's UpdateLastFrame for RGB-D / stereo).
  std::vector<std::pair<float, std::size_t>> by_depth;
  for (std::size_t i = 0; i < last_.size(); ++i) {
    if (last_.features->depth[i] > 0) by_depth.emplace_back(last_.features->depth[i], i);
  }
  std::sort(by_depth.begin(), by_depth.end());
  const SE3 T_w_l = last_.T_c_w->inverse();
  int count = 0;
  for (const auto& [z, i] : by_depth) {
    const auto& point = last_.points[i];
    if (last_.features->isMoving(i)) continue;
    if (dynamic_memory_.likelyMissedDetection() &&
        dynamic_memory_.nearRecentBox(last_.features->keypoints[i].pt)) {
      continue;
    }
    if (!point || point->observationCount() < 1) {
      const Eigen::Vector3d X_w = T_w_l * last_.unprojectCamera(i, camera_.intrinsics());
      auto temporary = std::make_shared<map::MapPoint>(0, X_w, nullptr);
      last_.points[i] = temporary;
      temporary_points_.push_back(std::move(temporary));
    }
    if (++count > 100 && z > camera_.close_depth) break;
  }
}

int Tracker::searchLastFrame(float radius) {
  std::vector<feature::ProjectedPoint> projected;
  std::vector<std::size_t> source;
  const SE3& T_c_w = *current_.T_c_w;
  for (std::size_t i = 0; i < last_.size(); ++i) {
    const auto& point = last_.points[i];
    if (!point || last_.outliers[i]) continue;
    const Eigen::Vector3d X_c = T_c_w * point->position();
    if (X_c.z() <= 0) continue;
    const Eigen::Vector2d projected_uv = camera_.pinhole.project(X_c);
    const cv::Point2f uv(static_cast<float>(projected_uv.x()),
                         static_cast<float>(projected_uv.y()));
    if (!bounds_.contains(uv)) continue;
    const auto& kp = last_.features->keypoints[i];
    feature::ProjectedPoint p;
    p.uv = uv;
    p.predictedLevel = kp.octave;
    p.descriptor = feature::descriptorAt(last_.features->descriptors, static_cast<int>(i));
    p.angle = kp.angle;
    projected.push_back(p);
    source.push_back(i);
  }
  feature::ProjectionSearchOptions options;
  options.radius = radius;
  options.ratio = 1.0F;
  options.checkRotation = true;
  const auto matches = feature::matchByProjection(
      projected, *current_.features->grid, current_.features->descriptors, *pyramid_, options);
  for (const auto& m : matches) {
    current_.points[static_cast<std::size_t>(m.trainIdx)] =
        last_.points[source[static_cast<std::size_t>(m.queryIdx)]];
  }
  return static_cast<int>(matches.size());
}

// `use`: which matches take part (null: all); the others are marked outliers. `rounds` > 0
// overrides the rounds of outlier rejection.
int Tracker::optimizeCurrentPose(const std::vector<bool>* use, int rounds) {
  optimize::PoseOnlyProblem problem;
  problem.camera = camera_.intrinsics();
  problem.T_c_w = *current_.T_c_w;
  std::vector<std::size_t> feature_of;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    auto& point = current_.points[i];
    if (point && leftOutOfPose(*point, i)) point = nullptr;
    if (!point) continue;
    if (use && !(*use)[i]) {
      current_.outliers[i] = true;
      continue;
    }
    optimize::PoseObservation obs;
    obs.X_w = point->position();
    const auto& uv = current_.features->undistorted[i];
    obs.uv = {uv.x, uv.y};
    obs.uRight = current_.features->u_right[i];
    const int octave = std::clamp(current_.features->keypoints[i].octave, 0, pyramid_->count() - 1);
    obs.invSigma2 = pyramid_->inverseSigma2(octave);
    problem.observations.push_back(obs);
    feature_of.push_back(i);
  }
  optimize::PoseOnlyOptions options;
  // Ceres' model of one HuberLoss block per observation, solved without Ceres' per-block
  // overhead (ceres::Solve took 90% of the tracking time).
  options.backend = optimize::PoseBackend::kLevenbergMarquardt;
  if (rounds > 0) options.rounds = rounds;
  const auto result = optimize::optimizePose(problem, options);
  if (!result.success) return 0;
  current_.T_c_w = result.T_c_w;
  for (std::size_t k = 0; k < feature_of.size(); ++k) {
    current_.outliers[feature_of[k]] = result.isOutlier[k];
  }
  return result.numInliers;
}

// Drops outlier matches; returns the number of remaining matches to real map points.
int Tracker::discardOutliers() {
  int in_map = 0;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    if (!current_.points[i]) continue;
    if (current_.outliers[i]) {
      current_.points[i] = nullptr;
      current_.outliers[i] = false;
    } else if (current_.points[i]->observationCount() > 0) {
      ++in_map;
    }
  }
  return in_map;
}

bool Tracker::trackWithMotionModel() {
  current_.T_c_w = *velocity_ * *last_.T_c_w;
  current_.clearMatches();
  int matches = searchLastFrame(params_.motion_search_radius);
  if (matches < 20) {
    current_.clearMatches();
    matches = searchLastFrame(2.0F * params_.motion_search_radius);
  }
  if (matches < 20) {
    spdlog::debug("frame {}: motion model found {} matches", current_.index, matches);
    return false;
  }
  testRigidity();
  const auto use = notRigidlyBroken();
  if (optimizeCurrentPose(rigidity_.informative() ? &use : nullptr) == 0) return false;
  return discardOutliers() >= 10;
}

// Projection search of the reference keyframe's and last frame's points from a pose prior
// with a wide window: the fallback when the motion model fails, and recovery when lost.
int Tracker::searchReferencePoints(float radius) {
  std::vector<feature::ProjectedPoint> projected;
  std::vector<std::shared_ptr<map::MapPoint>> source;
  std::unordered_set<map::Id> seen;
  const SE3& T_c_w = *current_.T_c_w;
  const Eigen::Vector3d center = T_c_w.inverse().translation();
  auto consider = [&](const std::shared_ptr<map::MapPoint>& point) {
    if (!point || point->isBad() || point->observationCount() < 1) return;
    if (!seen.insert(point->id()).second) return;
    const Eigen::Vector3d X_w = point->position();
    const Eigen::Vector3d X_c = T_c_w * X_w;
    if (X_c.z() <= 0) return;
    const Eigen::Vector2d projected_uv = camera_.pinhole.project(X_c);
    const cv::Point2f uv(static_cast<float>(projected_uv.x()),
                         static_cast<float>(projected_uv.y()));
    if (!bounds_.contains(uv)) return;
    feature::ProjectedPoint p;
    p.uv = uv;
    p.predictedLevel = point->predictScale((X_w - center).norm(), *pyramid_);
    p.descriptor = point->descriptor();
    projected.push_back(p);
    source.push_back(point);
  };
  if (reference_) {
    for (const auto& point : reference_->mapPoints()) consider(point);
    for (const auto& kf : reference_->covisibles(5)) {
      for (const auto& point : kf->mapPoints()) consider(point);
    }
  }
  feature::ProjectionSearchOptions options;
  options.radius = radius;
  options.ratio = 0.8F;
  options.levelsBelow = 2;
  options.levelsAbove = 2;
  const auto matches = feature::matchByProjection(
      projected, *current_.features->grid, current_.features->descriptors, *pyramid_, options);
  for (const auto& m : matches) {
    current_.points[static_cast<std::size_t>(m.trainIdx)] =
        source[static_cast<std::size_t>(m.queryIdx)];
  }
  return static_cast<int>(matches.size());
}

bool Tracker::trackFromPose(const SE3& T_c_w_prior, float radius) {
  current_.T_c_w = T_c_w_prior;
  current_.clearMatches();
  const int matches = searchReferencePoints(radius);
  if (matches < 15) {
    spdlog::debug("frame {}: {} matches with the reference keyframe's points", current_.index,
                  matches);
    return false;
  }
  testRigidity();
  const auto use = notRigidlyBroken();
  if (optimizeCurrentPose(rigidity_.informative() ? &use : nullptr) == 0) return false;
  return discardOutliers() >= 10;
}

bool Tracker::trackReferenceKeyFrame() {
  if (!reference_ || reference_->isBad()) return false;
  current_.clearMatches();
  current_.points = matchKeyFramePoints(*reference_, *current_.features, {});
  const auto matches = std::count_if(current_.points.begin(), current_.points.end(),
                                     [](const auto& point) { return point != nullptr; });
  if (matches < 15) {
    spdlog::debug("frame {}: {} descriptor matches with reference keyframe {}", current_.index,
                  matches, reference_->id());
    return false;
  }
  current_.T_c_w = last_.T_c_w ? *last_.T_c_w : reference_->T_c_w();
  poseFromPriorOrPnp();
  return discardOutliers() >= 10;
}

// Pose-only optimisation from the prior; when it keeps under half of the matches (the prior is
// too far off for the robust cost to converge), EPnP + RANSAC on the matches, then again.
void Tracker::poseFromPriorOrPnp() {
  const SE3 prior = *current_.T_c_w;
  const auto matched = current_.points;
  const auto matches = static_cast<int>(std::count_if(
      matched.begin(), matched.end(), [](const auto& point) { return point != nullptr; }));
  if (2 * optimizeCurrentPose() >= matches) return;
  std::vector<Eigen::Vector3d> X_w;
  std::vector<cv::Point2f> uv;
  std::vector<std::size_t> feature_of;
  for (std::size_t i = 0; i < matched.size(); ++i) {
    if (!matched[i]) continue;
    X_w.push_back(matched[i]->position());
    uv.push_back(current_.features->undistorted[i]);
    feature_of.push_back(i);
  }
  const auto found = camera::solvePnpRansac(X_w, uv, camera_.intrinsics(), {});
  if (!found) {
    current_.T_c_w = prior;
    return;
  }
  current_.clearMatches();
  for (std::size_t m = 0; m < feature_of.size(); ++m) {
    if (found->is_inlier[m]) current_.points[feature_of[m]] = matched[feature_of[m]];
  }
  current_.T_c_w = found->T_c_w;
  optimizeCurrentPose();
}

bool Tracker::relocalize() {
  if (!relocalizer_ || current_.size() == 0) return false;
  auto found = relocalizer_->relocalize(current_);
  if (!found) return false;
  current_.T_c_w = found->T_c_w;
  current_.clearMatches();
  current_.points = std::move(found->points);
  current_.points.resize(current_.size());
  spdlog::info("frame {}: relocalized with {} inliers", current_.index, found->inliers);
  return true;
}

void Tracker::updateLocalMap() {
  // Keyframes that see the current matches, weighted by how many they see.
  std::map<map::Id, std::pair<std::shared_ptr<map::KeyFrame>, int>> counts;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const auto& point = current_.points[i];
    if (!point || point->isBad()) continue;
    for (const auto& [kf, index] : point->observations()) {
      auto& entry = counts[kf->id()];
      entry.first = kf;
      ++entry.second;
    }
  }
  if (counts.empty()) return;
  local_keyframes_.clear();
  std::unordered_set<map::Id> in_local;
  std::shared_ptr<map::KeyFrame> best;
  int best_count = 0;
  for (const auto& [id, entry] : counts) {
    if (entry.first->isBad()) continue;
    if (entry.second > best_count) {
      best_count = entry.second;
      best = entry.first;
    }
    local_keyframes_.push_back(entry.first);
    in_local.insert(id);
  }
  const auto max_local = static_cast<std::size_t>(params_.max_local_keyframes);
  const auto first_ring = local_keyframes_;
  for (const auto& kf : first_ring) {
    if (local_keyframes_.size() >= max_local) break;
    auto add = [&](const std::shared_ptr<map::KeyFrame>& other) {
      if (other && !other->isBad() && in_local.insert(other->id()).second) {
        local_keyframes_.push_back(other);
      }
    };
    for (const auto& neighbour : kf->covisibles(10)) add(neighbour);
    for (const auto& child : kf->children()) add(child);
    add(kf->parent());
  }
  if (best) {
    reference_ = best;
    current_.reference = best;
  }
  local_points_.clear();
  std::unordered_set<map::Id> seen;
  for (const auto& kf : local_keyframes_) {
    for (const auto& point : kf->mapPoints()) {
      if (point && !point->isBad() && seen.insert(point->id()).second)
        local_points_.push_back(point);
    }
  }
}

int Tracker::searchLocalPoints() {
  std::unordered_set<map::Id> matched;
  for (const auto& point : current_.points) {
    if (point) {
      point->increaseVisible();
      matched.insert(point->id());
    }
  }
  const SE3& T_c_w = *current_.T_c_w;
  const Eigen::Vector3d center = T_c_w.inverse().translation();
  std::vector<feature::ProjectedPoint> projected;
  std::vector<std::shared_ptr<map::MapPoint>> source;
  for (const auto& point : local_points_) {
    if (matched.count(point->id()) || point->isBad()) continue;
    const Eigen::Vector3d X_w = point->position();
    const Eigen::Vector3d X_c = T_c_w * X_w;
    if (X_c.z() <= 0) continue;
    const Eigen::Vector2d projected_uv = camera_.pinhole.project(X_c);
    const cv::Point2f uv(static_cast<float>(projected_uv.x()),
                         static_cast<float>(projected_uv.y()));
    if (!bounds_.contains(uv)) continue;
    // ORB-SLAM's isInFrustum: inside the scale-invariance range and seen from within 60 deg.
    const Eigen::Vector3d ray = X_w - center;
    const double distance = ray.norm();
    if (distance < point->minDistance() || distance > point->maxDistance()) continue;
    if (ray.dot(point->normal()) < 0.5 * distance) continue;
    point->increaseVisible();
    feature::ProjectedPoint p;
    p.uv = uv;
    p.predictedLevel = point->predictScale(distance, *pyramid_);
    p.descriptor = point->descriptor();
    projected.push_back(p);
    source.push_back(point);
  }
  feature::ProjectionSearchOptions options;
  options.radius = params_.local_map_search_radius;
  options.ratio = 0.8F;
  options.levelsBelow = 1;
  options.levelsAbove = 0;
  const auto matches = feature::matchByProjection(
      projected, *current_.features->grid, current_.features->descriptors, *pyramid_, options);
  int added = 0;
  for (const auto& m : matches) {
    auto& slot = current_.points[static_cast<std::size_t>(m.trainIdx)];
    if (slot) continue;
    slot = source[static_cast<std::size_t>(m.queryIdx)];
    ++added;
  }
  return added;
}

bool Tracker::trackLocalMap(TrackingOutcome& outcome) {
  segmentAgainstMapOrigin();
  updateLocalMap();
  searchLocalPoints();
  testRigidity();
  optimizeConfirmedPointsFirst();
  cullDynamicPoints();
  inliers_ = 0;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const auto& point = current_.points[i];
    if (!point || current_.outliers[i]) continue;
    point->increaseFound();
    if (point->observationCount() > 0) ++inliers_;
  }
  if (!enoughInliers()) return false;
  excludeMovingPoints(outcome);  // only on an accepted pose: a rejected one would blame the scene
  return true;
}

// Robust first pose (issue 16): when enough matched points have been confirmed static by
// earlier frames, they alone give the pose; the other matches (new points, visual-odometry
// points, points on something that may have started to move) join only if they fit it. A
// person mapped at the last keyframe then cannot drag the pose along.
void Tracker::optimizeConfirmedPointsFirst() {
  if (!motion_evidence_.enabled()) {
    optimizeCurrentPose();
    return;
  }
  auto trusted = confirmedStaticMatches();
  int count = static_cast<int>(std::count(trusted.begin(), trusted.end(), true));
  // A map's first frames: what moved with the camera since the origin keyframe, first.
  if (origin_verdict_.holds >= params_.min_confirmed_points) {
    for (std::size_t i = 0; i < current_.size(); ++i) trusted[i] = origin_verdict_.holdsAt(i);
    count = origin_verdict_.holds;
  }
  // A map's first frames have nothing confirmed yet: the rigid consensus stands in for it.
  if (count < params_.min_confirmed_points && rigidity_.informative() &&
      rigidity_.holds >= params_.min_confirmed_points) {
    for (std::size_t i = 0; i < current_.size(); ++i) trusted[i] = rigidity_.holdsAt(i);
    count = rigidity_.holds;
  }
  if (count < params_.min_confirmed_points) {
    const auto use = notRigidlyBroken();
    optimizeCurrentPose(rigidity_.informative() ? &use : nullptr);
    return;
  }
  optimizeCurrentPose(&trusted);
  joinMatchesThatFit(trusted, count);
}

// Matched points confirmed static by earlier frames, less those the rigid consensus says
// moved.
std::vector<bool> Tracker::confirmedStaticMatches() const {
  std::vector<bool> confirmed(current_.size(), false);
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const auto& point = current_.points[i];
    confirmed[i] = point && !rigidity_.brokenAt(i) &&
                   motion_evidence_.isConfirmedStatic(point->id(), current_.index);
  }
  return confirmed;
}

// After the pose from the `trusted` matches: the others join if they fit it.
void Tracker::joinMatchesThatFit(const std::vector<bool>& trusted, int trusted_count) {
  std::vector<bool> fits(current_.size(), false);
  int joining = 0;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const auto& point = current_.points[i];
    if (!point) continue;
    fits[i] = trusted[i] ? !current_.outliers[i]
                         : !rigidity_.brokenAt(i) &&
                               motion_evidence_.fitsPose(current_, i, camera_, *pyramid_);
    if (fits[i] && !trusted[i]) ++joining;
  }
  // A few joining points would barely move the pose: they count as inliers of it as it is.
  if (20 * joining < trusted_count) {
    for (std::size_t i = 0; i < current_.size(); ++i) {
      if (fits[i] && !trusted[i]) current_.outliers[i] = false;
    }
    return;
  }
  optimizeCurrentPose(&fits, 2);  // from a pose near the optimum: two rounds
}

void Tracker::testRigidity() {
  rigidity_ = {};
  if (!motion_evidence_.enabled() || camera_.bf <= 0.0) return;
  const auto start = std::chrono::steady_clock::now();
  if (params_.motion_evidence.rigidity) {
    rigidity_ = rigidConsensus(current_, camera_.intrinsics(), params_.motion_evidence.rigid);
  }
  if (origin_verdict_.informative()) rigidity_ = origin_verdict_;
  rigidity_ms_ +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// A map's first frames (origin_segmentation.h): the static motion since the origin keyframe
// restarts the pose and the matches, and a second motion's features are broken for this
// frame's rigidity. Once the origin is out of view the test ends for the map.
void Tracker::segmentAgainstMapOrigin() {
  origin_verdict_ = {};
  const auto& params = params_.motion_evidence.origin;
  if (!motion_evidence_.enabled() || !params.enabled || camera_.bf <= 0.0 || !depth_map_origin_ ||
      depth_map_origin_->isBad() || !reference_ ||
      depth_map_origin_->mapId() != reference_->mapId() ||
      current_.index > depth_map_origin_->frameIndex() +
                           static_cast<std::size_t>(std::max(0, params.window_frames))) {
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  const auto size = camera_.size();
  auto segments = segmentAgainstOrigin(current_, *depth_map_origin_, camera_.intrinsics(),
                                       size.width, size.height, params);
  if (segments.pairs < params.min_points) depth_map_origin_.reset();
  if (segments.T_current_origin) {
    current_.T_c_w = *segments.T_current_origin * depth_map_origin_->T_c_w();
    current_.clearMatches();
    current_.points = std::move(segments.static_matches);
  }
  origin_verdict_ = std::move(segments.verdict);
  rigidity_ms_ +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<bool> Tracker::notRigidlyBroken() const {
  std::vector<bool> use(current_.size(), true);
  for (std::size_t i = 0; i < current_.size(); ++i) use[i] = !rigidity_.brokenAt(i);
  return use;
}

// Points the detector's memory or the residuals of recent frames call moving are left out, and
// those the rigid consensus of this frame finds moved.
bool Tracker::leftOutOfPose(const map::MapPoint& point, std::size_t feature) const {
  if (rigidity_.brokenAt(feature)) return true;
  if (dynamic_memory_.isDynamic(point.id())) return true;
  return motion_evidence_.isDynamic(point.id(), current_.index);
}

// Class-free motion evidence (issue 16): map points whose residuals keep saying they moved
// leave pose estimation for good; features found moving make no map point
// (FeatureSet::moving). A point that turns dynamic while still an inlier of this pose is
// taken out and the pose re-estimated. Dynamic points stay in the map (retiring them, and so
// re-creating points from the same features at the next keyframe, cost accuracy on static
// scenes: docs/dynamic.md "Motion evidence").
void Tracker::excludeMovingPoints(TrackingOutcome& outcome) {
  if (!motion_evidence_.enabled()) return;
  const auto start = std::chrono::steady_clock::now();
  const auto verdict = motion_evidence_.update(current_, last_, camera_, *pyramid_, rigidity_);
  outcome.moving_features = static_cast<int>(verdict.moving_features);
  outcome.moving_points.clear();
  if (verdict.moving_features > 0) {  // else FeatureSet::moving may be unset
    const auto& features = *current_.features;
    for (std::size_t i = 0; i < features.moving.size(); ++i) {
      if (features.moving[i]) outcome.moving_points.push_back(features.keypoints[i].pt);
    }
  }
  bool pose_used_one = false;
  for (const std::size_t i : verdict.dynamic_points) {
    if (!current_.outliers[i]) {
      pose_used_one = true;
      --inliers_;
    }
    current_.outliers[i] = true;
  }
  if (pose_used_one) optimizeCurrentPose();
  outcome.motion_evidence_ms =
      rigidity_ms_ +
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

int Tracker::inlierReference() const {
  if (recent_inliers_.empty()) return 0;
  std::vector<int> sorted(recent_inliers_.begin(), recent_inliers_.end());
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  return sorted[sorted.size() / 2];
}

bool Tracker::enoughInliers() const {
  if (inliers_ < params_.min_local_map_inliers) return false;
  const int recent = inlierReference();
  if (recent == 0) return true;
  const double frames_since = current_.index > last_tracked_frame_
                                  ? static_cast<double>(current_.index - last_tracked_frame_)
                                  : 1.0;
  const double reference = recent * std::exp2(-std::max(0.0, frames_since - 1.0) /
                                              std::max(1, params_.inlier_reference_half_life));
  if (inliers_ >= params_.min_inlier_fraction_of_last * reference) return true;
  spdlog::debug("frame {}: {} local-map inliers, under {:.2f} of the recent frames' {:.0f}",
                current_.index, inliers_, params_.min_inlier_fraction_of_last, reference);
  return false;
}

// Missed detections: map points that keep failing the chi-square test near a recent box of
// a moving object are on that object; they leave pose estimation and the map.
void Tracker::cullDynamicPoints() {
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const auto& point = current_.points[i];
    if (!point || point->observationCount() < 1) continue;  // not in the map (VO points)
    if (!dynamic_memory_.recordOutcome(point->id(), current_.features->keypoints[i].pt,
                                       current_.outliers[i])) {
      continue;
    }
    current_.outliers[i] = true;
    map_->retireMapPoint(point);
    // Nor may a new keyframe make a fresh point from this feature's depth.
    current_.features->depth[i] = -1.0F;
    current_.features->u_right[i] = -1.0F;
  }
}

Tracker::KeyFrameDecision Tracker::needNewKeyFrame() const {
  if (localization_only_) return KeyFrameDecision::No;
  const std::size_t keyframes =
      map_->keyFrameCountOf(reference_ ? reference_->mapId() : active_map_);
  const int min_observations = keyframes <= 2 ? 2 : 3;
  const int reference_matches = reference_ ? reference_->trackedMapPoints(min_observations) : 0;
  const bool mapper_idle = mapper_.acceptsKeyFrames();

  int tracked_close = 0;
  int untracked_close = 0;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const float z = current_.features->depth[i];
    if (z <= 0 || z >= camera_.close_depth) continue;
    if (current_.features->isMoving(i)) continue;  // no map point wanted there
    // Map points only, as ORB-SLAM3 counts them after dropping the frame's visual-odometry
    // points: those are not in the map, and counted they kept need_close from ever firing.
    const auto& point = current_.points[i];
    if (point && !current_.outliers[i] && point->observationCount() > 0) {
      ++tracked_close;
    } else {
      ++untracked_close;
    }
  }
  const bool need_close = tracked_close < 100 && untracked_close > 70;
  const double ratio = keyframes < 2 ? 0.4 : (camera_.bf > 0.0 ? 0.75 : 0.9);
  const std::size_t since = current_.index - last_keyframe_frame_;
  const bool c1a = since >= static_cast<std::size_t>(params_.max_frames_between_keyframes);
  const bool c1b_when_idle =
      since >= static_cast<std::size_t>(params_.min_frames_between_keyframes);
  const bool c1c = inliers_ < reference_matches * 0.25 || need_close;
  const bool c2 = (inliers_ < reference_matches * ratio || need_close) && inliers_ > 15;
  if (!c2) return KeyFrameDecision::No;
  if (mapper_idle && (c1a || c1b_when_idle || c1c)) return KeyFrameDecision::Now;
  if (!(c1a || c1c)) {
    return c1b_when_idle && params_.wait_for_busy_mapper ? KeyFrameDecision::WhenMapperIdle
                                                         : KeyFrameDecision::No;
  }
  mapper_.interruptBundleAdjustment();
  return mapper_.queuedKeyFrames() < 3 ? KeyFrameDecision::Now : KeyFrameDecision::No;
}

void Tracker::createNewKeyFrame() {
  auto kf = std::make_shared<map::KeyFrame>(map_->nextKeyFrameId(), current_.index,
                                            current_.timestamp, *current_.T_c_w, current_.features,
                                            pyramid_, camera_.intrinsics());
  active_map_ = reference_->mapId();  // follows merges
  kf->setMapId(active_map_);
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const auto& point = current_.points[i];
    if (point && !current_.outliers[i] && point->observationCount() > 0) kf->setMapPoint(i, point);
  }
  // New close points from depth, nearest first (ORB-SLAM's CreateNewKeyFrame for RGB-D).
  std::vector<std::pair<float, std::size_t>> by_depth;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    if (current_.features->depth[i] > 0) by_depth.emplace_back(current_.features->depth[i], i);
  }
  std::sort(by_depth.begin(), by_depth.end());
  int count = 0;
  for (const auto& [z, i] : by_depth) {
    const auto& point = current_.points[i];
    if (current_.features->isMoving(i)) continue;
    // A missed detection must not put map points on a person who was just there.
    if (dynamic_memory_.likelyMissedDetection() &&
        dynamic_memory_.nearRecentBox(current_.features->keypoints[i].pt)) {
      continue;
    }
    if (!point || point->observationCount() < 1 || current_.outliers[i]) {
      current_.outliers[i] = false;
      newPointFromDepth(i, kf);
    }
    if (++count > 100 && z > camera_.close_depth) break;
  }
  mapper_.insertKeyFrame(kf);
  reference_ = last_keyframe_ = kf;
  current_.reference = kf;
  last_keyframe_frame_ = current_.index;
}

}  // namespace lumaslam::track
