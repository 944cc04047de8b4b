#include "lumaslam/synth/preset.h"

#include "lumaslam/core/error.h"

namespace lumaslam::synth {

namespace {

Preset make(std::string name, std::string description, SensorKind sensor, TrajectoryKind trajectory,
            int frames) {
  Preset p;
  p.name = std::move(name);
  p.description = std::move(description);
  p.sensor = sensor;
  p.trajectory = trajectory;
  p.frames = frames;
  return p;
}

// Dark + long exposures (blur) + high gain (noise) + AirSLAM darkening: what breaks trackers.
LightingSchedule darkLighting(int dark_level) {
  LightingSchedule l;
  l.light_start = 0.06;
  l.light_end = 0.03;
  l.dark_level = dark_level;
  return l;
}

// A Kinect v1 as in TUM's fr1 sequences: every depth imperfection that matters for tracking.
DepthSensorModel kinectV1Depth() {
  DepthSensorModel d;
  d.min_ir_albedo = 0.02f;
  d.max_incidence_deg = 80.0f;
  d.grazing_noise = true;
  d.quantize_disparity = true;
  d.registration_shift_px = {1.4f, 0.8f};
  d.registration_scale = 1.003f;  // +-1 px more at the image corners
  d.max_time_offset_ms = 15.0;
  return d;
}

// A data table, one entry per preset (kept as one function, longer than 80 lines).
std::vector<Preset> buildPresets() {
  using enum SensorKind;
  using enum TrajectoryKind;
  std::vector<Preset> presets;
  presets.push_back(make("static-rgbd", "nearly still RGB-D camera, static scene (sanity baseline)",
                         Rgbd, Static, 300));
  presets.push_back(make("xyz-rgbd", "RGB-D translation shake, static scene (like TUM fr1/fr3 xyz)",
                         Rgbd, Xyz, 300));
  presets.push_back(make("rpy-rgbd", "RGB-D fast roll/pitch/yaw, static scene (like TUM fr1 rpy)",
                         Rgbd, Rpy, 300));
  presets.push_back(make("halfsphere-rgbd", "RGB-D moving over a half sphere, static scene", Rgbd,
                         Halfsphere, 300));
  presets.push_back(
      make("loop-rgbd", "RGB-D lap around the room that returns to its start", Rgbd, Loop, 600));

  Preset p =
      make("walking-static-rgbd",
           "still RGB-D camera, two people walking through the view (TUM fr3 walking_static)", Rgbd,
           Static, 300);
  p.walkers = 2;
  presets.push_back(p);
  p = make("walking-xyz-rgbd",
           "RGB-D xyz shake, two people and a moving box crossing the view (TUM fr3 walking_xyz)",
           Rgbd, Xyz, 300);
  p.walkers = 2;
  p.moving_boxes = 1;
  presets.push_back(p);
  p = make("walking-rpy-rgbd",
           "RGB-D fast rotations, two people walking within the turning view (TUM fr3 walking_rpy)",
           Rgbd, Rpy, 300);
  p.walkers = 2;
  p.walkers_follow_view = true;
  presets.push_back(p);
  p = make("walking-halfsphere-rgbd",
           "RGB-D half sphere, three people walking (TUM fr3 walking_halfsphere)", Rgbd, Halfsphere,
           300);
  p.walkers = 3;
  presets.push_back(p);
  p = make(
      "sitting-xyz-rgbd",
      "RGB-D xyz shake, two people sitting in view and shifting a few cm (TUM fr3 sitting_xyz)",
      Rgbd, Xyz, 300);
  p.walkers = 2;
  p.walkers_sitting = true;
  presets.push_back(p);

  p = make("flash-rgbd",
           "RGB-D xyz with sudden exposure jumps (x3 over-exposed, x0.2 dark) for a few frames",
           Rgbd, Xyz, 300);
  p.lighting.jumps = {{40, 3, 3.0}, {100, 4, 0.2}, {160, 2, 3.0}, {220, 3, 0.2}, {270, 3, 3.0}};
  presets.push_back(p);
  p = make("flicker-rgbd", "RGB-D xyz under flickering light (+-35% at an apparent 1.7 Hz)", Rgbd,
           Xyz, 300);
  p.lighting.flicker_amplitude = 0.35;
  p.lighting.flicker_hz = 1.7;
  presets.push_back(p);
  p = make("spotlight-rgbd",
           "RGB-D xyz in a dim room lit by a sweeping spotlight (non-uniform light)", Rgbd, Xyz,
           300);
  p.spotlight = true;
  presets.push_back(p);
  p = make(
      "dark-rgbd",
      "RGB-D xyz at 1.6x speed in the dark: long exposures (blur), high gain (noise), dark level 3",
      Rgbd, Xyz, 300);
  p.lighting = darkLighting(3);
  p.motion_speed = 1.6;
  presets.push_back(p);
  p = make("walking-dark-rgbd", "dark-rgbd with two people walking", Rgbd, Xyz, 300);
  p.lighting = darkLighting(3);
  p.walkers = 2;
  presets.push_back(p);
  p = make("fade-rgbd",
           "RGB-D xyz while the light fades from normal to very dark (auto-exposure runs out)",
           Rgbd, Xyz, 300);
  p.lighting.light_end = 0.02;
  p.lighting.dark_level = 1;
  presets.push_back(p);

  p = make("handheld-rgbd",
           "hand-held Kinect v1 like TUM fr1 desk/room: fast sweeps and quick turns, blur at a "
           "~17 ms exposure, 30 ms rolling shutter, depth misregistered by ~1.5 px, up to 15 ms "
           "out of sync and with holes on dark and grazing surfaces",
           Rgbd, Handheld, 300);
  p.lighting.light_start = p.lighting.light_end = 0.35;  // auto-exposure: 6 ms / 0.35
  p.readout_ms = 30.0;
  p.depth = kinectV1Depth();
  presets.push_back(p);

  presets.push_back(
      make("xyz-stereo", "EuRoC-like stereo translation shake, static scene", Stereo, Xyz, 300));
  presets.push_back(make(
      "loop-stereo", "EuRoC-like stereo lap around the room, returns to its start (loop closing)",
      Stereo, Loop, 600));
  p = make("dark-stereo",
           "EuRoC-like stereo in the dark like MH04/MH05/V203: blur + noise + dark level 3", Stereo,
           Xyz, 300);
  p.lighting = darkLighting(3);
  presets.push_back(p);
  p = make("dark-loop-stereo", "dark-stereo lighting on the loop trajectory", Stereo, Loop, 600);
  p.lighting = darkLighting(3);
  presets.push_back(p);
  return presets;
}

}  // namespace

const std::vector<Preset>& allPresets() {
  static const std::vector<Preset> presets = buildPresets();
  return presets;
}

std::string presetNames() {
  std::string names;
  for (const auto& p : allPresets()) names += (names.empty() ? "" : ", ") + p.name;
  return names;
}

const Preset& findPreset(std::string_view name) {
  for (const auto& p : allPresets())
    if (p.name == name) return p;
  fail("synth preset '{}' is unknown (known: {})", name, presetNames());
}

}  // namespace lumaslam::synth
