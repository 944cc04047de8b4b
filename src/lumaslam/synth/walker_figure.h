#pragma once
// The procedural walker's silhouette (head, neck, torso, swinging legs and arms) at one gait
// phase, prepared once per frame so that the per-pixel inside test is a few comparisons.
#include <array>

namespace lumaslam::synth {

class WalkerFigure {
 public:
  WalkerFigure() = default;
  WalkerFigure(float height, float gait_phase);

  // Whether billboard point (u: metres from the centre line, v: metres above the floor) is on
  // the figure.
  bool covers(float u, float v) const;

 private:
  struct Capsule {  // segment a -> a + d with a radius, in 1.75 m-person coordinates
    float ax = 0, ay = 0, dx = 0, dy = 0, inv_length2 = 0, radius2 = 0;
    float u_lo = 0, u_hi = 0, v_lo = 0, v_hi = 0;  // bounds of the capsule
  };
  static Capsule capsule(float ax, float ay, float bx, float by, float radius);
  static bool inside(const Capsule& c, float u, float v);

  float inv_scale_ = 1.0f;  // 1.75 m / height
  std::array<Capsule, 6> capsules_{};
};

}  // namespace lumaslam::synth
