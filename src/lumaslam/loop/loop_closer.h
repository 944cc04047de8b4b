#pragma once
// Loop closing (ORB-SLAM's LoopClosing): for stereo / RGB-D, where scale is observable, the
// loop transform is an SE3; for monocular (fix_scale = false) a Sim3 that also corrects the
// scale drift. For every keyframe local mapping has processed,
//  1. detect consistent loop candidates (LoopDetector);
//  2. compute the loop (computeLoop): SearchByBoW between the keyframe and each candidate,
//     EPnP + RANSAC on the keyframe's features against the candidate's map points, pose-only
//     refinement, guided projection matching of the points of the candidate and its
//     covisible keyframes, a second refinement; accepted with >= min_inliers.
//     Monocular (computeSim3Loop): the BoW matches whose feature has a map point in both
//     keyframes give 3D-3D pairs; Sim3 by RANSAC + Umeyama (sim3_ransac.h), guided matching of
//     the loop keyframe's points with it, Ceres refinement (optimize::refineSim3, >= 20
//     inliers), then projection matching of the loop neighbourhood; >= min_inliers.
//  3. correct the map (correctLoop), with local mapping paused and the map's update mutex
//     held: move the keyframe and its covisible neighbours (and their points) by the loop
//     correction, fuse the duplicated points, optimise the essential graph (spanning tree,
//     strong covisibility and loop edges) with optimize::optimizePoseGraph, then move every
//     other point with the keyframe it was corrected by (or its reference keyframe). In Sim3
//     (monocular) every keyframe is a Sim3 vertex (optimize::optimizeSim3PoseGraph), and a
//     point moves by S_corrected^-1 * S_before of its keyframe, which rescales it too.
//     Atlas: when the loop keyframe is in another map than the current one, the newer map
//     first moves into the older one's world (mergeMaps, map_merge.h), then the same
//     correction joins them; only the joined map's keyframes enter the essential graph.
//  4. optionally a global bundle adjustment of every keyframe and point (origin fixed), solved
//     on a snapshot without locks and written back with mapping paused; keyframes added
//     meanwhile follow their nearest ancestor in the spanning tree (ORB-SLAM's RunGlobalBA).
//     Threaded mode runs it in a stage of its own, so loop detection goes on; it is aborted
//     (its result discarded, the map untouched) when a new loop is corrected and at shutdown.
// A rejected candidate leaves the map untouched.
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "lumaslam/core/stage.h"
#include "lumaslam/feature/hamming.h"
#include "lumaslam/loop/keyframe_database.h"
#include "lumaslam/loop/loop_detector.h"
#include "lumaslam/loop/pose_matching.h"
#include "lumaslam/loop/sim3_ransac.h"
#include "lumaslam/loop/vocabulary.h"
#include "lumaslam/map/map.h"
#include "lumaslam/optimize/sim3.h"

namespace lumaslam::loop {

struct LoopCloserParams {
  bool threaded = true;
  std::size_t queue_capacity = 32;       // oldest keyframes are dropped beyond this
  int min_keyframes_between_loops = 10;  // ORB-SLAM: 10
  LoopDetectorParams detector;
  int direct_index_levels_up = 4;
  float bow_ratio = 0.75F;
  int bow_max_distance = feature::kThLow;
  int min_bow_matches = 20;  // ORB-SLAM: 20
  PnpRansacParams pnp{300, 4.0F, 15};
  float projection_radius_px = 10.0F;  // guided matching window (ORB-SLAM: 10)
  int min_inliers = 40;                // ORB-SLAM: 40
  float fusion_radius_px = 4.0F;       // SearchAndFuse window (ORB-SLAM: 4)
  int strong_covisibility = 100;       // essential-graph covisibility edges (ORB-SLAM: 100)
  int pose_graph_iterations = 20;
  bool global_bundle_adjustment = true;
  int global_ba_iterations = 30;
  // false (monocular): Sim3 loops and a Sim3 essential graph; true: SE3 (stereo / RGB-D).
  bool fix_scale = true;
  Sim3RansacParams sim3;
  float sim3_projection_radius_px = 7.5F;  // ORB-SLAM's SearchBySim3 window
  // Test hook: called in the global BA's thread right before the solve.
  std::function<void()> on_global_ba_start;
};

struct LoopMatch {
  std::shared_ptr<map::KeyFrame> current;
  std::shared_ptr<map::KeyFrame> loop;
  SE3 T_c_w = SE3::Identity();  // the current keyframe's pose in the loop keyframe's map
  optimize::Sim3 S_c_w{};       // the same with the current map's scale (1 for SE3 loops)
  PointSlots points;            // per feature of `current`: the matched loop map point (inliers)
  int inliers = 0;
};

struct ClosedLoop {
  map::Id current = 0;
  map::Id loop = 0;
  int inliers = 0;
  double correction_m = 0.0;  // how far the current keyframe moved
  double correction_deg = 0.0;
  double correction_scale = 1.0;  // the current keyframe's map scale vs the loop's (Sim3)
  // Set when the two keyframes were in different maps of the atlas: the newer map was moved
  // (by correction_m / correction_deg / correction_scale) into the older one (map_merge.h).
  std::optional<map::MapId> merged_map;
  map::MapId into_map = 0;
};

struct GlobalBAStats {
  int started = 0;
  int completed = 0;  // written back to the map
  int aborted = 0;    // stopped by a new loop or shutdown, nothing written
};

class LoopCloser {
 public:
  // Pauses local mapping while the map is corrected: returns a lock the mapper must hold
  // while it processes a keyframe (outer to Map::updateMutex). Empty: nothing to pause.
  using PauseMapping = std::function<std::unique_lock<std::mutex>()>;

  // Keeps references to the vocabulary and database: both must outlive the closer.
  LoopCloser(std::shared_ptr<map::Map> map, const Vocabulary& vocabulary,
             const KeyFrameDatabase& database, const LoopCloserParams& params = {},
             PauseMapping pause_mapping = {});
  ~LoopCloser();
  LoopCloser(const LoopCloser&) = delete;
  LoopCloser& operator=(const LoopCloser&) = delete;

  // Queues a keyframe local mapping has finished with.
  void insertKeyFrame(std::shared_ptr<map::KeyFrame> keyframe);
  // Sequential mode: handle every queued keyframe now, in the caller's thread.
  void processPending();
  // Threaded mode: block until the queue is empty and the closer idle.
  void waitUntilIdle();
  // Stops and joins the thread (idempotent); queued keyframes are handled first, a running
  // global BA is aborted.
  void shutdown();

  // The steps, public for tests. computeLoop never writes to the map.
  std::optional<LoopMatch> computeLoop(
      const std::shared_ptr<map::KeyFrame>& current,
      const std::vector<std::shared_ptr<map::KeyFrame>>& candidates) const;
  ClosedLoop correctLoop(const LoopMatch& match);
  ClosedLoop mergeMaps(const LoopMatch& match);
  // Returns false if there was nothing to adjust or it was aborted (map unchanged then).
  bool globalBundleAdjustment();
  void abortGlobalBundleAdjustment() { abort_global_ba_ = true; }
  bool globalBundleAdjustmentAbortRequested() const { return abort_global_ba_; }
  GlobalBAStats globalBundleAdjustmentStats() const;

  std::vector<ClosedLoop> closedLoops() const;
  int rejectedCandidates() const { return rejected_; }

 private:
  void process(const std::shared_ptr<map::KeyFrame>& keyframe);
  std::optional<KeyFrameBow> bowOf(const map::KeyFrame& keyframe) const;
  std::optional<LoopMatch> computeSim3Loop(const std::shared_ptr<map::KeyFrame>& current,
                                           const FeatureVector& current_nodes,
                                           const std::shared_ptr<map::KeyFrame>& candidate,
                                           const FeatureVector& candidate_nodes) const;
  struct GlobalBARun {};  // the global BA stage's input: adjust the whole atlas now

  // Aborts a running global BA and waits for it (threaded mode).
  void stopGlobalBundleAdjustment();
  void startGlobalBundleAdjustment();
  void runGlobalBundleAdjustment();

  std::shared_ptr<map::Map> map_;
  const Vocabulary& vocabulary_;
  const KeyFrameDatabase& database_;
  LoopCloserParams params_;
  PauseMapping pause_mapping_;
  LoopDetector detector_;
  map::Id last_loop_keyframe_ = 0;

  mutable std::mutex closed_mutex_;
  std::vector<ClosedLoop> closed_;
  std::atomic<int> rejected_{0};
  std::atomic<bool> abort_global_ba_{false};
  std::atomic<bool> stopping_{false};
  mutable std::mutex global_ba_mutex_;
  GlobalBAStats global_ba_stats_;  // guarded by global_ba_mutex_
  // Last: their threads use the above; the keyframe stage's thread starts global BA runs.
  core::Stage<GlobalBARun> global_ba_;
  core::Stage<std::shared_ptr<map::KeyFrame>> queue_;
};

}  // namespace lumaslam::loop
