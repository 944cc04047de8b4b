#include "lumaslam/mapping/local_mapper.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include <spdlog/spdlog.h>

#include "lumaslam/mapping/ba_observation.h"
#include "lumaslam/mapping/epipolar_matcher.h"
#include "lumaslam/mapping/point_fusion.h"
#include "lumaslam/mapping/triangulation.h"
#include "lumaslam/optimize/local_ba.h"

namespace lumaslam::mapping {
namespace {

// Median depth of a keyframe's map points in its camera (ORB-SLAM's ComputeSceneMedianDepth).
double medianSceneDepth(const map::KeyFrame& keyframe) {
  const SE3 T_c_w = keyframe.T_c_w();
  std::vector<double> depths;
  for (const auto& point : keyframe.mapPoints()) {
    if (point && !point->isBad()) depths.push_back((T_c_w * point->position()).z());
  }
  if (depths.empty()) return 0.0;
  std::nth_element(depths.begin(), depths.begin() + static_cast<long>(depths.size() / 2),
                   depths.end());
  return depths[depths.size() / 2];
}

}  // namespace

LocalMapper::LocalMapper(std::shared_ptr<map::Map> map, const track::FrameCamera& camera,
                         std::shared_ptr<const feature::ScaleLevels> pyramid,
                         const LocalMapperParams& params)
    : map_(std::move(map)),
      camera_(camera),
      pyramid_(std::move(pyramid)),
      params_(params),
      // A waiting keyframe stops the running bundle adjustment; taking one clears the request.
      queue_([this](const auto& keyframe) { process(keyframe); }, {.threaded = params.threaded},
             {.on_push = [this] { abort_ba_ = true; }, .on_take = [this] { abort_ba_ = false; }}) {}

LocalMapper::~LocalMapper() {
  shutdown();
}

void LocalMapper::shutdown() {
  queue_.shutdown();
}

void LocalMapper::insertKeyFrame(std::shared_ptr<map::KeyFrame> keyframe) {
  queue_.push(std::move(keyframe));
}

bool LocalMapper::acceptsKeyFrames() const {
  return queue_.idle();
}

std::size_t LocalMapper::queuedKeyFrames() const {
  return queue_.size();
}

void LocalMapper::processPending() {
  queue_.processPending();
}

void LocalMapper::waitUntilIdle() {
  queue_.waitUntilIdle();
}

bool LocalMapper::waitUntilIdleFor(std::chrono::microseconds timeout) {
  return queue_.waitUntilIdleFor(timeout);
}

void LocalMapper::process(const std::shared_ptr<map::KeyFrame>& keyframe) {
  {
    std::lock_guard processing(processing_mutex_);
    processLocked(keyframe);
  }
  if (params_.on_keyframe_processed && !keyframe->isBad()) {
    params_.on_keyframe_processed(keyframe);
  }
}

void LocalMapper::processLocked(const std::shared_ptr<map::KeyFrame>& keyframe) {
  attachObservations(keyframe);
  cullRecentPoints(keyframe);
  const std::size_t points_before = map_->mapPointCount();
  triangulateNewPoints(keyframe);
  spdlog::debug("keyframe {} (frame {}): {} points triangulated, {} in the map", keyframe->id(),
                keyframe->frameIndex(), map_->mapPointCount() - points_before,
                map_->mapPointCount());
  if (queuedKeyFrames() == 0) fuseWithNeighbours(keyframe);
  if (queuedKeyFrames() == 0) {
    if (params_.bundle_adjustment && map_->keyFrameCountOf(keyframe->mapId()) > 2) {
      localBundleAdjustment(keyframe);
    }
    if (params_.keyframe_culling) cullKeyFrames(keyframe);
  }
  ++processed_;
}

void LocalMapper::attachObservations(const std::shared_ptr<map::KeyFrame>& keyframe) {
  const auto points = keyframe->mapPoints();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& point = points[i];
    if (!point || point->isBad()) continue;
    if (point->featureIndexIn(keyframe->id()) < 0) {
      point->addObservation(keyframe, static_cast<int>(i));
      point->updateNormalAndDepth();
      point->computeDistinctiveDescriptor();
    } else {
      recent_points_.push_back(point);  // created by tracking for this keyframe
    }
  }
  keyframe->updateConnections();
  map_->addKeyFrame(keyframe);
}

void LocalMapper::cullRecentPoints(const std::shared_ptr<map::KeyFrame>& keyframe) {
  const int min_observations = camera_.bf > 0 ? 3 : 2;
  for (auto it = recent_points_.begin(); it != recent_points_.end();) {
    const auto& point = *it;
    const auto age = keyframe->id() - point->referenceKeyFrameId();
    if (point->isBad()) {
      it = recent_points_.erase(it);
    } else if (point->foundRatio() < 0.25 ||
               (age >= 2 && point->observationCount() <= min_observations)) {
      map_->retireMapPoint(point);
      it = recent_points_.erase(it);
    } else if (age >= 3) {
      it = recent_points_.erase(it);
    } else {
      ++it;
    }
  }
}

void LocalMapper::triangulateNewPoints(const std::shared_ptr<map::KeyFrame>& keyframe) {
  const auto neighbours =
      keyframe->covisibles(static_cast<std::size_t>(params_.triangulation_neighbours));
  const SE3 T_c1_w = keyframe->T_c_w();
  const Eigen::Vector3d C1 = keyframe->center();
  const auto& k = keyframe->intrinsics();
  const double baseline = k.bf > 0 ? k.bf / k.fx : 0.0;
  const double ratio_factor = 1.5 * pyramid_->scaleFactor();
  const auto& f1 = keyframe->features();

  int neighbours_used = 0;
  for (const auto& neighbour : neighbours) {
    // Keep up with tracking first, but as ORB-SLAM only after the best usable neighbour: a
    // mapper that falls behind (a loaded machine) must still give every keyframe new points,
    // or monocular tracking runs out of them and is lost.
    if (neighbours_used > 0 && queuedKeyFrames() > 0) return;
    const SE3 T_c2_w = neighbour->T_c_w();
    const Eigen::Vector3d C2 = neighbour->center();
    if ((C2 - C1).norm() < std::max(baseline, 1e-3)) continue;
    // Monocular: a baseline below 1% of the scene depth triangulates nothing useful.
    if (baseline == 0.0 && (C2 - C1).norm() < 0.01 * medianSceneDepth(*neighbour)) continue;
    ++neighbours_used;
    const auto& f2 = neighbour->features();
    const Eigen::Matrix3d F21 = fundamental21(T_c1_w, T_c2_w, k);
    const auto pairs = matchForTriangulation(*keyframe, *neighbour, F21);
    const SE3 T_w_c1 = T_c1_w.inverse();
    const SE3 T_w_c2 = T_c2_w.inverse();
    for (const auto& [i1, i2] : pairs) {
      const auto& p1 = f1.undistorted[i1];
      const auto& p2 = f2.undistorted[i2];
      const Eigen::Vector2d x1((p1.x - k.cx) / k.fx, (p1.y - k.cy) / k.fy);
      const Eigen::Vector2d x2((p2.x - k.cx) / k.fx, (p2.y - k.cy) / k.fy);
      const Eigen::Vector3d ray1 = T_w_c1.rotation() * x1.homogeneous();
      const Eigen::Vector3d ray2 = T_w_c2.rotation() * x2.homogeneous();
      const double cos_rays = ray1.dot(ray2) / (ray1.norm() * ray2.norm());
      const float z1 = f1.depth[i1];
      const float z2 = f2.depth[i2];
      const double cos_stereo1 = z1 > 0 ? std::cos(2 * std::atan2(baseline / 2, z1)) : 2.0;
      const double cos_stereo2 = z2 > 0 ? std::cos(2 * std::atan2(baseline / 2, z2)) : 2.0;
      const double cos_stereo = std::min(cos_stereo1, cos_stereo2);

      std::optional<Eigen::Vector3d> X_w;
      if (cos_rays < cos_stereo && cos_rays > 0 && (z1 > 0 || z2 > 0 || cos_rays < 0.9998)) {
        X_w = triangulateLinear(x1, T_c1_w, x2, T_c2_w);
      } else if (z1 > 0 && cos_stereo1 < cos_stereo2) {
        X_w = T_w_c1 * Eigen::Vector3d(x1.x() * z1, x1.y() * z1, z1);
      } else if (z2 > 0 && cos_stereo2 < cos_stereo1) {
        X_w = T_w_c2 * Eigen::Vector3d(x2.x() * z2, x2.y() * z2, z2);
      }
      if (!X_w) continue;
      const int octave1 = f1.keypoints[i1].octave;
      const int octave2 = f2.keypoints[i2].octave;
      if (!reprojectionAcceptable(*X_w, T_c1_w, k, {p1.x, p1.y}, f1.u_right[i1],
                                  pyramid_->sigma2(octave1)) ||
          !reprojectionAcceptable(*X_w, T_c2_w, k, {p2.x, p2.y}, f2.u_right[i2],
                                  pyramid_->sigma2(octave2))) {
        continue;
      }
      // Scale consistency: the distance ratio must agree with the pyramid-level ratio.
      const double d1 = (*X_w - C1).norm();
      const double d2 = (*X_w - C2).norm();
      if (d1 == 0 || d2 == 0) continue;
      const double ratio_distance = d2 / d1;
      const double ratio_octave = pyramid_->scale(octave1) / pyramid_->scale(octave2);
      if (ratio_distance * ratio_factor < ratio_octave ||
          ratio_distance > ratio_octave * ratio_factor) {
        continue;
      }
      auto point = std::make_shared<map::MapPoint>(map_->nextMapPointId(), *X_w, keyframe);
      point->addObservation(keyframe, static_cast<int>(i1));
      point->addObservation(neighbour, static_cast<int>(i2));
      keyframe->setMapPoint(i1, point);
      neighbour->setMapPoint(i2, point);
      point->computeDistinctiveDescriptor();
      point->updateNormalAndDepth();
      map_->addMapPoint(point);
      recent_points_.push_back(point);
    }
  }
}

void LocalMapper::fuseWithNeighbours(const std::shared_ptr<map::KeyFrame>& keyframe) {
  std::vector<std::shared_ptr<map::KeyFrame>> targets;
  std::unordered_set<map::Id> seen{keyframe->id()};
  for (const auto& neighbour :
       keyframe->covisibles(static_cast<std::size_t>(params_.fusion_neighbours))) {
    if (!seen.insert(neighbour->id()).second) continue;
    targets.push_back(neighbour);
    for (const auto& second : neighbour->covisibles(5)) {
      if (seen.insert(second->id()).second) targets.push_back(second);
    }
  }
  const auto own_points = keyframe->mapPoints();
  for (const auto& target : targets) fusePointsInto(*map_, target, own_points);

  std::vector<std::shared_ptr<map::MapPoint>> theirs;
  std::unordered_set<map::Id> seen_points;
  for (const auto& target : targets) {
    for (const auto& point : target->mapPoints()) {
      if (point && !point->isBad() && seen_points.insert(point->id()).second)
        theirs.push_back(point);
    }
  }
  fusePointsInto(*map_, keyframe, theirs);

  for (const auto& point : keyframe->mapPoints()) {
    if (point && !point->isBad()) {
      point->computeDistinctiveDescriptor();
      point->updateNormalAndDepth();
    }
  }
  keyframe->updateConnections();
}

void LocalMapper::localBundleAdjustment(const std::shared_ptr<map::KeyFrame>& keyframe) {
  std::vector<std::shared_ptr<map::KeyFrame>> local{keyframe};
  for (const auto& kf : keyframe->covisibles()) local.push_back(kf);
  std::unordered_map<map::Id, std::shared_ptr<map::KeyFrame>> in_problem;
  optimize::LocalBAProblem problem;
  problem.camera = camera_.intrinsics();
  for (const auto& kf : local) {
    in_problem[kf->id()] = kf;
    problem.keyFrames.push_back({kf->id(), kf->T_c_w(), map_->isMapOrigin(*kf)});
  }
  std::vector<std::shared_ptr<map::MapPoint>> points;
  std::unordered_set<map::Id> seen;
  for (const auto& kf : local) {
    for (const auto& point : kf->mapPoints()) {
      if (point && !point->isBad() && seen.insert(point->id()).second) points.push_back(point);
    }
  }
  struct ObservationRef {
    std::shared_ptr<map::KeyFrame> keyframe;
    std::shared_ptr<map::MapPoint> point;
    std::size_t index;
  };
  std::vector<ObservationRef> refs;
  for (const auto& point : points) {
    problem.points.push_back({point->id(), point->position()});
    for (const auto& [kf, index] : point->observations()) {
      if (kf->isBad()) continue;
      if (!in_problem.count(kf->id())) {
        in_problem[kf->id()] = kf;
        problem.keyFrames.push_back({kf->id(), kf->T_c_w(), true});  // outer: fixed gauge
      }
      const auto i = static_cast<std::size_t>(index);
      problem.observations.push_back(baObservation(*kf, i, point->id()));
      refs.push_back({kf, point, i});
    }
  }
  if (problem.observations.empty()) return;
  optimize::LocalBAOptions options;
  options.maxIterations = params_.ba_iterations;
  options.abort = &abort_ba_;
  const auto result = optimize::optimizeLocalBundle(problem, options);

  std::lock_guard lock(map_->updateMutex());
  for (std::size_t o = 0; o < refs.size(); ++o) {
    if (!result.isOutlier[o]) continue;
    const auto& ref = refs[o];
    if (ref.keyframe->mapPoint(ref.index) == ref.point) ref.keyframe->eraseMapPoint(ref.index);
    ref.point->eraseObservation(ref.keyframe->id());
  }
  for (std::size_t k = 0; k < problem.keyFrames.size(); ++k) {
    if (!problem.keyFrames[k].fixed) in_problem[problem.keyFrames[k].id]->setPose(result.T_c_w[k]);
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (points[p]->isBad()) continue;
    points[p]->setPosition(result.X_w[p]);
    points[p]->updateNormalAndDepth();
  }
}

void LocalMapper::cullKeyFrames(const std::shared_ptr<map::KeyFrame>& keyframe) {
  for (const auto& candidate : keyframe->covisibles()) {
    if (candidate->isBad() || map_->isOrigin(*candidate)) continue;
    const auto& f = candidate->features();
    const auto points = candidate->mapPoints();
    int total = 0;
    int redundant = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto& point = points[i];
      if (!point || point->isBad()) continue;
      if (camera_.bf > 0 && (f.depth[i] <= 0 || f.depth[i] > camera_.close_depth)) continue;
      ++total;
      if (point->observationCount() <= 3) continue;
      const int level = f.keypoints[i].octave;
      int observers = 0;
      for (const auto& [other, index] : point->observations()) {
        if (other == candidate) continue;
        if (other->features().keypoints[static_cast<std::size_t>(index)].octave <= level + 1)
          ++observers;
        if (observers >= 3) break;
      }
      if (observers >= 3) ++redundant;
    }
    if (total > 0 && redundant > params_.redundancy * total) map_->retireKeyFrame(candidate);
  }
}

}  // namespace lumaslam::mapping
