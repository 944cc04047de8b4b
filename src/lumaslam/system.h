#pragma once
// The public API (docs/api.md), in the style of stella_vslam's system.h: build a System from a
// settings file, feed it frames, get poses back. It includes no internal header; the library
// behind it is lumaslam::lumaslam (find_package(lumaslam CONFIG)). Errors are thrown as
// std::runtime_error with a message naming the file, key or value that was wrong.
//
// Thread safety: every member function may be called from any thread; calls are serialised
// by one mutex inside the System (a trackX call in one thread makes saveMap in another wait for
// the frame to finish). Local mapping, loop closing and detection run in the System's own
// threads, and a stereo frame's right image (and the monocular initialisation's homography) in
// helper jobs that finish within the frame's call, unless SystemConfig::sequential: then every
// stage runs in the calling thread. Different System objects share nothing.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "lumaslam/camera_pose.h"
#include "lumaslam/export.h"

namespace lumaslam {

enum class Sensor { Monocular, Stereo, Rgbd };
enum class TrackState { NotInitialized, Tracking, Lost };
LUMASLAM_API const char* toString(Sensor sensor);
LUMASLAM_API const char* toString(TrackState state);

// What a caller may change over the settings file; unset keeps the file's choice.
struct SystemConfig {
  std::optional<std::string> enhancement;  // Enhancement.preset: "off", "paper", "fused", ...
  std::optional<bool> sequential;          // run every stage in the caller's thread
  std::optional<std::string> detector;     // "yolo:MODEL.onnx", "boxes:FILE" or "none"
  // A vocabulary file for relocalization and loop closing, or "none"; unset: Loop.vocabulary,
  // else the default vocabulary installed with the library.
  std::optional<std::filesystem::path> vocabulary;
  std::optional<bool> loop_closing;
  std::optional<bool> motion_evidence;  // Dynamic.motionEvidence
  bool strict_settings = false;         // unknown settings keys are an error, not a warning
};

// The outcome of one frame.
struct TrackResult {
  std::size_t frame = 0;  // numbered by the System from 0, across reset()
  double timestamp = 0.0;
  TrackState state = TrackState::NotInitialized;
  std::optional<Eigen::Matrix4d> T_w_c;  // camera-to-world, set when tracked
  int inliers = 0;                       // map points the pose rests on
  bool keyframe = false;                 // the frame became a keyframe
  bool relocalized = false;              // recovered from Lost in a known map
  bool new_map = false;                  // started a new map of the atlas
  std::size_t map = 0;                   // the map it was tracked in
  double time_ms = 0.0;                  // this call's wall time
};

class LUMASLAM_API System {
 public:
  // Reads the settings file (ORB-SLAM3-style YAML, docs/settings.md); its sensor decides which
  // trackX call is allowed.
  explicit System(const std::filesystem::path& settings_file, const SystemConfig& config = {});
  ~System();
  System(const System&) = delete;
  System& operator=(const System&) = delete;
  System(System&&) noexcept;
  System& operator=(System&&) noexcept;

  Sensor sensor() const;

  // Images: 8-bit gray, or colour in the order the settings' Camera.RGB names: BGR (0, the
  // default; cv::imread and lumaslam::Dataset give BGR) or RGB (1; converted to BGR). Depth: CV_16U
  // raw (divided by the settings' DepthMapFactor) or CV_32F metres. Timestamps in seconds, finite
  // and increasing. The images are not kept after the call returns. Calling the trackX of another
  // sensor is an error.
  TrackResult trackMonocular(const cv::Mat& image, double timestamp);
  TrackResult trackStereo(const cv::Mat& left, const cv::Mat& right, double timestamp);
  TrackResult trackRgbd(const cv::Mat& image, const cv::Mat& depth, double timestamp);

  // Map files (docs/maps.md). saveMap first lets local mapping and loop closing handle every
  // queued keyframe, so the file holds all frames tracked so far; tracking goes on after it
  // (save as often as wanted). loadMap only before the first
  // frame; the file must have been made with this camera, ORB settings and vocabulary.
  void saveMap(const std::filesystem::path& file);
  void loadMap(const std::filesystem::path& file);

  // Localization mode: track against the map, relocalize when lost, add no keyframes.
  void setLocalizationMode(bool on);
  bool localizationMode() const;

  // Drops the map and starts afresh with the same settings; localization mode turns off.
  void reset();
  // Finishes local mapping and loop closing and stops their threads; idempotent, also done by
  // the destructor. Poses stay readable; trackX after it is an error.
  void shutdown();

  // Tracked frames of the main map (poses refined by mapping and loop closing) and its
  // keyframes, in the camera as calibrated. Read after shutdown() for the final poses.
  CameraTrajectory trajectory() const;
  CameraTrajectory keyframeTrajectory() const;
  std::size_t frameCount() const;  // frames fed since construction
  std::size_t keyframeCount() const;
  std::size_t mapPointCount() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lumaslam
