#pragma once
// A keyframe: an immutable FeatureSet plus the state mapping and loop closing refine (pose,
// landmark associations, covisibility, spanning tree). Owned by the Map. Locking: see map.h.
#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <vector>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/map/feature_set.h"
#include "lumaslam/map/ids.h"

namespace lumaslam::map {

class MapPoint;

class KeyFrame : public std::enable_shared_from_this<KeyFrame> {
 public:
  // Covisibility edges need at least this many shared points (ORB-SLAM's threshold).
  static constexpr int kMinCovisibilityWeight = 15;

  KeyFrame(Id id, std::size_t frame_index, double timestamp, const SE3& T_c_w,
           std::shared_ptr<const FeatureSet> features,
           std::shared_ptr<const feature::ScaleLevels> pyramid, const CameraIntrinsics& intrinsics);

  Id id() const { return id_; }
  std::size_t frameIndex() const { return frame_index_; }
  double timestamp() const { return timestamp_; }
  const FeatureSet& features() const { return *features_; }
  const feature::ScaleLevels& pyramid() const { return *pyramid_; }
  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  Descriptor descriptor(std::size_t feature_index) const;

  SE3 T_c_w() const;
  SE3 T_w_c() const;
  Eigen::Vector3d center() const;  // camera centre in the world
  void setPose(const SE3& T_c_w);

  // Landmark associations, one slot per feature.
  std::shared_ptr<MapPoint> mapPoint(std::size_t feature_index) const;
  std::vector<std::shared_ptr<MapPoint>> mapPoints() const;  // nullptr where none
  void setMapPoint(std::size_t feature_index, std::shared_ptr<MapPoint> point);
  void eraseMapPoint(std::size_t feature_index);
  void erasePointById(Id point_id);
  // Points observed by at least `min_observations` keyframes (ORB-SLAM's TrackedMapPoints).
  int trackedMapPoints(int min_observations) const;

  // Covisibility graph: rebuild this keyframe's edges from its points' observations and
  // update the neighbours' edges back; attaches the keyframe to the spanning tree the
  // first time (parent = strongest neighbour).
  void updateConnections();
  void addConnection(const std::shared_ptr<KeyFrame>& other, int weight);
  void eraseConnection(Id other);
  std::vector<std::shared_ptr<KeyFrame>> covisibles(std::size_t max_count = SIZE_MAX) const;
  std::vector<std::shared_ptr<KeyFrame>> covisiblesWithMinWeight(int min_weight) const;
  int weight(Id other) const;

  // Spanning tree and loop edges (essential graph).
  std::shared_ptr<KeyFrame> parent() const;
  void setParent(const std::shared_ptr<KeyFrame>& parent);
  std::vector<std::shared_ptr<KeyFrame>> children() const;
  void addChild(const std::shared_ptr<KeyFrame>& child);
  void eraseChild(Id child);
  void addLoopEdge(const std::shared_ptr<KeyFrame>& other);
  std::vector<std::shared_ptr<KeyFrame>> loopEdges() const;

  bool isBad() const { return bad_.load(); }
  // Which map of the atlas the keyframe belongs to (map.h); changes when maps are merged.
  MapId mapId() const { return map_id_.load(); }
  void setMapId(MapId id) { map_id_ = id; }
  // Pose relative to the parent, kept when the keyframe is retired so that frames tracked
  // against it can still be expressed in the world (ORB-SLAM's mTcp).
  SE3 T_c_parent() const;

 private:
  friend class Map;
  void retire(const std::shared_ptr<KeyFrame>& new_parent_for_self);
  void sortConnectionsLocked();

  const Id id_;
  const std::size_t frame_index_;
  const double timestamp_;
  const std::shared_ptr<const FeatureSet> features_;
  const std::shared_ptr<const feature::ScaleLevels> pyramid_;
  const CameraIntrinsics intrinsics_;

  mutable std::mutex pose_mutex_;
  SE3 T_c_w_;
  SE3 T_w_c_;
  SE3 T_c_parent_ = SE3::Identity();

  mutable std::mutex points_mutex_;
  std::vector<std::shared_ptr<MapPoint>> points_;

  mutable std::mutex graph_mutex_;
  std::map<Id, std::pair<std::weak_ptr<KeyFrame>, int>> connections_;
  std::vector<std::pair<int, std::weak_ptr<KeyFrame>>> ordered_connections_;  // weight desc
  bool in_spanning_tree_ = false;
  std::weak_ptr<KeyFrame> parent_;
  std::map<Id, std::weak_ptr<KeyFrame>> children_;
  std::map<Id, std::weak_ptr<KeyFrame>> loop_edges_;

  std::atomic<bool> bad_{false};
  std::atomic<MapId> map_id_{0};
};

}  // namespace lumaslam::map
