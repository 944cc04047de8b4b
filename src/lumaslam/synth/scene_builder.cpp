#include "lumaslam/synth/scene_builder.h"

#include <algorithm>
#include <string>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/box_face.h"

namespace lumaslam::synth {

namespace {

constexpr float kBoxTexel = 0.004f;
constexpr float kWalkerTexel = 0.004f;

void checkOptions(const SceneOptions& options) {
  if (options.walkers + options.moving_boxes > 200)
    fail("Scene: too many dynamic objects ({} walkers + {} boxes)", options.walkers,
         options.moving_boxes);
  for (size_t i = 0; i < options.people.size(); ++i)
    checkPersonImage(options.people[i], "Scene: person image " + std::to_string(i));
}

}  // namespace

bool SceneBuilder::Footprint::overlaps(const Footprint& other, float margin) const {
  return lo.x() < other.hi.x() + margin && other.lo.x() < hi.x() + margin &&
         lo.y() < other.hi.y() + margin && other.lo.y() < hi.y() + margin;
}

float SceneBuilder::Footprint::distanceTo(const Eigen::Vector2f& p) const {
  const Eigen::Vector2f d = (lo - p).cwiseMax(p - hi).cwiseMax(Eigen::Vector2f::Zero());
  return d.norm();
}

SceneBuilder::SceneBuilder(Scene& scene, const SceneOptions& options, std::uint64_t seed)
    : scene_(scene), options_(options), seed_(seed), rng_(seed, 0x5ce4e) {}

void SceneBuilder::build() {
  checkOptions(options_);
  buildRoom();
  setViewAxes();
  addWalkers();
  addMovingBoxes();
  addFurniture();
  addLightsAndLightmaps();
}

// Room: roughly 6.4-7.2 m x 5.6-6.4 m x 2.6-2.9 m.
void SceneBuilder::buildRoom() {
  BoxInstance& room = scene_.room_;
  room.lo = {-3.2f - static_cast<float>(rng_.uniform(0, 0.4)),
             -2.8f - static_cast<float>(rng_.uniform(0, 0.4)), 0.0f};
  room.hi = {3.2f + static_cast<float>(rng_.uniform(0, 0.4)),
             2.8f + static_cast<float>(rng_.uniform(0, 0.4)),
             2.6f + static_cast<float>(rng_.uniform(0, 0.3))};
  const Eigen::Vector3f room_size = room.hi - room.lo;
  for (int face = 0; face < 6; ++face) {
    const cv::Size2f size = faceSize(room_size, face);
    const float texel = std::max(0.005f, std::max(size.width, size.height) / 2048.0f);
    const SurfaceStyle style = face == 4   ? SurfaceStyle::Floor
                               : face == 5 ? SurfaceStyle::Ceiling
                                           : SurfaceStyle::Wall;
    Rng face_rng = rng_.fork();
    room.textures[static_cast<size_t>(face)] = scene_.addTexture(
        makeSurfaceTexture(size, texel, style, face_rng, options_.posters), texel);
  }
}

void SceneBuilder::setViewAxes() {
  origin_ = options_.view_origin.head<2>().cast<float>();
  forward_ = options_.view_direction.head<2>().cast<float>();
  if (forward_.norm() < 1e-6f) forward_ = {0.0f, 1.0f};
  forward_.normalize();
  across_ = {-forward_.y(), forward_.x()};
  inner_lo_ = scene_.room_.lo.head<2>() + Eigen::Vector2f::Constant(0.4f);
  inner_hi_ = scene_.room_.hi.head<2>() - Eigen::Vector2f::Constant(0.4f);
}

// Dynamic objects cross the main view at 1.3-3 m from its origin; keep furniture off their paths.
Scene::LinearPath SceneBuilder::crossingPath(float distance, float half_length, float speed) {
  Scene::LinearPath path;
  const Eigen::Vector2f centre = origin_ + forward_ * distance;
  path.a = (centre - across_ * half_length).cwiseMax(inner_lo_).cwiseMin(inner_hi_);
  path.b = (centre + across_ * half_length).cwiseMax(inner_lo_).cwiseMin(inner_hi_);
  path.speed = speed;
  path.offset_m = static_cast<float>(rng_.uniform(0, 2.0 * half_length));
  keep_clear_.push_back({path.a.cwiseMin(path.b) - Eigen::Vector2f::Constant(0.5f),
                         path.a.cwiseMax(path.b) + Eigen::Vector2f::Constant(0.5f)});
  return path;
}

void SceneBuilder::addWalkers() {
  for (int i = 0; i < options_.walkers; ++i) {
    Scene::Walker walker;
    walker.path = crossingPath(
        1.3f + 0.6f * static_cast<float>(i % 3) + static_cast<float>(rng_.uniform(0, 0.3)),
        static_cast<float>(rng_.uniform(1.8, 2.6)), static_cast<float>(rng_.uniform(0.9, 1.3)));
    // Side by side as at a desk, not one hidden behind the other in the middle of the view.
    if (options_.walkers_sitting) walker.path.sit(i % 2 == 0 ? 0.35f : 0.65f);
    if (options_.walkers_follow_view) walker.follow = viewFollowing(i);
    walker.height = static_cast<float>(rng_.uniform(1.6, 1.88));
    walker.width = 0.9f * walker.height / 1.75f;
    dressWalker(walker, i);
    scene_.walkers_.push_back(walker);
    scene_.object_classes_.push_back("person");
  }
}

// Drawn from the walker's own stream: the furniture stays as without.
Scene::ViewFollowing SceneBuilder::viewFollowing(int walker) const {
  Rng follow_rng(seed_, 0xf0110 + static_cast<std::uint64_t>(walker));
  Scene::ViewFollowing follow;
  follow.lag_s = static_cast<float>(follow_rng.uniform(0.25, 0.5));
  follow.sway_rad = static_cast<float>(follow_rng.uniform(0.2, 0.35));
  follow.sway_rate = static_cast<float>(follow_rng.uniform(0.4, 0.8));
  // Walkers start on opposite sides of the view and sway out of step.
  follow.sway_phase = static_cast<float>(CV_PI) * static_cast<float>(walker) +
                      static_cast<float>(follow_rng.uniform(-0.5, 0.5));
  follow.distance_m =
      1.6f + 0.5f * static_cast<float>(walker % 3) + static_cast<float>(follow_rng.uniform(0, 0.3));
  follow.distance_swing_m = static_cast<float>(follow_rng.uniform(0.2, 0.4));
  follow.distance_rate = static_cast<float>(follow_rng.uniform(0.2, 0.5));
  follow.distance_phase = static_cast<float>(follow_rng.uniform(0, 2.0 * CV_PI));
  return follow;
}

// A procedural figure, or a person photo scaled to the walker's height.
void SceneBuilder::dressWalker(Scene::Walker& walker, int index) {
  Rng texture_rng = rng_.fork();  // drawn even for photo walkers: same scene either way
  if (options_.people.empty()) {
    walker.texture = scene_.addTexture(
        makeWalkerTexture(walker.width, walker.height, kWalkerTexel, texture_rng), kWalkerTexel);
    return;
  }
  // Consecutive photos from a seeded start, so walkers differ when photos do.
  const PersonImage& person =
      options_.people[(hashKey(seed_, 0x9e09) + static_cast<std::uint64_t>(index)) %
                      options_.people.size()];
  const float rows = static_cast<float>(person.image.rows);
  walker.width = walker.height * static_cast<float>(person.image.cols) / rows;
  walker.texture = scene_.addTexture(person.image, walker.height / rows);
  walker.photo = static_cast<int>(scene_.photo_alphas_.size());
  scene_.photo_alphas_.push_back(person.alpha);
}

void SceneBuilder::addMovingBoxes() {
  for (int i = 0; i < options_.moving_boxes; ++i) {
    Scene::MovingBox box;
    box.path = crossingPath(2.0f + 0.5f * static_cast<float>(i % 3),
                            static_cast<float>(rng_.uniform(1.2, 2.0)),
                            static_cast<float>(rng_.uniform(0.3, 0.6)));
    box.size = {static_cast<float>(rng_.uniform(0.35, 0.6)),
                static_cast<float>(rng_.uniform(0.35, 0.6)),
                static_cast<float>(rng_.uniform(0.35, 0.7))};
    box.textures = crateTextures(box.size, SurfaceStyle::Crate);
    scene_.moving_boxes_.push_back(box);
    scene_.object_classes_.push_back("box");
  }
}

std::array<int, 6> SceneBuilder::crateTextures(const Eigen::Vector3f& size, SurfaceStyle style) {
  std::array<int, 6> faces{};
  for (int face = 0; face < 6; ++face) {
    Rng face_rng = rng_.fork();
    const cv::Size2f fs = faceSize(size, face);
    faces[static_cast<size_t>(face)] =
        face == 4
            ? 0  // never seen from below: reuse any texture
            : scene_.addTexture(
                  makeSurfaceTexture(fs, kBoxTexel, style, face_rng, options_.posters), kBoxTexel);
  }
  return faces;
}

// Furniture around the walls and in the corners, off the camera's working area.
void SceneBuilder::addFurniture() {
  const int wanted = rng_.uniformInt(13, 18);
  for (int attempt = 0; attempt < 400 && static_cast<int>(placed_.size()) < wanted; ++attempt) {
    const double kind = rng_.uniform();
    if (kind < 0.25)
      placeBookshelf();
    else if (kind < 0.5)
      placeTable();
    else
      placeCrateStack();
  }
}

bool SceneBuilder::fits(const Footprint& f) const {
  const BoxInstance& room = scene_.room_;
  if ((f.lo.array() < room.lo.head<2>().array() + 0.02f).any() ||
      (f.hi.array() > room.hi.head<2>().array() - 0.02f).any())
    return false;
  if (f.distanceTo(origin_) < 1.2f || f.distanceTo(Eigen::Vector2f::Zero()) < 1.5f) return false;
  for (const auto& other : keep_clear_)
    if (f.overlaps(other, 0.0f)) return false;
  for (const auto& other : placed_)
    if (f.overlaps(other, 0.15f)) return false;
  return true;
}

// Inline on purpose: as an out-of-line call (-fPIC) it moved table items by a float ulp, and
// the scene must stay byte-identical to the one built before Scene::build was split.
inline void SceneBuilder::addStaticBox(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
                                       const std::array<int, 6>& faces) {
  scene_.static_boxes_.push_back({lo, hi, faces, 0});
}

// Against a wall, books facing the room.
void SceneBuilder::placeBookshelf() {
  const BoxInstance& room = scene_.room_;
  const int wall = rng_.uniformInt(0, 3);
  const float width = static_cast<float>(rng_.uniform(0.8, 1.4)), depth = 0.35f;
  const float height = static_cast<float>(rng_.uniform(1.3, 2.0));
  Eigen::Vector3f lo, hi;
  const int axis = wall / 2;
  const int other = 1 - axis;
  const float along =
      static_cast<float>(rng_.uniform(room.lo[other] + 0.1, room.hi[other] - 0.1 - width));
  lo[other] = along;
  hi[other] = along + width;
  lo[axis] = wall % 2 ? room.hi[axis] - depth - 0.01f : room.lo[axis] + 0.01f;
  hi[axis] = lo[axis] + depth;
  lo.z() = 0.0f;
  hi.z() = height;
  const Footprint f{lo.head<2>(), hi.head<2>()};
  if (!fits(f)) return;
  placed_.push_back(f);
  std::array<int, 6> faces = crateTextures(hi - lo, SurfaceStyle::Table);
  const int front = axis * 2 + (wall % 2 ? 0 : 1);
  Rng face_rng = rng_.fork();
  faces[static_cast<size_t>(front)] = scene_.addTexture(
      makeSurfaceTexture(faceSize(hi - lo, front), kBoxTexel, SurfaceStyle::Shelf, face_rng, {}),
      kBoxTexel);
  addStaticBox(lo, hi, faces);
}

// With legs and things on top.
void SceneBuilder::placeTable() {
  const BoxInstance& room = scene_.room_;
  const Eigen::Vector2f size(static_cast<float>(rng_.uniform(0.9, 1.6)),
                             static_cast<float>(rng_.uniform(0.6, 0.9)));
  const Eigen::Vector2f lo2(static_cast<float>(rng_.uniform(room.lo.x(), room.hi.x() - size.x())),
                            static_cast<float>(rng_.uniform(room.lo.y(), room.hi.y() - size.y())));
  const Footprint f{lo2, lo2 + size};
  if (!fits(f)) return;
  placed_.push_back(f);
  const float top_z = static_cast<float>(rng_.uniform(0.72, 0.78));
  const Eigen::Vector3f top_lo(lo2.x(), lo2.y(), top_z - 0.04f),
      top_hi(lo2.x() + size.x(), lo2.y() + size.y(), top_z);
  addStaticBox(top_lo, top_hi, crateTextures(top_hi - top_lo, SurfaceStyle::Table));
  const std::array<int, 6> leg_faces = crateTextures({0.05f, 0.05f, top_z}, SurfaceStyle::Table);
  for (const float fx : {0.0f, 1.0f})
    for (const float fy : {0.0f, 1.0f}) {
      const Eigen::Vector3f leg_lo(lo2.x() + fx * (size.x() - 0.05f),
                                   lo2.y() + fy * (size.y() - 0.05f), 0.0f);
      addStaticBox(leg_lo, leg_lo + Eigen::Vector3f(0.05f, 0.05f, top_z - 0.04f), leg_faces);
    }
  const int items = rng_.uniformInt(0, 2);
  for (int i = 0; i < items; ++i) {
    const Eigen::Vector3f item(static_cast<float>(rng_.uniform(0.12, 0.4)),
                               static_cast<float>(rng_.uniform(0.12, 0.35)),
                               static_cast<float>(rng_.uniform(0.08, 0.4)));
    const Eigen::Vector3f item_lo(
        static_cast<float>(rng_.uniform(top_lo.x(), top_hi.x() - item.x())),
        static_cast<float>(rng_.uniform(top_lo.y(), top_hi.y() - item.y())), top_z);
    addStaticBox(item_lo, item_lo + item, crateTextures(item, SurfaceStyle::Crate));
  }
}

// One to three crates, each smaller one on top of the one below.
void SceneBuilder::placeCrateStack() {
  const BoxInstance& room = scene_.room_;
  Eigen::Vector3f size(static_cast<float>(rng_.uniform(0.4, 1.0)),
                       static_cast<float>(rng_.uniform(0.4, 1.0)),
                       static_cast<float>(rng_.uniform(0.3, 0.9)));
  const Eigen::Vector2f lo2(static_cast<float>(rng_.uniform(room.lo.x(), room.hi.x() - size.x())),
                            static_cast<float>(rng_.uniform(room.lo.y(), room.hi.y() - size.y())));
  const Footprint f{lo2, lo2 + size.head<2>()};
  if (!fits(f)) return;
  placed_.push_back(f);
  Eigen::Vector3f lo(lo2.x(), lo2.y(), 0.0f);
  const int levels = rng_.uniformInt(1, 3);
  for (int level = 0; level < levels && lo.z() + size.z() < room.hi.z() - 0.3f; ++level) {
    addStaticBox(lo, lo + size, crateTextures(size, SurfaceStyle::Crate));
    const Eigen::Vector3f next(size.x() * static_cast<float>(rng_.uniform(0.5, 0.95)),
                               size.y() * static_cast<float>(rng_.uniform(0.5, 0.95)),
                               static_cast<float>(rng_.uniform(0.2, 0.6)));
    lo += Eigen::Vector3f(static_cast<float>(rng_.uniform(0, size.x() - next.x())),
                          static_cast<float>(rng_.uniform(0, size.y() - next.y())), size.z());
    size = next;
  }
}

// Four hanging ceiling lights, then the static light baked on the room and the furniture.
void SceneBuilder::addLightsAndLightmaps() {
  const BoxInstance& room = scene_.room_;
  const Eigen::Vector3f room_size = room.hi - room.lo;
  const float light_z = room.hi.z() - 0.5f;
  for (const float sx : {-0.5f, 0.5f})
    for (const float sy : {-0.5f, 0.5f})
      scene_.lights_.push_back({{sx * room_size.x() * 0.6f, sy * room_size.y() * 0.6f, light_z},
                                options_.spotlight ? 0.12f : 3.2f});
  scene_.ambient_ = options_.spotlight ? 0.02f : 0.28f;
  scene_.bakeLightmaps(scene_.room_, true);
  for (auto& box : scene_.static_boxes_) scene_.bakeLightmaps(box, false);
}

}  // namespace lumaslam::synth
