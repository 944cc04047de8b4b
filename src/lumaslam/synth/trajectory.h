#pragma once
// Smooth hand-held camera trajectories like the TUM RGB-D / EuRoC benchmark motions: sums of
// sinusoids (C-infinity) plus a small seeded tremor, evaluated at any time.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/core/pose.h"

namespace lumaslam::synth {

enum class TrajectoryKind {
  Static,      // nearly still: millimetre drift and tremor
  Xyz,         // translation shake along x, y, z (~0.2-0.35 m/s), looking at the scene
  Rpy,         // fast roll/pitch/yaw rotations (~40-90 deg/s) with little translation
  Halfsphere,  // moving over a half sphere (r ~0.6 m) while looking at the scene
  Loop,        // a closed ellipse around the room, looking outwards; ends where it began
  // Hand-held sweeps like TUM fr1 desk/room: ~0.3 m/s, rotation peaking at 1.5-3 degrees per
  // frame at 30 Hz, with a quick ~14-degree turn every 2-3 s (~5 degrees in its fastest frame).
  Handheld,
};

TrajectoryKind trajectoryKindFromName(std::string_view name);  // throws Error on unknown names
std::string trajectoryKindName(TrajectoryKind kind);

class CameraTrajectory {
 public:
  // `duration_s` sets the loop period (the loop closes at t = duration_s); `speed` > 1 plays
  // the other motions faster (e.g. 1.6 for MAV-like speeds).
  CameraTrajectory(TrajectoryKind kind, double duration_s, std::uint64_t seed, double speed = 1.0);

  TrajectoryKind kind() const { return kind_; }
  // Camera-to-world pose at time t (seconds from the start). Camera: x right, y down, z forward.
  SE3 pose(double t) const;

  // Where the camera mostly is and looks, for placing walkers and clear space in the scene.
  Eigen::Vector3d viewOrigin() const;
  Eigen::Vector3d viewDirection() const;

 private:
  struct Tremor {
    Eigen::Vector3d amplitude, frequency, phase;
    Eigen::Vector3d at(double t) const;
  };
  // A quick turn of the hand: `angle` radians about yaw (axis 0) or pitch (axis 1) over
  // `duration` seconds from `start`, with a raised-cosine angular rate (peak 2 angle/duration).
  struct Turn {
    double start = 0.0, duration = 0.2, angle = 0.0;
    int axis = 0;
    double at(double t) const;
  };
  static std::vector<Turn> planTurns(double duration_s, std::uint64_t seed);

  // Position and angles (see orientation() in trajectory.cpp) before the tremor.
  struct Motion {
    Eigen::Vector3d position;
    double yaw = 0.0, pitch = 0.0, roll = 0.0;
  };
  Motion motion(double t) const;  // t: trajectory time (scaled by speed_ except for the loop)
  Motion staticMotion(double t) const;
  Motion xyzMotion(double t) const;
  Motion rpyMotion(double t) const;
  Motion halfsphereMotion(double t) const;
  Motion loopMotion(double t) const;
  Motion handheldMotion(double t) const;

  TrajectoryKind kind_;
  double duration_;
  double speed_;
  Tremor position_tremor_;
  Tremor angle_tremor_;
  Eigen::Vector3d phases_;
  std::vector<Turn> turns_;  // Handheld only
};

}  // namespace lumaslam::synth
