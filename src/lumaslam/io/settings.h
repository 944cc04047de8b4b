#pragma once
// Typed settings of a run, read from one ORB-SLAM3-compatible %YAML:1.0 file (docs/settings.md).
// Both the old ORB-SLAM2 keys (Camera.fx, Camera.bf, DepthMapFactor, ThDepth) and the ORB-SLAM3
// "File.version 1.0" keys (Camera1.fx, Stereo.b, Stereo.T_c1_c2, RGBD.DepthMapFactor) are read.
// Modules with their own sections (ORBextractor.* by feature::OrbSettings, Enhancement.*,
// Detector.*) parse them from `file`, each in one place.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "lumaslam/core/pose.h"
#include "lumaslam/core/settings_file.h"

namespace lumaslam::io {

enum class SensorType { Monocular, Stereo, Rgbd };
// Pinhole: radial-tangential distortion, stereo pairs need rectification (Camera2 + T_c1_c2).
// Rectified: undistorted, row-aligned stereo pair (KITTI); only camera 1 and Stereo.b are read.
enum class CameraModel { Pinhole, Rectified };

std::string_view toString(SensorType sensor);  // "mono", "stereo", "rgbd"
std::string_view toString(CameraModel model);  // "PinHole", "Rectified"

struct ImageSize {
  int width = 0;
  int height = 0;
  friend bool operator==(const ImageSize&, const ImageSize&) = default;
};

struct CameraSettings {
  CameraModel model = CameraModel::Pinhole;
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  // OpenCV order k1, k2, p1, p2, k3 (radial-tangential), all zero for Rectified.
  std::array<double, 5> distortion{};
  ImageSize size;                     // size of the images as read from the dataset
  std::optional<ImageSize> resizeTo;  // Camera.newWidth/newHeight: images are resized first
  double fps = 30.0;
  // Camera.RGB: colour images handed to the System API are RGB (1) or BGR (0, default, as
  // ORB-SLAM3). Image files are decoded by OpenCV in BGR whatever the key says.
  bool rgb = false;

  bool hasDistortion() const;
  // The calibration of the images after the optional resize (intrinsics scaled, resizeTo
  // cleared); distortion is unchanged because it acts on normalised coordinates.
  CameraSettings atWorkingSize() const;
};

struct StereoSettings {
  double baseline = 0.0;  // metres (Stereo.b, or Camera.bf / fx, or |t| of T_c1_c2)
  // Stereo.T_c1_c2: pose of camera 2 in camera 1 (maps camera-2 points into camera 1).
  // Identity rotation with t = (baseline, 0, 0) for a Rectified pair.
  SE3 T_c1_c2 = SE3::Identity();
  // Camera2.*: only for an unrectified (Pinhole) pair; rectify with camera::StereoRectifier.
  std::optional<CameraSettings> right;
};

struct DepthSettings {
  // RGB-D only: raw depth value / depthMapFactor = metres (5000 for TUM 16-bit PNGs).
  double depthMapFactor = 1.0;
  // Close/far threshold in baselines (ORB-SLAM "ThDepth"); see Settings::closeDepth().
  double thDepth = 40.0;
};

struct SystemSettings {
  bool sequential = false;  // System.sequential: run every stage in the caller's thread
  // System.newMapAfter: seconds lost before a frame that cannot be relocalized starts a new
  // map (Atlas, docs/tracking.md); negative: stay lost instead.
  double newMapAfter = 1.0;
  // System.datasetRoot: default dataset folder, relative paths resolved against the
  // settings file's folder. Empty when not set.
  std::filesystem::path datasetRoot;
};

struct LoopSettings {
  // Loop.vocabulary: place-recognition vocabulary (our binary or DBoW2 text, e.g. ORBvoc.txt)
  // for relocalization and loop closing; relative paths resolved against the settings
  // file's folder; "none" kept as is (no vocabulary). Empty when not set: the System loads
  // the default vocabulary (loop/vocabulary_choice.h).
  std::filesystem::path vocabulary;
  // Loop.closing: close loops (own thread) when a vocabulary is given (default 1).
  bool closing = true;
};

struct DynamicSettings {
  // Dynamic.motionEvidence: class-free motion test of tracking (track/motion_evidence.h):
  // map points whose residuals say they move leave pose estimation, moving features make no
  // map point. Unset: on for RGB-D, off for stereo and monocular (docs/dynamic.md says why).
  std::optional<bool> motionEvidence;
  bool motionEvidenceFor(SensorType sensor) const {
    return motionEvidence.value_or(sensor == SensorType::Rgbd);
  }
};

struct Settings {
  SensorType sensor = SensorType::Monocular;
  CameraSettings camera;  // camera 1 (left camera for stereo, colour camera for RGB-D)
  // Stereo and RGB-D only (RGB-D: the IR projector baseline, for the virtual right
  // coordinate u_r = u - bf / z); nullopt for monocular.
  std::optional<StereoSettings> stereo;
  DepthSettings depth;
  SystemSettings system;
  LoopSettings loop;
  DynamicSettings dynamic;
  // The whole file, for modules that read their own sections (ORBextractor.*, Enhancement.*,
  // Detector.*).
  std::shared_ptr<const core::SettingsFile> file;
  std::filesystem::path path;  // empty when read from a string

  double baseline() const { return stereo ? stereo->baseline : 0.0; }
  // Baseline times fx ("Camera.bf"); for an unrectified pair this uses camera 1's fx, the
  // rectified value comes from camera::StereoRectifier.
  double bf() const { return baseline() * camera.atWorkingSize().fx; }
  // Depth in metres below which a stereo/RGB-D point is "close" (ThDepth * baseline).
  double closeDepth() const { return depth.thDepth * baseline(); }

  // One line for logs: "stereo, PinHole 752x480 @20 Hz, fx=458.654 ..., b=0.110 m, ...".
  std::string summary() const;

  // Parses and checks every key this struct holds; throws Error naming file, key and value.
  // The sensor is `sensor` when given (e.g. a CLI flag), else System.sensor, else inferred
  // from the keys present (docs/settings.md).
  static Settings fromFile(std::shared_ptr<const core::SettingsFile> file,
                           std::optional<SensorType> sensor = std::nullopt);
  static Settings fromFile(const core::SettingsFile& file,
                           std::optional<SensorType> sensor = std::nullopt);
};

// System.sensor, System.sequential and System.newMapAfter as settings lines that fromFile reads
// back (`lumaslam run --print-settings`); System.datasetRoot is not printed.
std::string printSystemSettings(SensorType sensor, const SystemSettings& system);

// Opens `path` and parses it; a relative System.datasetRoot or Loop.vocabulary is resolved
// against its folder.
Settings loadSettings(const std::filesystem::path& path,
                      std::optional<SensorType> sensor = std::nullopt);

}  // namespace lumaslam::io
