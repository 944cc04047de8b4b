// The monocular part of Tracker: two-view initialisation and the initial map (ORB-SLAM's
// MonocularInitialization and CreateInitialMapMonocular; the initial bundle adjustment is
// the TwoViewInitializer's refinement).
#include <algorithm>

#include <spdlog/spdlog.h>

#include "lumaslam/track/tracker.h"

namespace lumaslam::track {

bool Tracker::initializeMonocular() {
  if (!monocular_initializer_) {
    monocular_initializer_ = std::make_unique<MonocularInitializer>(camera_, params_.monocular);
  }
  const auto pair = monocular_initializer_->tryInitialize(current_);
  if (!pair) return false;
  const bool created = createInitialMonocularMap(*pair);
  // Success or not, the next attempt starts from a new reference frame.
  monocular_initializer_->reset();
  return created;
}

bool Tracker::createInitialMonocularMap(const InitialPair& pair) {
  const Frame& ref = monocular_initializer_->reference();
  auto kf1 = std::make_shared<map::KeyFrame>(map_->nextKeyFrameId(), ref.index, ref.timestamp,
                                             SE3::Identity(), ref.features, pyramid_,
                                             camera_.intrinsics());
  auto kf2 = std::make_shared<map::KeyFrame>(map_->nextKeyFrameId(), current_.index,
                                             current_.timestamp, pair.T_cur_ref, current_.features,
                                             pyramid_, camera_.intrinsics());
  // The points come refined by the initializer's two-view bundle adjustment.
  std::vector<std::shared_ptr<map::MapPoint>> kept;
  std::vector<double> depths;
  for (const auto& initial : pair.points) {
    if (initial.X_ref.z() <= 0) continue;
    // Referenced to the older keyframe: the mapper ages points by keyframe id from it.
    auto point = std::make_shared<map::MapPoint>(map_->nextMapPointId(), initial.X_ref, kf1);
    point->addObservation(kf1, static_cast<int>(initial.reference_index));
    point->addObservation(kf2, static_cast<int>(initial.current_index));
    kf1->setMapPoint(initial.reference_index, point);
    kf2->setMapPoint(initial.current_index, point);
    depths.push_back(initial.X_ref.z());  // the first keyframe is the world frame
    kept.push_back(std::move(point));
  }
  if (static_cast<int>(kept.size()) < params_.min_initial_monocular_points) {
    spdlog::info("frame {}: initial map rejected, {} points (need {})", current_.index, kept.size(),
                 params_.min_initial_monocular_points);
    // Nothing was published: for the first map this only rewinds the id counters.
    if (map_->keyFrameCount() == 0) map_->clear();
    return false;
  }
  // Scale the map so that the median scene depth of the first keyframe is 1.
  std::nth_element(depths.begin(), depths.begin() + static_cast<long>(depths.size() / 2),
                   depths.end());
  const double scale = 1.0 / depths[depths.size() / 2];
  SE3 T_c2_w = pair.T_cur_ref;
  T_c2_w.translation() *= scale;
  kf2->setPose(T_c2_w);
  for (const auto& point : kept) point->setPosition(point->position() * scale);

  kf1->setMapId(active_map_);
  kf2->setMapId(active_map_);
  map_->addKeyFrame(kf1);
  map_->addKeyFrame(kf2);
  for (const auto& point : kept) {
    point->computeDistinctiveDescriptor();
    point->updateNormalAndDepth();
    map_->addMapPoint(point);
  }
  kf1->updateConnections();
  kf2->updateConnections();

  current_.T_c_w = T_c2_w;
  current_.clearMatches();
  for (std::size_t i = 0; i < current_.size(); ++i) {
    auto point = kf2->mapPoint(i);
    if (point) current_.points[i] = std::move(point);
  }
  spdlog::info("map {} initialised (monocular) at frames {}-{} with {} points", active_map_,
               ref.index, current_.index, kept.size());
  mapper_.insertKeyFrame(kf1);
  mapper_.insertKeyFrame(kf2);
  reference_ = last_keyframe_ = kf2;
  last_keyframe_frame_ = current_.index;
  current_.reference = kf2;
  local_keyframes_ = {kf1, kf2};
  inliers_ = static_cast<int>(kept.size());
  return true;
}

}  // namespace lumaslam::track
