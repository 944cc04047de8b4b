#pragma once
// Scene::build in named steps. The scene is defined by the order of the random draws: every
// step draws from the one generator in the order it is called, including draws whose result
// is thrown away, so the steps must keep their order (see build()).
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/synth/random.h"
#include "lumaslam/synth/scene.h"
#include "lumaslam/synth/texture_factory.h"

namespace lumaslam::synth {

class SceneBuilder {
 public:
  SceneBuilder(Scene& scene, const SceneOptions& options, std::uint64_t seed);
  void build();

 private:
  struct Footprint {
    Eigen::Vector2f lo, hi;
    bool overlaps(const Footprint& other, float margin) const;
    float distanceTo(const Eigen::Vector2f& p) const;
  };

  void buildRoom();
  void setViewAxes();
  Scene::LinearPath crossingPath(float distance, float half_length, float speed);
  void addWalkers();
  Scene::ViewFollowing viewFollowing(int walker) const;
  void dressWalker(Scene::Walker& walker, int index);
  void addMovingBoxes();
  std::array<int, 6> crateTextures(const Eigen::Vector3f& size, SurfaceStyle style);
  void addFurniture();
  bool fits(const Footprint& f) const;
  void addStaticBox(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
                    const std::array<int, 6>& faces);
  void placeBookshelf();
  void placeTable();
  void placeCrateStack();
  void addLightsAndLightmaps();

  Scene& scene_;
  const SceneOptions& options_;
  std::uint64_t seed_;
  Rng rng_;
  // The main view on the floor: dynamic objects cross it, furniture keeps off it.
  Eigen::Vector2f origin_, forward_, across_;
  Eigen::Vector2f inner_lo_, inner_hi_;  // the room less a 0.4 m margin
  std::vector<Footprint> keep_clear_;    // around the dynamic objects' paths
  std::vector<Footprint> placed_;        // furniture so far
};

}  // namespace lumaslam::synth
