#pragma once
// The synthetic indoor scene: a textured room (walls, floor, ceiling) holding axis-aligned
// boxes (crates, shelves, tables), moving boxes and "walker" billboards with person-like
// silhouettes, lit by ceiling point lights and optionally a moving spotlight. World frame:
// z up, metres. `at(t)` gives the geometry at time t for the renderer.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "lumaslam/synth/person_image.h"
#include "lumaslam/synth/texture.h"
#include "lumaslam/synth/walker_figure.h"

namespace lumaslam::synth {

// Face index = axis * 2 + (1 for the +axis face, 0 for the -axis face).
struct BoxInstance {
  Eigen::Vector3f lo;
  Eigen::Vector3f hi;
  std::array<int, 6> textures{};
  std::array<int, 6> lightmaps{-1, -1, -1, -1, -1, -1};  // baked static light, -1 = shade per pixel
  std::uint8_t object_id = 0;                            // 0 = static scene
};

struct WalkerInstance {
  Eigen::Vector3f base;    // on the floor, centre of the billboard
  Eigen::Vector3f normal;  // horizontal, towards the viewer
  Eigen::Vector3f right;   // horizontal, along the billboard
  float width = 0.7f;
  float height = 1.75f;
  float gait_phase = 0.0f;  // radians
  int texture = 0;
  int photo = -1;  // Scene::photoAlpha index when textured from a person photo, else -1
  std::uint8_t object_id = 0;
  WalkerFigure figure;  // the procedural silhouette at gait_phase (photo walkers: unused)
};

struct PointLight {
  Eigen::Vector3f position;
  float intensity = 1.0f;
};

struct SpotLight {
  Eigen::Vector3f position;
  Eigen::Vector3f direction;  // unit
  float cos_outer = 0.9f;
  float cos_inner = 0.95f;
  float intensity = 1.0f;
};

struct SceneSnapshot {
  BoxInstance room;  // seen from inside
  std::vector<BoxInstance> boxes;
  std::vector<WalkerInstance> walkers;
  std::vector<PointLight> lights;
  std::optional<SpotLight> spot;
  float ambient = 0.3f;
};

struct SceneOptions {
  int walkers = 0;
  int moving_boxes = 0;
  bool spotlight = false;        // dim room, lit mainly by a sweeping spotlight
  std::vector<cv::Mat> posters;  // optional user images (CV_8UC3) pasted as posters
  // Optional person photos: walkers show one of them (chosen by seed) instead of a procedural
  // figure, scaled to the walker's height with the photo's aspect ratio.
  std::vector<PersonImage> people;
  // Where the camera mostly is and looks (horizontal); walkers cross this view.
  Eigen::Vector3d view_origin{0.0, -0.9, 1.3};
  Eigen::Vector3d view_direction{0.0, 1.0, 0.0};
  // When set, walkers do not cross the fixed view but walk within the field of view of this
  // camera pose over time (seconds from the start): each keeps to a bearing that trails the
  // camera's heading by a fraction of a second and sways +-15-20 deg about it, at 1.4-2.6 m,
  // so they stay in a fast-rotating view and cover up to ~40% of it (like TUM fr3 walking_rpy,
  // where people move in front of the camera for most of the sequence).
  std::function<Eigen::Isometry3d(double)> walkers_follow_view;
  // Walkers stay put like people sitting at a desk (TUM fr3 sitting_*): each sways over
  // 4-6 cm at 3-5 cm/s (shifting in a chair, leaning) instead of crossing the room; the slow
  // motion that must not erase the static map behind them.
  bool walkers_sitting = false;
};

// Lambertian light at p (normal n) from ambient + point lights, and from a spotlight.
float staticLighting(const std::vector<PointLight>& lights, float ambient, const Eigen::Vector3f& p,
                     const Eigen::Vector3f& n);
float spotLighting(const SpotLight& spot, const Eigen::Vector3f& p, const Eigen::Vector3f& n);

// Static lighting is baked per face on a grid of this spacing (it varies slowly: no shadows).
constexpr float kLightmapCell = 0.1f;

// Inside-silhouette test of a walker in billboard coordinates (u: metres from the centre line,
// v: metres above the floor).
bool insideWalkerSilhouette(float u, float v, float height, float gait_phase);

// Photo walkers lean by up to this fraction of their height with the gait (head moves most).
constexpr float kPhotoWalkerLean = 0.02f;

// Texture coordinates (metres from the texture's top-left corner) of a point on a walker, see
// Scene::walkerCovers.
struct WalkerTexel {
  float u = 0.0f, v = 0.0f;
};

class Scene {
 public:
  static Scene build(const SceneOptions& options, std::uint64_t seed);

  // Geometry and lights at time t (seconds from the start); walkers face `viewer`.
  SceneSnapshot at(double t, const Eigen::Vector3d& viewer) const;

  const MipTexture& texture(int index) const { return textures_[static_cast<size_t>(index)]; }
  // Whether billboard point (u, v) (as in insideWalkerSilhouette) is on walker w, and if so
  // its texture coordinates (texel is left alone when not). Procedural walkers use the
  // silhouette; photo walkers the photo's alpha (or whole rectangle), leaning with the gait.
  bool walkerCovers(const WalkerInstance& w, float u, float v, WalkerTexel& texel) const;
  // Class name of a dynamic object id (1-based): "person" for walkers, "box" for moving boxes.
  const std::string& objectClass(std::uint8_t object_id) const;
  int dynamicObjectCount() const { return static_cast<int>(object_classes_.size()); }
  const BoxInstance& room() const { return room_; }
  // CV_32F grid of staticLighting() over a face, sampled at (u, v) / kLightmapCell.
  const cv::Mat& lightmap(int index) const { return lightmaps_[static_cast<size_t>(index)]; }

 private:
  friend class SceneBuilder;  // Scene::build's steps

  struct LinearPath {  // back and forth between a and b on the floor
    Eigen::Vector2f a, b;
    float speed = 1.0f;
    float offset_m = 0.0f;
    Eigen::Vector2f at(double t) const;
    void sit(float fraction);  // see SceneOptions::walkers_sitting
  };
  struct ViewFollowing {  // see SceneOptions::walkers_follow_view
    float lag_s = 0.3f;
    float sway_rad = 0.3f, sway_rate = 0.5f, sway_phase = 0.0f;
    float distance_m = 2.0f, distance_swing_m = 0.3f, distance_rate = 0.3f, distance_phase = 0.0f;
  };
  struct Walker {
    LinearPath path;
    std::optional<ViewFollowing> follow;
    float height = 1.75f;
    float width = 0.7f;
    int texture = 0;
    int photo = -1;
  };
  struct MovingBox {
    LinearPath path;
    Eigen::Vector3f size;
    std::array<int, 6> textures{};
  };

  int addTexture(const cv::Mat& image, float texel_size_m);
  Eigen::Vector2f walkerPosition(const Walker& walker, double t) const;
  void bakeLightmaps(BoxInstance& box, bool is_room);

  std::vector<MipTexture> textures_;
  BoxInstance room_;
  std::vector<BoxInstance> static_boxes_;
  std::vector<Walker> walkers_;
  std::vector<MovingBox> moving_boxes_;
  std::vector<PointLight> lights_;
  std::vector<std::string> object_classes_;
  std::vector<cv::Mat> lightmaps_;
  std::vector<cv::Mat> photo_alphas_;  // per photo walker: CV_8U alpha, empty = whole rectangle
  float ambient_ = 0.28f;
  bool spotlight_ = false;
  SceneOptions options_;
};

}  // namespace lumaslam::synth
