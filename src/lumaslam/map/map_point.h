#pragma once
// A 3D landmark. Owned by the Map (shared_ptr); keyframes hold shared_ptrs to the points they
// observe, points hold weak_ptrs back (no ownership cycle). Locking: see map.h.
#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/map/ids.h"

namespace lumaslam::map {

class KeyFrame;

class MapPoint {
 public:
  MapPoint(Id id, const Eigen::Vector3d& position_w, const std::shared_ptr<KeyFrame>& reference);
  // A point read from a map file: its reference keyframe may have been retired (null) but the
  // id is kept.
  MapPoint(Id id, const Eigen::Vector3d& position_w, Id reference_id,
           const std::shared_ptr<KeyFrame>& reference);

  Id id() const { return id_; }
  Id referenceKeyFrameId() const { return reference_id_; }
  std::shared_ptr<KeyFrame> referenceKeyFrame() const;

  Eigen::Vector3d position() const;
  void setPosition(const Eigen::Vector3d& position_w);
  Eigen::Vector3d normal() const;  // mean viewing direction, unit length
  double minDistance() const;      // scale-invariance range (ORB-SLAM's 0.8 / 1.2 margins)
  double maxDistance() const;
  Descriptor descriptor() const;

  // Observations: keyframe id -> feature index. A stereo/RGB-D observation counts twice,
  // as in ORB-SLAM, so `observationCount() <= 2` means "seen by one stereo keyframe".
  void addObservation(const std::shared_ptr<KeyFrame>& keyframe, int feature_index);
  // Returns true when too few observations remain and the point should be retired.
  bool eraseObservation(Id keyframe_id);
  std::vector<std::pair<std::shared_ptr<KeyFrame>, int>> observations() const;
  int observationCount() const;
  int featureIndexIn(Id keyframe_id) const;  // -1 if not observed there

  // Recompute normal and distance range from the observing keyframes' centres.
  void updateNormalAndDepth();
  // Choose as representative the observed descriptor with the least median distance to the
  // others (ORB-SLAM's ComputeDistinctiveDescriptors).
  void computeDistinctiveDescriptor();
  int predictScale(double distance, const feature::ScaleLevels& pyramid) const;

  // Tracking statistics: how often the point was predicted visible and how often matched.
  void increaseVisible(int n = 1) { visible_ += n; }
  void increaseFound(int n = 1) { found_ += n; }
  double foundRatio() const;

  // What updateNormalAndDepth / computeDistinctiveDescriptor and tracking derived, as of now:
  // map files store it and restore it as it was, so that a loaded map saves to the same bytes.
  struct DerivedState {
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    double min_distance = 0.0;
    double max_distance = 0.0;
    Descriptor descriptor{};
    int visible = 1;
    int found = 1;
  };
  DerivedState derivedState() const;
  void restoreDerivedState(const DerivedState& state);

  bool isBad() const { return bad_.load(); }
  void markBad() { bad_.store(true); }
  std::shared_ptr<MapPoint> replacement() const;
  void setReplacement(const std::shared_ptr<MapPoint>& by);

 private:
  const Id id_;
  const Id reference_id_;
  std::weak_ptr<KeyFrame> reference_;

  mutable std::mutex mutex_;  // guards everything below
  Eigen::Vector3d position_w_;
  Eigen::Vector3d normal_ = Eigen::Vector3d::Zero();
  double min_distance_ = 0.0;
  double max_distance_ = 0.0;
  Descriptor descriptor_{};
  struct Observation {
    std::weak_ptr<KeyFrame> keyframe;
    int index;
    bool stereo;
  };
  std::map<Id, Observation> observations_;
  int observation_count_ = 0;
  std::weak_ptr<MapPoint> replaced_by_;

  std::atomic<int> visible_{1};
  std::atomic<int> found_{1};
  std::atomic<bool> bad_{false};
};

}  // namespace lumaslam::map
