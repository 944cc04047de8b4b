#pragma once
// ORB-SLAM-style tracking for RGB-D, stereo and monocular cameras (monocular: two-view
// initialisation, tracker_monocular.cpp): constant-velocity motion model with projection search,
// reference-keyframe fallback, local-map tracking, pose-only optimisation, keyframe decision. Runs
// in the caller's thread; holds Map::updateMutex() for one frame at a time.
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/map/map.h"
#include "lumaslam/track/dynamic_point_memory.h"
#include "lumaslam/track/frame.h"
#include "lumaslam/track/frame_camera.h"
#include "lumaslam/track/frame_relocalizer.h"
#include "lumaslam/track/keyframe_sink.h"
#include "lumaslam/track/monocular_initializer.h"
#include "lumaslam/track/motion_evidence.h"
#include "lumaslam/track/origin_segmentation.h"
#include "lumaslam/track/trajectory_recorder.h"

namespace lumaslam::track {

enum class TrackingState { NotInitialized, Ok, Lost };
const char* toString(TrackingState state);

// The step that gave a frame its pose prior and matches before the local map (docs/tracking.md).
enum class TrackingStep {
  None,
  Initialization,
  MotionModel,
  ReferenceKeyFrame,
  LastPose,
  Relocalization
};
const char* toString(TrackingStep step);

struct TrackerParams {
  int min_initial_features = 500;         // features with depth needed to start a map
  int max_frames_between_keyframes = 30;  // camera fps, as ORB-SLAM
  int min_frames_between_keyframes = 0;
  // Threaded mapping: after a frame that made a keyframe, or wanted one while the mapper was
  // still busy, the Pipeline gives the mapper what is left of the frame interval (the time a
  // camera would have given it) before the next frame. Without that, a run faster than the
  // camera, or on a loaded machine, gets keyframes only every max_frames_between_keyframes:
  // monocular KITTI 07 threaded had 40 keyframes where the sequential run has 126, a third of
  // its inliers, and lost tracking on a loaded machine (docs/tracking.md). The Pipeline sets
  // it for monocular only.
  bool wait_for_busy_mapper = false;
  int min_local_map_inliers = 30;
  // A frame also needs this fraction of the local-map inliers of the recently tracked frames
  // (the median of the last `inlier_reference_frames`), a reference that halves every
  // `inlier_reference_half_life` frames while lost. Camera motion in a static scene never lost
  // 2/3 of the matches from one frame to the next in our runs (lowest 0.67, low-light); a
  // sudden sensor event (x5 over-exposure) keeps ~20 %, matched at displaced places, and gave
  // poses 2-3 cm off with 100 inliers (docs/accuracy.md). The median, not the last frame: on
  // real RGB-D the frame after a keyframe can match its fresh depth points by the hundred
  // (7-Scenes frame 480: 93 -> 822 -> 195), and one such spike must not reject the next frame.
  double min_inlier_fraction_of_last = 1.0 / 3.0;
  int inlier_reference_frames = 5;
  int inlier_reference_half_life = 30;  // frames (the System: camera fps, i.e. one second)
  float motion_search_radius = 7.0F;    // pixels at level 0 (doubled on a second try)
  float local_map_search_radius = 8.0F;
  float lost_search_radius = 40.0F;  // window when trying to recover from the last pose
  int max_local_keyframes = 80;
  MonocularInitParams monocular{};
  int min_initial_monocular_points = 50;  // after the initial bundle adjustment (ORB-SLAM3)
  DynamicMemoryParams dynamic_memory;     // points failing near recent people boxes
  MotionEvidenceParams motion_evidence;   // class-free: residuals of points and feature flow
  // With motion evidence: the first pose of the local-map step uses only the points confirmed
  // static, when at least this many are matched.
  int min_confirmed_points = 50;
  // Atlas (ORB-SLAM3): once tracking has been lost this long (seconds of frame time) and
  // relocalization still fails on a frame that could start a map, a new map starts from it
  // and tracking goes on there; the loop closer merges it when it sees an earlier map again.
  // Negative: stay lost. ORB-SLAM3 waits 3 s; 1 s here, so that a camera covered for a few
  // seconds is back at once when uncovered, while short dropouts (blur, a few dark frames)
  // are still recovered in the same map.
  double new_map_after_s = 1.0;
  // Monocular: when a new map is due, a lost map with fewer keyframes than this is reset (its
  // frames reported lost; ORB-SLAM3: 10) instead of kept: a map lost so soon after its two-view
  // initialisation is likely wrong. RGB-D / stereo keep every map: their poses are true from
  // the first frame.
  int monocular_reset_below_keyframes = 10;
};

struct TrackingOutcome {
  TrackingState state = TrackingState::NotInitialized;
  std::optional<SE3> T_w_c;  // set when tracked
  int inliers = 0;
  bool new_keyframe = false;
  bool relocalized = false;  // recovered from Lost by the relocalizer (not the last-pose search)
  bool new_map = false;      // this frame started a new map of the atlas
  TrackingStep step = TrackingStep::None;  // None when lost
  map::MapId map = 0;                      // the map the frame was tracked in (when tracked)
  int moving_features = 0;                 // features the motion test found moving
  std::vector<cv::Point2f> moving_points;  // where they are (pixels of the tracked image)
  bool keyframe_waits_for_mapper = false;  // a keyframe was due, the mapper was busy
  double motion_evidence_ms = 0.0;         // the motion test's time, with its rigid consensus tests
};

class Tracker {
 public:
  Tracker(std::shared_ptr<map::Map> map, KeyFrameSink& mapper, const FrameCamera& camera,
          std::shared_ptr<const feature::ScaleLevels> pyramid, const TrackerParams& params);

  TrackingOutcome track(Frame frame);

  // While lost, tried after the search around the last pose; null = relocalization off.
  void setRelocalizer(std::shared_ptr<const FrameRelocalizer> relocalizer) {
    relocalizer_ = std::move(relocalizer);
  }

  // A map was loaded into the (empty) map before the first frame (map/map_file.h): tracking
  // starts lost, so the first frame relocalizes in it; unless in localization mode, a new map
  // of the atlas starts after new_map_after_s without relocalization, as after any loss.
  void startInLoadedMap();
  // Localization mode (ORB-SLAM's ActivateLocalizationMode): frames are tracked against the
  // map and relocalized when lost, but make no keyframe and start no map (an empty map stays
  // empty: every frame is lost). Switchable between frames.
  void setLocalizationMode(bool on) { localization_only_ = on; }
  bool localizationMode() const { return localization_only_; }

  TrackingState state() const { return state_; }
  const TrajectoryRecorder& trajectory() const { return recorder_; }
  const Frame& lastFrame() const { return last_; }
  // Map points declared dynamic so far (failed the chi-square test near recent boxes).
  std::size_t dynamicPointCount() const { return dynamic_memory_.dynamicCount(); }
  // Map points the residuals of the recent frames say are moving (MotionEvidence), detector or
  // not, as of the last frame.
  std::size_t movingPointCount() const { return motion_evidence_.dynamicCount(last_.index); }
  bool motionEvidenceOn() const { return motion_evidence_.enabled(); }

 private:
  bool estimatePose(TrackingOutcome& outcome);
  void recordTrackedFrame(TrackingState previous, bool map_started, TrackingOutcome& outcome);
  void recordLostFrame(TrackingState previous);
  void keepAsLastFrame(bool tracked);
  bool initialize();
  bool recoverWhileLost(TrackingOutcome& outcome);
  bool newMapDue() const;
  bool resetDue() const;
  void startNewMap();
  bool initializeMonocular();  // tracker_monocular.cpp
  bool createInitialMonocularMap(const InitialPair& pair);
  void updateLastFrame();
  bool trackWithMotionModel();
  bool trackFromPose(const SE3& T_c_w_prior, float radius);
  bool trackReferenceKeyFrame();
  void poseFromPriorOrPnp();
  bool relocalize();
  bool trackLocalMap(TrackingOutcome& outcome);
  bool enoughInliers() const;
  enum class KeyFrameDecision { No, Now, WhenMapperIdle };
  KeyFrameDecision needNewKeyFrame() const;
  void createNewKeyFrame();

  int searchLastFrame(float radius);
  int searchReferencePoints(float radius);
  int searchLocalPoints();
  int optimizeCurrentPose(const std::vector<bool>* use = nullptr, int rounds = 0);
  void optimizeConfirmedPointsFirst();
  int discardOutliers();
  void cullDynamicPoints();
  void excludeMovingPoints(TrackingOutcome& outcome);
  bool leftOutOfPose(const map::MapPoint& point, std::size_t feature) const;
  void testRigidity();
  void segmentAgainstMapOrigin();
  std::vector<bool> confirmedStaticMatches() const;
  void joinMatchesThatFit(const std::vector<bool>& trusted, int trusted_count);
  std::vector<bool> notRigidlyBroken() const;
  void updateLocalMap();
  std::shared_ptr<map::MapPoint> newPointFromDepth(std::size_t i,
                                                   const std::shared_ptr<map::KeyFrame>& kf);

  std::shared_ptr<map::Map> map_;
  KeyFrameSink& mapper_;
  FrameCamera camera_;
  std::shared_ptr<const feature::ScaleLevels> pyramid_;
  TrackerParams params_;
  cv::Rect2f bounds_;

  TrackingState state_ = TrackingState::NotInitialized;
  Frame current_;
  Frame last_;
  SE3 last_T_l_r_ = SE3::Identity();  // last frame relative to its reference keyframe
  std::optional<SE3> velocity_;       // T_current_last
  std::shared_ptr<map::KeyFrame> reference_;
  std::shared_ptr<map::KeyFrame> last_keyframe_;
  std::size_t last_keyframe_frame_ = 0;
  std::vector<std::shared_ptr<map::KeyFrame>> local_keyframes_;
  std::vector<std::shared_ptr<map::MapPoint>> local_points_;
  std::vector<std::shared_ptr<map::MapPoint>> temporary_points_;  // last frame's VO points
  int inliers_ = 0;
  std::deque<int> recent_inliers_;  // local-map inliers of the last tracked frames; none yet
  int inlierReference() const;      // their median, 0 when there are none
  std::size_t last_tracked_frame_ = 0;
  std::optional<double> lost_since_;  // timestamp of the first frame of the current loss
  map::MapId active_map_ = 0;         // the map new keyframes start in (follows merges)
  DynamicPointMemory dynamic_memory_;
  MotionEvidence motion_evidence_;
  RigidVerdict rigidity_;  // of current_'s matches as they are now (rigid_consensus.h)
  // The first keyframe of the map made from depth (RGB-D, stereo): origin_segmentation.h.
  std::shared_ptr<const map::KeyFrame> depth_map_origin_;
  RigidVerdict origin_verdict_;  // this frame's, from segmentAgainstMapOrigin
  double rigidity_ms_ = 0.0;     // this frame's rigid consensus tests, part of motion_evidence_ms
  bool localization_only_ = false;
  TrajectoryRecorder recorder_;
  std::unique_ptr<MonocularInitializer> monocular_initializer_;
  std::shared_ptr<const FrameRelocalizer> relocalizer_;
};

}  // namespace lumaslam::track
