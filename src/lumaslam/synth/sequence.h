#pragma once
// A synthetic sequence in memory: scene + trajectory + lighting plan for a preset and seed.
// render(i) is const, thread-safe and a pure function of (preset, seed, options, i).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/core/pose.h"
#include "lumaslam/synth/depth_sensor.h"
#include "lumaslam/synth/lighting.h"
#include "lumaslam/synth/preset.h"
#include "lumaslam/synth/renderer.h"
#include "lumaslam/synth/rolling_shutter.h"
#include "lumaslam/synth/scene.h"
#include "lumaslam/synth/trajectory.h"

namespace lumaslam::synth {

// Overrides of a preset's defaults.
struct SynthOptions {
  std::optional<int> walkers;
  std::optional<int> moving_boxes;
  std::optional<int> dark_level;
  bool motion_blur = true;
  bool sensor_noise = true;
  bool depth_noise = true;         // Kinect-like noise and holes in sensor_depth
  bool rolling_shutter = true;     // the preset's rolling shutter (false: global shutter)
  bool depth_misalignment = true;  // the preset's depth/colour misregistration and time offsets
  std::vector<std::filesystem::path> texture_images;  // posters (throws if one is unreadable)
  std::vector<PersonImage> people;  // walker photos (see SceneOptions::people); empty = procedural
};

struct ObjectBox {
  std::string class_name;  // "person" or "box"
  int object_id = 0;
  cv::Rect box;  // tight box around the object's visible pixels
};

struct CameraFrame {
  cv::Mat image;  // CV_8UC3 BGR
  cv::Mat depth;  // CV_32F true z-depth in metres
  cv::Mat mask;   // CV_8U, 255 on dynamic objects
  std::vector<ObjectBox> boxes;
  SE3 T_w_c;
};

struct Frame {
  int index = 0;
  std::int64_t timestamp_ns = 0;  // colour (cam0) stamp; with a rolling shutter, of its middle rows
  double timestamp() const { return static_cast<double>(timestamp_ns) * 1e-9; }
  std::int64_t depth_timestamp_ns = 0;  // RGB-D: when sensor_depth was captured
  FrameExposure exposure;
  CameraFrame cam0;                 // rgb (RGB-D) or left (stereo)
  std::optional<CameraFrame> cam1;  // right (stereo)
  cv::Mat sensor_depth;             // RGB-D: Kinect-like depth in metres, 0 = hole
};

class SequenceRenderer {
 public:
  SequenceRenderer(const Preset& preset, int frames, std::uint64_t seed,
                   const SynthOptions& options = {});

  Frame render(int index) const;

  const Preset& preset() const { return preset_; }
  const Rig& rig() const { return rig_; }
  const Scene& scene() const { return scene_; }
  const CameraTrajectory& trajectory() const { return trajectory_; }
  int frameCount() const { return frames_; }
  std::uint64_t seed() const { return seed_; }
  std::int64_t timestampNs(int index) const;
  // RGB-D: the depth frame's stamp, timestampNs plus the preset's per-frame stream offset.
  std::int64_t depthTimestampNs(int index) const;
  const DepthSensorModel& depthModel() const { return depth_model_; }
  // Trajectory time (trajectory().pose, scene().at) of a frame timestamp.
  double secondsFromStart(std::int64_t timestamp_ns) const;
  // cam0 pose at an absolute timestamp (seconds, same clock as the frames).
  SE3 poseAt(double timestamp) const;
  const FrameExposure& exposure(int index) const;

 private:
  // Poses of the rows of camera c (T_c0_c in the rig) for a frame at t (seconds from start).
  RowPoses rowPosesAt(double t, const SE3& T_c0_c) const;
  RenderedView renderAt(double t, const SE3& T_c0_c) const;
  cv::Mat blurred(const RenderedView& view, int index, double t, const SE3& T_c0_c) const;
  CameraFrame exposeCamera(int index, int camera, const RenderedView& view, const SE3& T_w_c,
                           const cv::Mat& radiance) const;
  cv::Mat sensorDepth(int index, const RenderedView& colour_view) const;

  Preset preset_;
  Rig rig_;
  int frames_;
  std::uint64_t seed_;
  SynthOptions options_;
  std::int64_t start_ns_;
  CameraTrajectory trajectory_;
  Scene scene_;
  std::vector<FrameExposure> exposures_;
  DepthSensorModel depth_model_;
};

// Convenience: render `frames` frames of the named preset and write the dataset to `out`
// (TUM RGB-D layout for *-rgbd presets, EuRoC ASL for *-stereo). frames <= 0: preset default.
// `progress` (dataset_writer.h's FrameProgress) is told after every frame.
void writeSequence(const std::filesystem::path& out, const std::string& preset, int frames,
                   std::uint64_t seed, const SynthOptions& options = {},
                   const std::function<void(int done, int total)>& progress = {});

}  // namespace lumaslam::synth
