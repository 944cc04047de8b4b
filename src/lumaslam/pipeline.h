#pragma once
// The internal facade the CLI, tests and the public System (system.h) use: feed frames, get
// poses. Owns the map, the tracker (runs in the caller's thread), the local mapper, the loop
// closer and the detection worker (own threads, or inline when System.sequential, which also
// runs the per-frame side jobs inline). Not installed: embed lumaslam through system.h.
#include <chrono>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/core/pose.h"
#include "lumaslam/feature/orb_settings.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/map/map_file.h"
#include "lumaslam/track/tracker.h"

namespace lumaslam {

namespace camera {
class StereoRectifier;
}
namespace detect {
class DetectionWorker;
struct DetectorParams;
}  // namespace detect
namespace enhance {
class Enhancer;
struct EnhancementPlan;
}  // namespace enhance
namespace io {
struct FrameData;
}
namespace loop {
class LoopCloser;
class PlaceRecognition;
}  // namespace loop
namespace mapping {
class LocalMapper;
}
namespace track {
class FrameBuilder;
}

struct PipelineOptions {
  std::optional<std::string> enhance_preset;  // overrides Enhancement.preset ("off" disables)
  std::optional<bool> sequential;             // overrides System.sequential
  // Overrides the Detector.* choice: "yolo:MODEL.onnx", "boxes:FILE" or "none".
  std::optional<std::string> detector;
  // Overrides Loop.vocabulary: a vocabulary file for relocalization and loop closing, or
  // "none". Neither set: the default vocabulary (loop/vocabulary_choice.h).
  std::optional<std::filesystem::path> vocabulary;
  std::optional<bool> loop_closing;     // overrides Loop.closing (needs a vocabulary)
  std::optional<bool> motion_evidence;  // overrides Dynamic.motionEvidence
  // Settings keys nothing reads (typos, e.g. Enhancement.presett) are a warning naming the
  // closest known key; with strict_settings an Error.
  bool strict_settings = false;
};

struct FrameTiming {  // milliseconds
  double enhance = 0, features = 0, tracking = 0, mapping = 0, total = 0;
  double detection_wait = 0;  // tracking thread blocked on this frame's boxes
  double detection = 0;       // detector thread's work on this frame (inference or propagation)
  double enhance_ahead = 0;   // the part of `enhance` done by prepareAhead(), before track()
};

// One frame as the sensor delivered it. Which fields are needed depends on Settings::sensor.
struct SensorFrame {
  std::size_t index = 0;
  double timestamp = 0.0;
  cv::Mat image;         // left / rgb / mono: 8-bit gray or BGR
  cv::Mat right;         // stereo: right image, same size and type as `image`
  cv::Mat depth;         // RGB-D: CV_16U raw (divided by DepthMapFactor) or CV_32F metres
  cv::Mat dynamic_mask;  // optional CV_8U in `image`'s pixels (rectified with it), nonzero where
                         // features must not be taken
};

// A dataset frame as the sensor input (image, right, depth; no mask).
SensorFrame toSensorFrame(const io::FrameData& frame);

struct FrameResult {
  track::TrackingOutcome outcome;
  FrameTiming timing;
  std::vector<cv::Rect2f> dynamic_boxes;      // this frame's detections (when a detector runs)
  std::vector<cv::Point2f> dropped_features;  // keypoints removed by the dynamic mask
  // What the front end saw (for a viewer): the gray image features were taken from (enhanced
  // when enhancement is on; the rectified left image for stereo), the keypoints it kept, and
  // the dynamic mask made from this frame's boxes (empty without boxes).
  cv::Mat feature_image;
  std::vector<cv::Point2f> kept_features;
  cv::Mat dynamic_mask;
  // The camera centre in the map's world (for a rectified pair the rectified camera's world,
  // where outcome.T_w_c is converted back to the calibrated camera's).
  std::optional<Eigen::Vector3d> centre_in_map;
};

class Pipeline {
 public:
  explicit Pipeline(const io::Settings& settings, const PipelineOptions& options = {});
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  // Tracks one frame of the configured sensor. Throws Error for input the sensor cannot use
  // (missing depth / right image, wrong size or type). An unrectified stereo pair (Camera2.*)
  // is rectified first and tracked in the rectified left camera. Stereo timing: `enhance` is
  // the work of both images (the right one runs beside the left), `features` the rest of the
  // front end (rectification, both extractions, stereo matching) in wall time.
  FrameResult track(const SensorFrame& frame);

  // Reading ahead (`lumaslam run`): a coming frame's images are enhanced and handed to the
  // detector now, so that its detection runs while the frames before it are tracked instead of
  // while the tracker waits for it; track() of that frame then takes them. At most two frames
  // ahead, in increasing index order. Monocular and RGB-D with a
  // detector only (otherwise nothing to overlap). The results are those of tracking without it
  // (the enhancer sees the same images in the same order); input that track() would refuse is
  // left for track() to refuse.
  void prepareAhead(const SensorFrame& next);

  // RGB-D shorthand for track().
  FrameResult trackRgbd(std::size_t index, double timestamp, const cv::Mat& image,
                        const cv::Mat& depth, const cv::Mat& dynamic_mask = cv::Mat());

  // Waits for local mapping to finish and stops its thread. Idempotent; the destructor calls it.
  // track() after it is an Error.
  void shutdown();

  // Map files (map/map_file.h, docs/maps.md); both throw Error naming the file and the problem.
  // saveMap waits until local mapping and loop closing have handled every queued keyframe
  // (and a running global BA is written back), then writes the atlas atomically; tracking can
  // go on after it. loadMap only before the first frame: the map must be empty, the file made with
  // this camera, ORB settings and vocabulary; tracking then starts lost, so that the first
  // frame relocalizes in the loaded map.
  void saveMap(const std::filesystem::path& file);
  void loadMap(const std::filesystem::path& file);
  // Track against the map without adding keyframes or maps (Tracker::setLocalizationMode).
  void setLocalizationMode(bool on);
  bool localizationMode() const;
  // What a map file made by this Pipeline records of its settings (camera, ORB, vocabulary).
  map::MapFingerprint mapFingerprint() const;

  // Poses of the left / rgb camera as calibrated (for a rectified pair, converted back from
  // the rectified camera): T_w_c, world = that camera at the first keyframe.
  // Tracked frames of the main map: the map of the atlas with most frames (with one map, every
  // tracked frame). Frames of maps never merged into it are in mapTrajectories() only.
  Trajectory frameTrajectory() const;
  std::map<map::MapId, Trajectory> mapTrajectories() const;  // every map's tracked frames
  map::MapId mainMap() const;
  Trajectory keyFrameTrajectory() const;  // keyframes of the main map
  std::size_t keyFrameCount() const;
  std::size_t mapPointCount() const;
  // The atlas, for readers in other threads (a viewer); its own locks make reads safe.
  std::shared_ptr<const map::Map> map() const { return map_; }
  const track::Tracker& tracker() const { return *tracker_; }
  // Vocabulary + keyframe database, shared by relocalization and loop closing; null without a
  // vocabulary ("none", or no default vocabulary found): relocalization off.
  std::shared_ptr<loop::PlaceRecognition> placeRecognition() const { return places_; }
  // Null when loop closing is off (no vocabulary, Loop.closing 0 or --no-loop-closing).
  const loop::LoopCloser* loopCloser() const { return loop_closer_.get(); }
  const io::Settings& settings() const { return settings_; }
  // ORBextractor.* as the feature extractor uses them (read once, by feature::OrbSettings).
  const feature::OrbSettings& orbSettings() const;
  // The camera tracking works in (the rectified one for an unrectified stereo pair).
  const track::FrameCamera& frameCamera() const;
  // True for an unrectified stereo pair: keypoints are in the rectified left image's pixels.
  bool rectifiesStereo() const { return rectifier_ != nullptr; }
  // "none", "yolo MODEL" or "box_file FILE".
  const std::string& detectorDescription() const { return detector_description_; }
  // The vocabulary file in use, or "none".
  const std::string& vocabularyDescription() const { return vocabulary_description_; }

 private:
  // The constructor's steps, in order.
  void setUpStereoRectification();
  void setUpEnhancement(const PipelineOptions& options);
  void setUpDetector(const PipelineOptions& options);
  void setUpPlaceRecognition(const PipelineOptions& options);
  void setUpStages(const track::FrameCamera& camera, const PipelineOptions& options);

  struct Images {
    cv::Mat gray;      // for ORB features
    cv::Mat detector;  // for the detector: raw or enhanced colour (Detector.image)
  };
  // A frame's images and depth, enhanced and pushed to the detector by prepareAhead().
  struct PreparedFrame {
    std::size_t index = 0;
    Images images;
    cv::Mat depth_m;
    double enhance_ms = 0.0;
  };
  PreparedFrame prepareFrame(const SensorFrame& input, FrameTiming& timing);
  PreparedFrame preparedFrame(const SensorFrame& input, FrameTiming& timing);
  void finishQueuedMapWork();
  void waitForBusyMapper(double timestamp, std::chrono::steady_clock::time_point frame_start);
  // With `plan`, the image is enhanced with it instead of its own (stereo shared plans).
  Images prepareImages(const cv::Mat& image, FrameTiming& timing,
                       const enhance::EnhancementPlan* plan = nullptr);
  cv::Mat depthInMetres(const SensorFrame& frame) const;
  cv::Mat rightGray(const cv::Mat& image, FrameTiming& timing,  // stereo right image
                    const enhance::EnhancementPlan* left_plan = nullptr);
  track::Frame buildStereoFrame(const SensorFrame& frame, FrameResult& result);
  SE3 toCalibratedCamera(const SE3& T_w_c) const;  // identity unless rectifying
  Trajectory toCalibratedCamera(Trajectory trajectory) const;
  cv::Mat extractionMask(const cv::Mat& given) const;
  void pushForDetection(const SensorFrame& input, const cv::Mat& detector_image);
  track::Frame withoutDynamicFeatures(const SensorFrame& input, const cv::Mat& depth_m,
                                      FrameResult& result,
                                      const std::function<track::Frame()>& build);
  void removeDynamicFeatures(track::Frame& frame, const cv::Mat& depth_m, FrameResult& result);

  io::Settings settings_;
  feature::OrbSettings orb_settings_;  // ORBextractor.*, defaults without a settings file
  bool sequential_ = false;
  std::shared_ptr<map::Map> map_;
  std::shared_ptr<loop::PlaceRecognition> places_;  // the Map's KeyFrameIndex
  std::unique_ptr<loop::LoopCloser> loop_closer_;   // fed by the local mapper
  std::unique_ptr<enhance::Enhancer> enhancer_;
  std::unique_ptr<enhance::Enhancer> right_enhancer_;   // stereo "independent": the right's own
  std::unique_ptr<camera::StereoRectifier> rectifier_;  // unrectified stereo pairs only
  std::unique_ptr<detect::DetectorParams> detector_params_;
  std::unique_ptr<detect::DetectionWorker> detector_;
  std::string detector_description_ = "none";
  std::string vocabulary_description_ = "none";
  std::uint64_t vocabulary_fingerprint_ = 0;  // loop::vocabularyFingerprint, 0 without one
  bool shut_down_ = false;
  std::optional<double> previous_timestamp_;  // of the last tracked frame (any outcome)
  cv::Mat previous_dynamic_mask_;     // the last frame's mask from its boxes (extraction budget)
  std::deque<PreparedFrame> ahead_;   // prepareAhead()'s frames, until track() takes them
  bool wait_for_busy_mapper_ = true;  // TrackerParams::wait_for_busy_mapper
  std::unique_ptr<track::FrameBuilder> frame_builder_;
  std::unique_ptr<mapping::LocalMapper> mapper_;
  std::unique_ptr<track::Tracker> tracker_;
};

}  // namespace lumaslam
