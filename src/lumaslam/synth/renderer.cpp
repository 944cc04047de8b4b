#include "lumaslam/synth/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace lumaslam::synth {

namespace {

struct ScreenRect {
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;  // inclusive; empty when x1 < x0
  float near_z = 0.0f;                   // smallest camera z of the object's visible part
  bool empty() const { return x1 < x0 || y1 < y0; }
};

// Rays are cast from the camera centre, so hits closer than this are never needed.
constexpr float kNearZ = 1e-3f;

// Image rectangle covered by the convex hull of `points` (box corners or billboard corners in
// the order of corners() below), clipped to the part in front of the camera (z >= kNearZ): an
// object behind the camera gets an empty rectangle.
template <typename Points>
ScreenRect projectBounds(const Points& points, const Eigen::Matrix3f& R_c_w,
                         const Eigen::Vector3f& t_c_w, const PinholeCamera& cam) {
  constexpr int n = static_cast<int>(std::tuple_size_v<Points>);
  std::array<Eigen::Vector3f, n> pc;
  for (int i = 0; i < n; ++i)
    pc[static_cast<size_t>(i)] = R_c_w * points[static_cast<size_t>(i)] + t_c_w;
  float xmin = std::numeric_limits<float>::max(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  float near_z = xmin;
  const auto add = [&](const Eigen::Vector3f& p) {
    const float u = static_cast<float>(cam.fx) * p.x() / p.z() + static_cast<float>(cam.cx);
    const float v = static_cast<float>(cam.fy) * p.y() / p.z() + static_cast<float>(cam.cy);
    xmin = std::min(xmin, u), xmax = std::max(xmax, u), ymin = std::min(ymin, v),
    ymax = std::max(ymax, v), near_z = std::min(near_z, p.z());
  };
  // Points of the hull in front of the near plane: the corners there, and where the edges
  // (all pairs: a superset of the real edges, still inside the hull) cross the plane.
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f& a = pc[static_cast<size_t>(i)];
    if (a.z() >= kNearZ) add(a);
    for (int j = i + 1; j < n; ++j) {
      const Eigen::Vector3f& b = pc[static_cast<size_t>(j)];
      if ((a.z() < kNearZ) != (b.z() < kNearZ))
        add(a + (b - a) * ((kNearZ - a.z()) / (b.z() - a.z())));
    }
  }
  ScreenRect r;
  if (near_z == std::numeric_limits<float>::max()) return r;  // wholly behind the camera
  // Clamp in float first: points just in front of the near plane project far outside.
  const auto clampTo = [](float value, int hi) {
    return static_cast<int>(std::clamp(value, -2.0f, static_cast<float>(hi) + 2.0f));
  };
  r.x0 = std::max(0, clampTo(std::floor(xmin), cam.width) - 1);
  r.x1 = std::min(cam.width - 1, clampTo(std::ceil(xmax), cam.width) + 1);
  r.y0 = std::max(0, clampTo(std::floor(ymin), cam.height) - 1);
  r.y1 = std::min(cam.height - 1, clampTo(std::ceil(ymax), cam.height) + 1);
  r.near_z = near_z;
  return r;
}

std::array<Eigen::Vector3f, 8> corners(const BoxInstance& box) {
  std::array<Eigen::Vector3f, 8> c;
  for (int i = 0; i < 8; ++i)
    c[static_cast<size_t>(i)] = {(i & 1) ? box.hi.x() : box.lo.x(),
                                 (i & 2) ? box.hi.y() : box.lo.y(),
                                 (i & 4) ? box.hi.z() : box.lo.z()};
  return c;
}

std::array<Eigen::Vector3f, 4> corners(const WalkerInstance& w) {
  const float lean = w.photo >= 0 ? kPhotoWalkerLean * w.height : 0.0f;
  const Eigen::Vector3f half = w.right * (w.width * 0.5f + lean);
  const Eigen::Vector3f up(0.0f, 0.0f, w.height);
  return {w.base - half, w.base + half, w.base - half + up, w.base + half + up};
}

// Texture coordinates (metres) of point p on a face of a box (see BoxInstance).
inline void faceUv(const BoxInstance& box, int face, const Eigen::Vector3f& p, float& u, float& v) {
  switch (face / 2) {
    case 0:
      u = p.y() - box.lo.y(), v = box.hi.z() - p.z();
      break;
    case 1:
      u = p.x() - box.lo.x(), v = box.hi.z() - p.z();
      break;
    default:
      u = p.x() - box.lo.x(), v = p.y() - box.lo.y();
      break;
  }
}

struct Hit {
  float t = std::numeric_limits<float>::max();  // = z-depth, rays have unit camera-z
  int kind = 0;                                 // 0 room, 1 box, 2 walker
  int index = 0;
  int face = 0;
};

float lightmapSample(const cv::Mat& map, float u, float v) {
  const float x = std::clamp(u * (1.0f / kLightmapCell), 0.0f, static_cast<float>(map.cols - 2));
  const float y = std::clamp(v * (1.0f / kLightmapCell), 0.0f, static_cast<float>(map.rows - 2));
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
  const float* r0 = map.ptr<float>(y0);
  const float* r1 = map.ptr<float>(y0 + 1);
  return (r0[x0] + fx * (r0[x0 + 1] - r0[x0])) * (1.0f - fy) +
         (r1[x0] + fx * (r1[x0 + 1] - r1[x0])) * fy;
}

// Everything the per-pixel loop needs of one camera pose: a global-shutter image has one,
// a rolling-shutter image one per row.
struct ViewSetup {
  Eigen::Matrix3f R_w_c;
  Eigen::Vector3f origin;
  std::vector<ScreenRect> box_rects;
  // Visible boxes nearest first, so a pixel stops testing once the boxes left start behind
  // its hit (equal distances keep scene order: the same image whatever the sort does).
  std::vector<int> box_order;
  std::vector<ScreenRect> walker_rects;
};

ViewSetup setupView(const SceneSnapshot& snapshot, const PinholeCamera& cam, const SE3& T_w_c) {
  ViewSetup view;
  view.R_w_c = T_w_c.linear().cast<float>();
  view.origin = T_w_c.translation().cast<float>();
  const Eigen::Matrix3f R_c_w = view.R_w_c.transpose();
  const Eigen::Vector3f t_c_w = -R_c_w * view.origin;
  for (const auto& box : snapshot.boxes)
    view.box_rects.push_back(projectBounds(corners(box), R_c_w, t_c_w, cam));
  for (int i = 0; i < static_cast<int>(view.box_rects.size()); ++i)
    if (!view.box_rects[static_cast<size_t>(i)].empty()) view.box_order.push_back(i);
  std::stable_sort(view.box_order.begin(), view.box_order.end(), [&](int a, int b) {
    return view.box_rects[static_cast<size_t>(a)].near_z <
           view.box_rects[static_cast<size_t>(b)].near_z;
  });
  for (const auto& w : snapshot.walkers)
    view.walker_rects.push_back(projectBounds(corners(w), R_c_w, t_c_w, cam));
  return view;
}

// Per-row scratch lists: boxes whose projected bounds cover each 32-pixel block of the row,
// and walkers whose bounds cover the row.
constexpr int kBlock = 32;
struct RowCandidates {
  std::vector<std::vector<int>> boxes_in_block;
  std::vector<int> walkers_in_row;
  explicit RowCandidates(int width) : boxes_in_block((width + kBlock - 1) / kBlock) {}
};

void collectCandidates(const ViewSetup& setup, int y, RowCandidates& c) {
  for (auto& block : c.boxes_in_block) block.clear();
  c.walkers_in_row.clear();
  for (const int i : setup.box_order) {
    const ScreenRect& r = setup.box_rects[static_cast<size_t>(i)];
    if (y < r.y0 || y > r.y1) continue;
    for (int b = r.x0 / kBlock; b <= r.x1 / kBlock; ++b)
      c.boxes_in_block[static_cast<size_t>(b)].push_back(i);
  }
  for (int i = 0; i < static_cast<int>(setup.walker_rects.size()); ++i)
    if (y >= setup.walker_rects[static_cast<size_t>(i)].y0 &&
        y <= setup.walker_rects[static_cast<size_t>(i)].y1)
      c.walkers_in_row.push_back(i);
}

// Where a ray (direction d with unit camera-z, inv its componentwise inverse) leaves the room.
Hit roomExit(const BoxInstance& room, const Eigen::Vector3f& origin, const Eigen::Vector3f& d,
             const Eigen::Vector3f& inv) {
  Hit hit;
  for (int a = 0; a < 3; ++a) {
    const float plane = d[a] > 0.0f ? room.hi[a] : room.lo[a];
    const float t = (plane - origin[a]) * inv[a];
    if (t > 0.0f && t < hit.t) hit = {t, 0, 0, a * 2 + (d[a] > 0.0f ? 1 : 0)};
  }
  return hit;
}

// Replaces `hit` by the nearest box of pixel x's block in front of it.
void hitBoxes(const SceneSnapshot& snapshot, const ViewSetup& setup,
              const RowCandidates& candidates, int x, const Eigen::Vector3f& d,
              const Eigen::Vector3f& inv, Hit& hit) {
  const Eigen::Vector3f& origin = setup.origin;
  for (const int i : candidates.boxes_in_block[static_cast<size_t>(x / kBlock)]) {
    const ScreenRect& r = setup.box_rects[static_cast<size_t>(i)];
    if (r.near_z >= hit.t) break;  // this and every later box lie behind the hit
    if (x < r.x0 || x > r.x1) continue;
    const BoxInstance& box = snapshot.boxes[static_cast<size_t>(i)];
    float t_near = 0.0f, t_far = hit.t;
    int near_axis = -1;
    bool miss = false;
    for (int a = 0; a < 3 && !miss; ++a) {
      float t0 = (box.lo[a] - origin[a]) * inv[a];
      float t1 = (box.hi[a] - origin[a]) * inv[a];
      if (t0 > t1) std::swap(t0, t1);
      if (t0 > t_near) t_near = t0, near_axis = a;
      t_far = std::min(t_far, t1);
      miss = t_near > t_far;
    }
    if (miss || near_axis < 0 || t_near >= hit.t) continue;
    hit = {t_near, 1, i, near_axis * 2 + (d[near_axis] > 0.0f ? 0 : 1)};
  }
}

// Replaces `hit` by the nearest walker of the row in front of it, with its texture coordinates.
void hitWalkers(const Scene& scene, const SceneSnapshot& snapshot, const ViewSetup& setup,
                const RowCandidates& candidates, int x, const Eigen::Vector3f& d, Hit& hit,
                WalkerTexel& walker_texel) {
  const Eigen::Vector3f& origin = setup.origin;
  for (const int i : candidates.walkers_in_row) {
    const ScreenRect& r = setup.walker_rects[static_cast<size_t>(i)];
    if (x < r.x0 || x > r.x1) continue;
    const WalkerInstance& w = snapshot.walkers[static_cast<size_t>(i)];
    const float denom = d.dot(w.normal);
    if (std::abs(denom) < 1e-6f) continue;
    const float t = (w.base - origin).dot(w.normal) / denom;
    if (t <= 0.0f || t >= hit.t) continue;
    const Eigen::Vector3f p = origin + t * d - w.base;
    const float u = p.dot(w.right), v = p.z();
    if (!scene.walkerCovers(w, u, v, walker_texel)) continue;
    hit = {t, 2, i, 0};
  }
}

// What the renderer needs of the surface at a hit.
struct Surface {
  cv::Vec3f albedo;
  Eigen::Vector3f normal;
  std::uint8_t id = 0;
  float light = -1.0f;  // baked light if the face has a lightmap
  float view_cosine = 1.0f;
};

Surface walkerSurface(const Scene& scene, const WalkerInstance& w, const Eigen::Vector3f& d,
                      float ray_length, float pixel_size, const WalkerTexel& walker_texel) {
  Surface s;
  s.view_cosine = std::abs(d.dot(w.normal)) / ray_length;
  const float cosine = std::max(0.2f, s.view_cosine);
  s.albedo = scene.texture(w.texture).sample(walker_texel.u, walker_texel.v,
                                             pixel_size / std::sqrt(cosine));
  s.normal = w.normal;
  s.id = w.object_id;
  return s;
}

Surface boxSurface(const Scene& scene, const SceneSnapshot& snapshot, const Hit& hit,
                   const Eigen::Vector3f& p, const Eigen::Vector3f& d, float ray_length,
                   float pixel_size) {
  Surface s;
  const BoxInstance& box =
      hit.kind == 0 ? snapshot.room : snapshot.boxes[static_cast<size_t>(hit.index)];
  const int axis = hit.face / 2;
  s.normal = Eigen::Vector3f::Zero();
  // Room faces point into the room, box faces out of the box.
  s.normal[axis] = (hit.face % 2 == 1) == (hit.kind == 0) ? -1.0f : 1.0f;
  float u = 0.0f, v = 0.0f;
  faceUv(box, hit.face, p, u, v);
  // Geometric mean of the footprint's two axes: little blur, little aliasing.
  s.view_cosine = std::abs(d[axis]) / ray_length;
  const float cosine = std::max(0.05f, s.view_cosine);
  s.albedo = scene.texture(box.textures[static_cast<size_t>(hit.face)])
                 .sample(u, v, pixel_size / std::sqrt(cosine));
  s.id = box.object_id;
  const int lightmap = box.lightmaps[static_cast<size_t>(hit.face)];
  if (lightmap >= 0) s.light = lightmapSample(scene.lightmap(lightmap), u, v);
  return s;
}

void renderRow(const Scene& scene, const SceneSnapshot& snapshot, const PinholeCamera& cam,
               const ViewSetup& setup, int y, RowCandidates& candidates, RenderedView& view) {
  collectCandidates(setup, y, candidates);
  const Eigen::Matrix3f& R_w_c = setup.R_w_c;
  const Eigen::Vector3f& origin = setup.origin;
  const float fx = static_cast<float>(cam.fx), fy = static_cast<float>(cam.fy);
  const float cx = static_cast<float>(cam.cx), cy = static_cast<float>(cam.cy);
  auto* radiance = view.radiance.ptr<cv::Vec3f>(y);
  auto* depth = view.depth.ptr<float>(y);
  auto* ids = view.object_ids.ptr<std::uint8_t>(y);
  auto* ir_albedo = view.ir_albedo.ptr<float>(y);
  auto* incidence = view.incidence_cos.ptr<float>(y);
  const Eigen::Vector3f row_dir = R_w_c.col(1) * ((static_cast<float>(y) - cy) / fy) + R_w_c.col(2);
  for (int x = 0; x < cam.width; ++x) {
    // Ray with unit camera-z component, so the hit parameter t is the z-depth.
    const Eigen::Vector3f d = row_dir + R_w_c.col(0) * ((static_cast<float>(x) - cx) / fx);
    const Eigen::Vector3f inv(1.0f / d.x(), 1.0f / d.y(), 1.0f / d.z());
    Hit hit = roomExit(snapshot.room, origin, d, inv);
    hitBoxes(snapshot, setup, candidates, x, d, inv, hit);
    WalkerTexel walker_texel;
    hitWalkers(scene, snapshot, setup, candidates, x, d, hit, walker_texel);

    const Eigen::Vector3f p = origin + hit.t * d;
    const float ray_length = d.norm();
    const float pixel_size = hit.t * ray_length * ray_length / fx;  // on a fronto-parallel plane
    Surface s = hit.kind == 2
                    ? walkerSurface(scene, snapshot.walkers[static_cast<size_t>(hit.index)], d,
                                    ray_length, pixel_size, walker_texel)
                    : boxSurface(scene, snapshot, hit, p, d, ray_length, pixel_size);
    if (s.light < 0.0f) s.light = staticLighting(snapshot.lights, snapshot.ambient, p, s.normal);
    if (snapshot.spot) s.light += spotLighting(*snapshot.spot, p, s.normal);
    // Textures are display-encoded (gamma ~2): square to linear reflectance.
    const cv::Vec3f reflectance(s.albedo[0] * s.albedo[0], s.albedo[1] * s.albedo[1],
                                s.albedo[2] * s.albedo[2]);
    radiance[x] = reflectance * s.light;
    depth[x] = hit.t;
    ids[x] = s.id;
    ir_albedo[x] = (reflectance[0] + reflectance[1] + reflectance[2]) * (1.0f / 3.0f);
    incidence[x] = s.view_cosine;
  }
}

}  // namespace

RenderedView renderView(const Scene& scene, const SceneSnapshot& snapshot, const PinholeCamera& cam,
                        const SE3& T_w_c) {
  return renderView(scene, snapshot, cam, RowPoses(T_w_c));
}

RenderedView renderView(const Scene& scene, const SceneSnapshot& snapshot, const PinholeCamera& cam,
                        const RowPoses& row_poses) {
  RenderedView view;
  view.radiance.create(cam.height, cam.width, CV_32FC3);
  view.depth.create(cam.height, cam.width, CV_32F);
  view.object_ids.create(cam.height, cam.width, CV_8U);
  view.ir_albedo.create(cam.height, cam.width, CV_32F);
  view.incidence_cos.create(cam.height, cam.width, CV_32F);

  std::vector<ViewSetup> setups(row_poses.global() ? 1 : static_cast<size_t>(cam.height));
  tbb::parallel_for(0, static_cast<int>(setups.size()), [&](int i) {
    setups[static_cast<size_t>(i)] = setupView(snapshot, cam, row_poses[i]);
  });
  tbb::parallel_for(
      tbb::blocked_range<int>(0, cam.height, 8), [&](const tbb::blocked_range<int>& rows) {
        RowCandidates candidates(cam.width);
        for (int y = rows.begin(); y < rows.end(); ++y)
          renderRow(scene, snapshot, cam, setups[row_poses.global() ? 0 : static_cast<size_t>(y)],
                    y, candidates, view);
      });
  return view;
}

}  // namespace lumaslam::synth
