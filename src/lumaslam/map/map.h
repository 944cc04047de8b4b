#pragma once
// The map: the only state shared between tracking, local mapping and loop closing.
//
// Locking story (lock order from outer to inner; never acquire an outer lock while holding
// an inner one):
//   1. Map::updateMutex()   held by tracking for one frame and by mapping / loop closing
//                           while they write optimisation results back, so that tracking
//                           never sees half of a bundle adjustment applied.
//   2. Map's own structure lock (shared_mutex, internal): membership of keyframes/points.
//   3. Object locks inside KeyFrame (pose / points / graph) and MapPoint: leaf locks. They are
//      held only inside one accessor and never two at once: methods that need another
//      object's data copy it out first (e.g. KeyFrame::updateConnections reads each point's
//      observations, releases, then writes its own edges, then each neighbour's).
//   4. The KeyFrameIndex's own lock (place-recognition database): a leaf, taken only inside
//      its calls, which the Map makes with none of its own locks held.
// Atlas (ORB-SLAM3): the Map holds every map the tracker started; each keyframe carries its
// map's id, maps share no covisibility, and merging relabels one map's keyframes with the
// other's id (loop/map_merge.h). Each map's first keyframe is its origin: never retired, and
// fixed in bundle adjustment (the gauge).
// Objects are never deleted under someone's feet: retiring marks them bad and removes them
// from the Map; shared_ptrs held elsewhere keep them alive until released.
#include <atomic>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <vector>

#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/keyframe_index.h"
#include "lumaslam/map/map_point.h"

namespace lumaslam::map {

class Map {
 public:
  Id nextKeyFrameId() { return next_keyframe_id_++; }
  Id nextMapPointId() { return next_point_id_++; }

  void addKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);
  void addMapPoint(const std::shared_ptr<MapPoint>& point);

  std::shared_ptr<KeyFrame> keyFrame(Id id) const;
  std::shared_ptr<MapPoint> mapPoint(Id id) const;
  std::vector<std::shared_ptr<KeyFrame>> keyFrames() const;  // sorted by id
  std::vector<std::shared_ptr<MapPoint>> mapPoints() const;  // sorted by id
  std::size_t keyFrameCount() const;
  std::size_t mapPointCount() const;
  std::shared_ptr<KeyFrame> originKeyFrame() const;  // the first map's

  // A fresh id for a new map of the atlas (the first map is 0).
  MapId newMapId() { return next_map_id_++; }
  // True for the first keyframe of any map, merged since or not: never retired.
  bool isOrigin(const KeyFrame& keyframe) const;
  // True for the first keyframe of the keyframe's (current) map: fixed in bundle adjustment.
  bool isMapOrigin(const KeyFrame& keyframe) const;
  std::vector<std::shared_ptr<KeyFrame>> keyFramesOf(MapId map) const;  // sorted by id
  std::size_t keyFrameCountOf(MapId map) const;
  // Keyframes of `moved` join `into` (their poses must already be in its world).
  void relabelMap(MapId moved, MapId into);
  // Resets a map (ORB-SLAM3's ResetActiveMap): its keyframes leave place recognition and take
  // the id kDiscardedMap, so that no frame, relocalization, loop or merge uses them again.
  void discardMap(MapId map);

  // Marks the point bad, detaches it from every keyframe and removes it from the map.
  void retireMapPoint(const std::shared_ptr<MapPoint>& point);
  // ORB-SLAM's KeyFrame::SetBadFlag: detaches the keyframe from the covisibility graph and
  // its points (retiring points left with too few observations), hands its children to the
  // covisible keyframes best connected to them, and removes it. The origin is never retired.
  // Returns false if it was not retired.
  bool retireKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);
  // Fusion: every observation of `old_point` moves to `new_point` (unless that keyframe
  // already sees `new_point`); `old_point` is retired and records its replacement.
  void replaceMapPoint(const std::shared_ptr<MapPoint>& old_point,
                       const std::shared_ptr<MapPoint>& new_point);

  // Map files (map_file.h): the id counters and each map's origin, as saved and restored.
  struct Bookkeeping {
    Id next_keyframe_id = 0;
    Id next_point_id = 0;
    MapId next_map_id = 1;
    std::vector<std::pair<MapId, Id>> origins;  // sorted by map id
  };
  Bookkeeping bookkeeping() const;
  // After every keyframe of a loaded map was added (which records the first keyframe of each
  // map id as its origin, not knowing about merges).
  void restoreBookkeeping(const Bookkeeping& bookkeeping);

  std::mutex& updateMutex() const { return update_mutex_; }
  void clear();

  // Keeps `index` in step with the keyframes from now on (the ones already in the map are
  // added at once). Set it before other threads use the map; null detaches it.
  void setKeyFrameIndex(std::shared_ptr<KeyFrameIndex> index);

 private:
  mutable std::mutex update_mutex_;
  mutable std::shared_mutex mutex_;
  std::unordered_map<Id, std::shared_ptr<KeyFrame>> keyframes_;
  std::unordered_map<Id, std::shared_ptr<MapPoint>> points_;
  std::weak_ptr<KeyFrame> origin_;
  std::unordered_map<MapId, Id> origins_;  // per map id ever used: its first keyframe
  std::shared_ptr<KeyFrameIndex> index_;
  std::atomic<Id> next_keyframe_id_{0};
  std::atomic<Id> next_point_id_{0};
  std::atomic<MapId> next_map_id_{1};
};

}  // namespace lumaslam::map
