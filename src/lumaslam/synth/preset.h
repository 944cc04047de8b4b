#pragma once
// Named synthetic sequences, each built to test one thing (docs/synthetic.md describes them).
#include <string>
#include <string_view>
#include <vector>

#include "lumaslam/synth/camera_rig.h"
#include "lumaslam/synth/depth_sensor.h"
#include "lumaslam/synth/lighting.h"
#include "lumaslam/synth/trajectory.h"

namespace lumaslam::synth {

struct Preset {
  std::string name;
  std::string description;
  SensorKind sensor = SensorKind::Rgbd;
  TrajectoryKind trajectory = TrajectoryKind::Xyz;
  int frames = 300;
  double motion_speed = 1.0;  // >1 plays the trajectory faster
  int walkers = 0;
  // Walkers stay in the camera's (rotating) view instead of crossing a fixed spot: see
  // SceneOptions::walkers_follow_view.
  bool walkers_follow_view = false;
  // People who stay put (TUM fr3 sitting_*): see SceneOptions::walkers_sitting.
  bool walkers_sitting = false;
  int moving_boxes = 0;
  bool spotlight = false;
  LightingSchedule lighting;
  double readout_ms = 0.0;  // rolling shutter of every camera (see rolling_shutter.h), 0 = global
  DepthSensorModel depth;   // RGB-D only

  Rig rig() const {
    Rig r = sensor == SensorKind::Stereo ? eurocStereoRig() : tumRgbdRig();
    r.readout_ms = readout_ms;
    return r;
  }
};

const std::vector<Preset>& allPresets();
// Throws Error naming the unknown preset and listing the known ones.
const Preset& findPreset(std::string_view name);
std::string presetNames();  // comma-separated

}  // namespace lumaslam::synth
