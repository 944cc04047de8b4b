#include "lumaslam/map/map_file_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>
#include <Eigen/Core>

#include "lumaslam/core/error.h"
#include "lumaslam/feature/orb_settings.h"

namespace lumaslam::map {
namespace {

template <class Values>
bool allFinite(const Values& values) {
  return std::all_of(std::begin(values), std::end(values),
                     [](double v) { return std::isfinite(v); });
}

void checkFingerprint(const MapFingerprint& f, const std::string& name) {
  constexpr int kMaxSide = 1 << 15;
  if (f.image_width < 1 || f.image_width > kMaxSide || f.image_height < 1 ||
      f.image_height > kMaxSide) {
    fail("{}: image size {}x{} (each side 1-{} pixels)", name, f.image_width, f.image_height,
         kMaxSide);
  }
  const auto& k = f.camera;
  if (!allFinite(std::array{k.fx, k.fy, k.cx, k.cy, k.bf}) || !(k.fx > 0.0) || !(k.fy > 0.0)) {
    fail("{}: camera fx {} fy {} cx {} cy {} bf {} (finite, focal lengths > 0)", name, k.fx, k.fy,
         k.cx, k.cy, k.bf);
  }
  feature::OrbSettings orb;
  orb.nFeatures = f.orb_features;
  orb.scaleFactor = f.orb_scale_factor;
  orb.nLevels = f.orb_levels;
  orb.iniThFAST = f.orb_ini_fast;
  orb.minThFAST = f.orb_min_fast;
  if (const auto problem = orb.firstProblem()) {
    fail("{}: the map's {} {}", name, problem->key, problem->why);
  }
}

void checkFeatureArrays(const FeatureRecord& f, const std::string& what) {
  const std::size_t n = f.x.size();
  const bool sizes_agree =
      f.y.size() == n && f.size.size() == n && f.angle.size() == n && f.response.size() == n &&
      f.octave.size() == n && f.class_id.size() == n && f.undistorted_x.size() == n &&
      f.undistorted_y.size() == n && f.u_right.size() == n && f.depth.size() == n &&
      f.descriptors.size() == 32 * n && (f.moving.empty() || f.moving.size() == n);
  if (!sizes_agree) fail("{}: feature arrays of different lengths", what);
  // Grids are feature::FeatureGrid's 64 x 48 cells; a corrupt count must not allocate gigabytes.
  constexpr std::int64_t kMaxGridCells = 1 << 16;
  const bool no_grid = f.grid_columns == 0 && f.grid_rows == 0;
  const bool grid_ok =
      no_grid || (f.grid_columns > 0 && f.grid_rows > 0 &&
                  std::int64_t{f.grid_columns} * f.grid_rows <= kMaxGridCells &&
                  allFinite(f.grid_bounds) && f.grid_bounds[2] > 0.0F && f.grid_bounds[3] > 0.0F);
  if (!grid_ok) {
    fail("{}: feature grid of {}x{} cells over {}x{} pixels (at most {} cells)", what,
         f.grid_columns, f.grid_rows, f.grid_bounds[2], f.grid_bounds[3], kMaxGridCells);
  }
}

// Keypoints are detected in the image (pixel centres 0..side-1) at a pyramid level the map's ORB
// settings have; tracking indexes the pyramid's scale tables with the level.
void checkKeypoints(const FeatureRecord& f, const MapFingerprint& fingerprint,
                    const std::string& what) {
  const auto inside = [](float v, int side) { return v >= 0.0F && v <= static_cast<float>(side); };
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    if (!inside(f.x[i], fingerprint.image_width) || !inside(f.y[i], fingerprint.image_height)) {
      fail("{}: keypoint {} at ({}, {}) is outside the {}x{} image", what, i, f.x[i], f.y[i],
           fingerprint.image_width, fingerprint.image_height);
    }
    if (f.octave[i] < 0 || f.octave[i] >= fingerprint.orb_levels) {
      fail("{}: keypoint {} at pyramid level {} (the map has levels 0-{})", what, i, f.octave[i],
           fingerprint.orb_levels - 1);
    }
    const bool finite =
        allFinite(std::array{f.size[i], f.angle[i], f.response[i], f.undistorted_x[i],
                             f.undistorted_y[i], f.u_right[i], f.depth[i]});
    if (!finite) fail("{}: keypoint {} has a value that is not a finite number", what, i);
  }
}

// A rotation drifts from orthonormal only by rounding; a written pose far from one is not a pose.
bool isPose(const std::array<double, 12>& m) {
  if (!allFinite(m)) return false;
  const Eigen::Matrix3d R =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m.data());
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6 &&
         R.determinant() > 0.0;
}

void checkKeyFrameValues(const KeyFrameRecord& k, const MapFingerprint& fingerprint,
                         const std::string& what) {
  if (!std::isfinite(k.timestamp)) fail("{}: timestamp {}", what, k.timestamp);
  if (!isPose(k.T_c_w)) fail("{}: the pose is not a finite rotation and translation", what);
  const auto& c = k.intrinsics;
  if (!allFinite(c) || !(c[0] > 0.0) || !(c[1] > 0.0)) {
    fail("{}: camera fx {} fy {} cx {} cy {} bf {} (finite, focal lengths > 0)", what, c[0], c[1],
         c[2], c[3], c[4]);
  }
  checkKeypoints(k.features, fingerprint, what);
}

void checkPointValues(const MapPointRecord& p, const std::string& name) {
  const bool ok = allFinite(p.position) && allFinite(p.normal) && std::isfinite(p.min_distance) &&
                  std::isfinite(p.max_distance) && p.min_distance >= 0.0 &&
                  p.max_distance >= p.min_distance && p.visible >= 0 && p.found >= 0;
  if (!ok) {
    fail(
        "{}: map point {}: position, normal, distance range [{}, {}] or counts {}/{} out of "
        "range",
        name, p.id, p.min_distance, p.max_distance, p.found, p.visible);
  }
}

void checkIds(const MapRecord& r, const std::string& name) {
  std::unordered_map<Id, std::size_t> feature_counts;
  std::unordered_set<Id> points;
  for (const auto& k : r.keyframes) {
    const std::string what = fmt::format("{}: keyframe {}", name, k.id);
    if (k.points.size() != k.features.x.size()) fail("{}: {} point slots", what, k.points.size());
    if (!feature_counts.emplace(k.id, k.features.x.size()).second) fail("{} twice", what);
  }
  for (const auto& p : r.points) {
    if (!points.insert(p.id).second) fail("{}: map point {} twice", name, p.id);
    for (const auto& [keyframe, index] : p.observations) {
      const auto it = feature_counts.find(keyframe);
      if (it == feature_counts.end() || index < 0 || static_cast<std::size_t>(index) >= it->second)
        fail("{}: map point {} observed by unknown feature {} of keyframe {}", name, p.id, index,
             keyframe);
    }
  }
  const auto known = [&](Id id) { return feature_counts.contains(id); };
  for (const auto& k : r.keyframes) {
    for (const Id id : k.points) {
      if (id != kNoId && !points.contains(id))
        fail("{}: keyframe {} refers to unknown map point {}", name, k.id, id);
    }
    const bool graph_known = std::all_of(k.connections.begin(), k.connections.end(),
                                         [&](const auto& c) { return known(c.first); }) &&
                             (k.parent == kNoId || known(k.parent)) &&
                             std::all_of(k.children.begin(), k.children.end(), known) &&
                             std::all_of(k.loop_edges.begin(), k.loop_edges.end(), known);
    if (!graph_known) fail("{}: keyframe {} is linked to an unknown keyframe", name, k.id);
  }
}

}  // namespace

void checkMapRecord(const MapFingerprint& fingerprint, const MapRecord& record,
                    const std::string& name) {
  checkFingerprint(fingerprint, name);
  for (const auto& k : record.keyframes) {
    checkFeatureArrays(k.features, fmt::format("{}: keyframe {}", name, k.id));
  }
  checkIds(record, name);
  for (const auto& k : record.keyframes) {
    checkKeyFrameValues(k, fingerprint, fmt::format("{}: keyframe {}", name, k.id));
  }
  for (const auto& p : record.points) checkPointValues(p, name);
}

}  // namespace lumaslam::map
