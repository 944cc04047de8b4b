#include "lumaslam/synth/walker_figure.h"

#include <algorithm>
#include <cmath>

namespace lumaslam::synth {

WalkerFigure::Capsule WalkerFigure::capsule(float ax, float ay, float bx, float by, float radius) {
  Capsule c;
  c.ax = ax, c.ay = ay, c.dx = bx - ax, c.dy = by - ay;
  c.inv_length2 = 1.0f / (c.dx * c.dx + c.dy * c.dy);
  c.radius2 = radius * radius;
  c.u_lo = std::min(ax, bx) - radius, c.u_hi = std::max(ax, bx) + radius;
  c.v_lo = std::min(ay, by) - radius, c.v_hi = std::max(ay, by) + radius;
  return c;
}

bool WalkerFigure::inside(const Capsule& c, float u, float v) {
  if (u < c.u_lo || u > c.u_hi || v < c.v_lo || v > c.v_hi) return false;
  const float t = std::clamp(((u - c.ax) * c.dx + (v - c.ay) * c.dy) * c.inv_length2, 0.0f, 1.0f);
  const float ex = u - (c.ax + t * c.dx), ey = v - (c.ay + t * c.dy);
  return ex * ex + ey * ey < c.radius2;
}

WalkerFigure::WalkerFigure(float height, float gait_phase) : inv_scale_(1.75f / height) {
  const float swing = std::sin(gait_phase);
  capsules_ = {capsule(0.0f, 1.44f, 0.0f, 1.54f, 0.05f),            // neck
               capsule(0.0f, 1.05f, 0.0f, 1.3f, 0.15f),             // torso
               capsule(0.0f, 0.95f, 0.3f * swing, 0.05f, 0.075f),   // leg
               capsule(0.0f, 0.95f, -0.3f * swing, 0.05f, 0.075f),  // other leg
               capsule(0.0f, 1.38f, -0.25f * swing, 0.84f, 0.05f),  // arm, opposite
               capsule(0.0f, 1.38f, 0.25f * swing, 0.84f, 0.05f)};  // other arm
}

bool WalkerFigure::covers(float u, float v) const {
  u *= inv_scale_;
  v *= inv_scale_;
  if (v < 0.0f || v > 1.75f || std::abs(u) > 0.45f) return false;
  if (u * u + (v - 1.63f) * (v - 1.63f) < 0.1f * 0.1f) return true;  // head
  for (const Capsule& c : capsules_)
    if (inside(c, u, v)) return true;
  return false;
}

}  // namespace lumaslam::synth
