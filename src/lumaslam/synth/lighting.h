#pragma once
// Lighting and camera photometry shared by `synth` and `perturb`: a scene-light schedule with
// flicker and sudden exposure jumps, a lagging auto-exposure (exposure time then gain, both
// capped, so dark scenes get long exposures = motion blur, and high gain = noise), shot + read
// sensor noise, saturation, a gamma-2 display encoding and AirSLAM's dark model
// V_out = A * V_in^(1/gamma).
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/synth/camera_rig.h"

namespace lumaslam::synth {

struct ExposureJump {
  int first_frame = 0;
  int frames = 3;
  double factor = 3.0;  // e.g. 3 (over-exposed flash) or 0.2 (sudden dark)
};

struct LightingSchedule {
  double light_start = 1.0;        // scene light level at the first frame (1 = lit office)
  double light_end = 1.0;          // ... at the last frame (linear ramp in between)
  double flicker_amplitude = 0.0;  // relative, e.g. 0.3
  double flicker_hz = 0.0;         // apparent (aliased) flicker frequency
  std::vector<ExposureJump> jumps;
  int dark_level = 0;        // 0..5, see darkCurve()
  double noise_scale = 1.0;  // 0 = no sensor noise
  bool motion_blur = true;
};

// What the camera did for one frame.
struct FrameExposure {
  double scene_light = 1.0;
  double exposure_ms = 6.0;
  double gain = 1.0;
  double jump = 1.0;  // exposure-jump factor on this frame (1 = none)
  double nominal_ms = 6.0;
  // Photons collected relative to a nominal frame, and the overall brightness factor.
  double signal() const { return scene_light * jump * exposure_ms / nominal_ms; }
  double brightness() const { return signal() * gain; }
};

// Auto-exposure over the whole schedule: it reacts to the scene light of the previous frames
// (exponential smoothing), so flicker and jumps show through for a few frames.
std::vector<FrameExposure> planExposures(const LightingSchedule& schedule, const Rig& rig,
                                         int frames);

struct DarkCurve {
  double a = 1.0;
  double inv_gamma = 1.0;  // V_out = a * V_in^inv_gamma, V in [0, 1]
};
// Level 0 is the identity; levels 1..5 darken monotonically. Throws Error outside 0..5.
DarkCurve darkCurve(int level);

struct SensorModel {
  double full_well_e = 3000.0;  // electrons for a white surface at nominal exposure
  double read_noise_e = 6.0;
  double noise_scale = 1.0;  // 0 disables noise
};

// Linear radiance (CV_32FC1/C3) -> 8-bit display image: collect `signal` x radiance photons,
// add shot + read noise (keyed by `noise_key`, independent of threads), amplify by `gain`,
// saturate, gamma-2 encode and apply the dark curve. `light_field` (CV_32F, optional) multiplies
// the radiance per pixel (non-uniform light for perturb's spotlight).
cv::Mat exposeImage(const cv::Mat& radiance, double signal, double gain, int dark_level,
                    const SensorModel& sensor, std::uint64_t noise_key,
                    const cv::Mat& light_field = cv::Mat());

// 8-bit display image -> linear radiance (inverse of the gamma-2 encoding), CV_32FC(n).
cv::Mat displayToLinear(const cv::Mat& image);

}  // namespace lumaslam::synth
