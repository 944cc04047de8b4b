#pragma once
// Pinhole camera and sensor rigs of the synthetic sequences (undistorted images).
#include <Eigen/Core>

#include "lumaslam/core/pose.h"

namespace lumaslam::synth {

struct PinholeCamera {
  int width = 640;
  int height = 480;
  double fx = 535.4;
  double fy = 539.2;
  double cx = 320.1;
  double cy = 247.6;
};

enum class SensorKind { Rgbd, Stereo };

struct Rig {
  SensorKind kind = SensorKind::Rgbd;
  PinholeCamera camera;  // cam0 (rgb for RGB-D, left for stereo); cam1 has the same K
  double fps = 30.0;
  double baseline_m = 0.0;  // stereo only: cam1 sits at +x of cam0
  double nominal_exposure_ms = 6.0;
  double max_exposure_ms = 30.0;  // auto-exposure limit (below the frame period)
  double max_gain = 4.0;          // analog gain limit of auto-exposure
  double readout_ms = 0.0;        // rolling-shutter readout top to bottom, 0 = global shutter

  SE3 T_c0_c1() const {
    SE3 T = SE3::Identity();
    T.translation().x() = baseline_m;
    return T;
  }
};

// TUM fr3-like Kinect: 640x480 at 30 Hz.
inline Rig tumRgbdRig() {
  return Rig{};
}

// EuRoC-like stereo: 752x480 at 20 Hz, 11 cm baseline.
inline Rig eurocStereoRig() {
  Rig rig;
  rig.kind = SensorKind::Stereo;
  rig.camera = {752, 480, 458.654, 457.296, 367.215, 248.375};
  rig.fps = 20.0;
  rig.baseline_m = 0.11;
  rig.max_exposure_ms = 45.0;
  rig.max_gain = 6.0;
  return rig;
}

}  // namespace lumaslam::synth
