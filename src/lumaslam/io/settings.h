#pragma once
// Typed settings of a run, read from one ORB-SLAM3-compatible %YAML:1.0 file (docs/settings.md).
// Both the old ORB-SLAM2 keys (Camera.fx, Camera.bf, DepthMapFactor, ThDepth) and the ORB-SLAM3
// "File.version 1.0" keys (Camera1.fx, Stereo.b, Stereo.T_c1_c2, RGBD.DepthMapFactor) are read.
// Modules with their own sections (ORBextractor.* by feature::OrbSettings, Enhancement.*,
// Detector.*) parse them from `file`, each in one place.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "lumaslam/camera/camera_settings.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/core/settings_file.h"

namespace lumaslam::io {

enum class SensorType { Monocular, Stereo, Rgbd };
std::string_view toString(SensorType sensor);  // "mono", "stereo", "rgbd"

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
  camera::CameraSettings camera;  // camera 1 (left camera for stereo, colour camera for RGB-D)
  // Stereo and RGB-D only (RGB-D: the IR projector baseline, for the virtual right
  // coordinate u_r = u - bf / z); nullopt for monocular.
  std::optional<camera::StereoSettings> stereo;
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
  // The file's name for messages: its origin when read from text, else its path.
  std::string origin() const { return file ? file->origin() : path.string(); }

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
