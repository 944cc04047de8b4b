#pragma once
// Local mapping (ORB-SLAM's LocalMapping): for every new keyframe, attach its observations,
// cull doubtful new points, triangulate new points with covisible keyframes, fuse duplicates,
// run local bundle adjustment and cull redundant keyframes.
// Threaded: its own thread fed through a queue. Sequential (System.sequential): the caller
// runs processPending() after each tracked frame, outside the tracker's map lock.
#include <atomic>
#include <chrono>
#include <functional>
#include <list>
#include <memory>
#include <mutex>

#include "lumaslam/core/stage.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/map/map.h"
#include "lumaslam/track/frame_camera.h"
#include "lumaslam/track/keyframe_sink.h"

namespace lumaslam::mapping {

struct LocalMapperParams {
  bool threaded = true;
  int triangulation_neighbours = 10;
  int fusion_neighbours = 10;
  int ba_iterations = 10;
  bool bundle_adjustment = true;
  bool keyframe_culling = true;
  double redundancy = 0.9;  // a keyframe whose points are this redundant is culled
  // Called with every keyframe once it is processed (and not culled), e.g. to feed loop
  // closing; runs in the mapper's thread with no lock held.
  std::function<void(const std::shared_ptr<map::KeyFrame>&)> on_keyframe_processed;
};

class LocalMapper : public track::KeyFrameSink {
 public:
  LocalMapper(std::shared_ptr<map::Map> map, const track::FrameCamera& camera,
              std::shared_ptr<const feature::ScaleLevels> pyramid, const LocalMapperParams& params);
  ~LocalMapper() override;
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  void insertKeyFrame(std::shared_ptr<map::KeyFrame> keyframe) override;
  bool acceptsKeyFrames() const override;
  std::size_t queuedKeyFrames() const override;
  void interruptBundleAdjustment() override { abort_ba_ = true; }

  // Sequential mode: process every queued keyframe now, in the caller's thread.
  void processPending();
  // Threaded mode: block until the queue is empty and the mapper idle.
  void waitUntilIdle();
  // The same for at most `timeout`; returns whether the mapper is idle.
  bool waitUntilIdleFor(std::chrono::microseconds timeout);
  // Stops and joins the thread (idempotent); queued keyframes are processed first.
  void shutdown();

  std::size_t processedKeyFrames() const { return processed_; }
  // While the returned lock is held the mapper processes no keyframe (loop correction).
  // Lock order: outer to Map::updateMutex().
  std::unique_lock<std::mutex> pauseProcessing() { return std::unique_lock(processing_mutex_); }

 private:
  void process(const std::shared_ptr<map::KeyFrame>& keyframe);
  void processLocked(const std::shared_ptr<map::KeyFrame>& keyframe);
  void attachObservations(const std::shared_ptr<map::KeyFrame>& keyframe);
  void cullRecentPoints(const std::shared_ptr<map::KeyFrame>& keyframe);
  void triangulateNewPoints(const std::shared_ptr<map::KeyFrame>& keyframe);
  void fuseWithNeighbours(const std::shared_ptr<map::KeyFrame>& keyframe);
  void localBundleAdjustment(const std::shared_ptr<map::KeyFrame>& keyframe);
  void cullKeyFrames(const std::shared_ptr<map::KeyFrame>& keyframe);

  std::shared_ptr<map::Map> map_;
  track::FrameCamera camera_;
  std::shared_ptr<const feature::ScaleLevels> pyramid_;
  LocalMapperParams params_;

  std::mutex processing_mutex_;  // held while a keyframe is processed
  std::atomic<bool> abort_ba_{false};
  std::atomic<std::size_t> processed_{0};
  std::list<std::shared_ptr<map::MapPoint>> recent_points_;
  core::Stage<std::shared_ptr<map::KeyFrame>> queue_;  // last: its thread uses the above
};

}  // namespace lumaslam::mapping
