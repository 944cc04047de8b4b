#include "lumaslam/synth/trajectory.h"

#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/random.h"

namespace lumaslam::synth {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Camera looking along world +y with z up: x_c = +x_w, y_c = -z_w, z_c = +y_w.
Eigen::Matrix3d baseOrientation() {
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return R;
}

// yaw about world z, then pitch about camera x, then roll about camera z.
Eigen::Matrix3d orientation(double yaw, double pitch, double roll) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * baseOrientation() *
         (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
             .toRotationMatrix();
}

// yaw/pitch that look from `from` towards `to`.
void lookAt(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double& yaw, double& pitch) {
  const Eigen::Vector3d d = to - from;
  yaw = std::atan2(-d.x(), d.y());
  pitch = std::atan2(d.z(), std::hypot(d.x(), d.y()));  // positive pitch looks up
}

const Eigen::Vector3d kOrigin(0.0, -0.9, 1.3);  // where the camera works for all but the loop
const Eigen::Vector3d kTarget(0.0, 2.0, 0.9);   // what it looks at

}  // namespace

TrajectoryKind trajectoryKindFromName(std::string_view name) {
  if (name == "static") return TrajectoryKind::Static;
  if (name == "xyz") return TrajectoryKind::Xyz;
  if (name == "rpy") return TrajectoryKind::Rpy;
  if (name == "halfsphere") return TrajectoryKind::Halfsphere;
  if (name == "loop") return TrajectoryKind::Loop;
  if (name == "handheld") return TrajectoryKind::Handheld;
  fail("trajectory '{}' is unknown (expected static, xyz, rpy, halfsphere, loop or handheld)",
       name);
}

std::string trajectoryKindName(TrajectoryKind kind) {
  switch (kind) {
    case TrajectoryKind::Static:
      return "static";
    case TrajectoryKind::Xyz:
      return "xyz";
    case TrajectoryKind::Rpy:
      return "rpy";
    case TrajectoryKind::Halfsphere:
      return "halfsphere";
    case TrajectoryKind::Loop:
      return "loop";
    case TrajectoryKind::Handheld:
      return "handheld";
  }
  return "?";
}

Eigen::Vector3d CameraTrajectory::Tremor::at(double t) const {
  return {amplitude.x() * std::sin(frequency.x() * t + phase.x()),
          amplitude.y() * std::sin(frequency.y() * t + phase.y()),
          amplitude.z() * std::sin(frequency.z() * t + phase.z())};
}

CameraTrajectory::CameraTrajectory(TrajectoryKind kind, double duration_s, std::uint64_t seed,
                                   double speed)
    : kind_(kind), duration_(duration_s), speed_(speed) {
  if (!(duration_s > 0.0)) fail("trajectory: duration must be positive, got {}", duration_s);
  if (!(speed > 0.0)) fail("trajectory: speed must be positive, got {}", speed);
  Rng rng(seed, 0x7a7);
  const auto randomVector = [&](double lo, double hi) {
    return Eigen::Vector3d(rng.uniform(lo, hi), rng.uniform(lo, hi), rng.uniform(lo, hi));
  };
  // Hand tremor: sub-millimetre at 1.5-4 Hz and < 0.1 degree (a still hand on TUM's Kinect).
  const double scale = kind == TrajectoryKind::Static ? 0.3 : 1.0;
  position_tremor_ = {randomVector(0.0003, 0.001) * scale, randomVector(10.0, 25.0),
                      randomVector(0, 2 * kPi)};
  angle_tremor_ = {randomVector(0.03, 0.08) * kDeg * scale, randomVector(10.0, 25.0),
                   randomVector(0, 2 * kPi)};
  phases_ = randomVector(0, 2 * kPi);
  if (kind == TrajectoryKind::Handheld) turns_ = planTurns(duration_s * speed, seed);
}

double CameraTrajectory::Turn::at(double t) const {
  if (t <= start) return 0.0;
  if (t >= start + duration) return angle;
  const double s = (t - start) / duration;
  return angle * (s - std::sin(2.0 * kPi * s) / (2.0 * kPi));
}

std::vector<CameraTrajectory::Turn> CameraTrajectory::planTurns(double duration_s,
                                                                std::uint64_t seed) {
  // Alternating directions per axis, so the view swings back instead of drifting away.
  Rng rng(seed, 0x7e4c);
  std::vector<Turn> turns;
  std::array<double, 2> sign{1.0, 1.0};
  for (double t = rng.uniform(1.2, 2.0); t < duration_s; t += rng.uniform(1.8, 3.2)) {
    Turn turn;
    turn.start = t;
    turn.duration = rng.uniform(0.15, 0.2);
    turn.axis = rng.chance(0.65) ? 0 : 1;
    const double magnitude = (turn.axis == 0 ? rng.uniform(12.0, 16.0) : rng.uniform(8.0, 11.0));
    turn.angle = sign[static_cast<size_t>(turn.axis)] * magnitude * kDeg;
    sign[static_cast<size_t>(turn.axis)] *= -1.0;
    turns.push_back(turn);
  }
  return turns;
}

Eigen::Vector3d CameraTrajectory::viewOrigin() const {
  return kind_ == TrajectoryKind::Loop ? Eigen::Vector3d(0.0, 0.0, 1.3) : kOrigin;
}

Eigen::Vector3d CameraTrajectory::viewDirection() const {
  return (kTarget - kOrigin).normalized();
}

SE3 CameraTrajectory::pose(double real_t) const {
  const double t = kind_ == TrajectoryKind::Loop ? real_t : real_t * speed_;
  Motion m = motion(t);
  m.position += position_tremor_.at(t) - position_tremor_.at(0.0);
  const Eigen::Vector3d tremor = angle_tremor_.at(t) - angle_tremor_.at(0.0);
  m.yaw += tremor.x(), m.pitch += tremor.y(), m.roll += tremor.z();
  SE3 T_w_c = SE3::Identity();
  T_w_c.linear() = orientation(m.yaw, m.pitch, m.roll);
  T_w_c.translation() = m.position;
  return T_w_c;
}

CameraTrajectory::Motion CameraTrajectory::motion(double t) const {
  switch (kind_) {
    case TrajectoryKind::Static:
      return staticMotion(t);
    case TrajectoryKind::Xyz:
      return xyzMotion(t);
    case TrajectoryKind::Rpy:
      return rpyMotion(t);
    case TrajectoryKind::Halfsphere:
      return halfsphereMotion(t);
    case TrajectoryKind::Loop:
      return loopMotion(t);
    case TrajectoryKind::Handheld:
      return handheldMotion(t);
  }
  return {kOrigin};
}

CameraTrajectory::Motion CameraTrajectory::staticMotion(double t) const {
  const Eigen::Vector3d& ph = phases_;
  Motion m{kOrigin};
  m.position +=
      Eigen::Vector3d(0.004 * std::sin(0.3 * t + ph.x()), 0.004 * std::sin(0.23 * t + ph.y()),
                      0.003 * std::sin(0.37 * t + ph.z()));
  lookAt(m.position, kTarget, m.yaw, m.pitch);
  return m;
}

// Peak speed ~0.35 m/s, mean ~0.25 m/s; eases in from rest over the first second.
CameraTrajectory::Motion CameraTrajectory::xyzMotion(double t) const {
  const Eigen::Vector3d& ph = phases_;
  Motion m{kOrigin};
  const double ease = t < 1.0 ? t * t * (3.0 - 2.0 * t) : 1.0;
  m.position += ease * Eigen::Vector3d(0.28 * std::sin(1.05 * t + ph.x()) - 0.28 * std::sin(ph.x()),
                                       0.22 * std::sin(0.8 * t + ph.y()) - 0.22 * std::sin(ph.y()),
                                       0.14 * std::sin(1.3 * t + ph.z()) - 0.14 * std::sin(ph.z()));
  lookAt(m.position,
         kTarget + Eigen::Vector3d(0.3 * std::sin(0.4 * t), 0.0, 0.1 * std::sin(0.5 * t)), m.yaw,
         m.pitch);
  m.roll = 3.0 * kDeg * std::sin(0.6 * t + ph.x());
  return m;
}

CameraTrajectory::Motion CameraTrajectory::rpyMotion(double t) const {
  const Eigen::Vector3d& ph = phases_;
  Motion m{kOrigin};
  const double ease = t < 1.0 ? t * t * (3.0 - 2.0 * t) : 1.0;
  m.position += ease * Eigen::Vector3d(0.03 * std::sin(0.7 * t), 0.02 * std::sin(0.5 * t),
                                       0.02 * std::sin(0.9 * t));
  lookAt(m.position, kTarget, m.yaw, m.pitch);
  // Peak angular rates ~45-60 deg/s per axis.
  m.yaw += ease * 28.0 * kDeg * (std::sin(1.9 * t + ph.x()) - std::sin(ph.x()));
  m.pitch += ease * 15.0 * kDeg * (std::sin(2.3 * t + ph.y()) - std::sin(ph.y()));
  m.roll = ease * 22.0 * kDeg * (std::sin(2.1 * t + ph.z()) - std::sin(ph.z()));
  return m;
}

// On a sphere of radius 0.6 m around the working point, ~0.3 m/s.
CameraTrajectory::Motion CameraTrajectory::halfsphereMotion(double t) const {
  const Eigen::Vector3d& ph = phases_;
  Motion m{kOrigin};
  const double ease = t < 1.0 ? t * t * (3.0 - 2.0 * t) : 1.0;
  const double azimuth = ease * 1.1 * std::sin(0.45 * t + ph.x()) - 1.1 * std::sin(ph.x()) * ease;
  const double elevation = 0.35 + ease * 0.3 * std::sin(0.6 * t + ph.y());
  const Eigen::Vector3d centre = kOrigin + Eigen::Vector3d(0.0, 0.6, -0.2);
  m.position =
      centre + 0.6 * Eigen::Vector3d(std::sin(azimuth) * std::cos(elevation),
                                     -std::cos(azimuth) * std::cos(elevation), std::sin(elevation));
  lookAt(m.position, kTarget, m.yaw, m.pitch);
  m.roll = 4.0 * kDeg * std::sin(0.5 * t + ph.z());
  return m;
}

// One lap of an ellipse in `duration_` seconds, heading outwards; closes exactly.
CameraTrajectory::Motion CameraTrajectory::loopMotion(double t) const {
  Motion m{kOrigin};
  const double s = 2.0 * kPi * t / duration_;
  m.position =
      Eigen::Vector3d(1.0 * std::sin(s), -0.7 * std::cos(s), 1.3 + 0.08 * std::sin(2.0 * s));
  m.yaw = s + kPi;  // facing away from the centre (towards -y at s = 0)
  m.yaw += 0.25 * std::sin(s);
  m.pitch =
      -10.0 * kDeg + 4.0 * kDeg * std::sin(3.0 * s);  // slightly down: floor and furniture in view
  m.roll = 3.0 * kDeg * std::sin(2.0 * s);
  return m;
}

// Sweeps over the desk-like scene in front (TUM fr1 desk: 0.41 m/s, 23 deg/s on average): yaw
// peaks at ~55 deg/s, pitch ~40, roll ~20, plus the quick turns.
CameraTrajectory::Motion CameraTrajectory::handheldMotion(double t) const {
  const Eigen::Vector3d& ph = phases_;
  Motion m{kOrigin};
  const double ease = t < 1.0 ? t * t * (3.0 - 2.0 * t) : 1.0;
  const auto sweep = [&](double amplitude, double rate, double phase) {
    return amplitude * (std::sin(rate * t + phase) - std::sin(phase));
  };
  m.position += ease * Eigen::Vector3d(sweep(0.45, 0.9, ph.x()), sweep(0.25, 0.7, ph.y()),
                                       sweep(0.15, 1.1, ph.z()));
  lookAt(m.position, kTarget, m.yaw, m.pitch);
  m.yaw += ease * (sweep(20.0 * kDeg, 1.6, ph.y()) + sweep(8.0 * kDeg, 3.1, ph.z()));
  m.pitch += ease * (sweep(12.0 * kDeg, 2.0, ph.z()) + sweep(5.0 * kDeg, 3.7, ph.x()));
  m.roll = ease * (sweep(8.0 * kDeg, 1.3, ph.x()) + sweep(3.0 * kDeg, 4.1, ph.y()));
  for (const Turn& turn : turns_) (turn.axis == 0 ? m.yaw : m.pitch) += turn.at(t);
  return m;
}

}  // namespace lumaslam::synth
