#include "lumaslam/mapping/point_fusion.h"

#include "lumaslam/feature/hamming.h"
#include "lumaslam/mapping/triangulation.h"

namespace lumaslam::mapping {

int fusePointsInto(map::Map& map, const std::shared_ptr<map::KeyFrame>& target,
                   const std::vector<std::shared_ptr<map::MapPoint>>& points, float radius) {
  const auto& features = target->features();
  if (!features.grid) return 0;
  const SE3 T_c_w = target->T_c_w();
  const Eigen::Vector3d center = target->center();
  const auto& k = target->intrinsics();
  const auto& pyramid = target->pyramid();
  const auto& bounds = features.grid->bounds();
  int fused = 0;
  for (const auto& point : points) {
    if (!point || point->isBad() || point->featureIndexIn(target->id()) >= 0) continue;
    const Eigen::Vector3d X_w = point->position();
    const Eigen::Vector3d X_c = T_c_w * X_w;
    if (X_c.z() <= 0) continue;
    const double u = k.fx * X_c.x() / X_c.z() + k.cx;
    const double v = k.fy * X_c.y() / X_c.z() + k.cy;
    if (!bounds.contains(cv::Point2f(static_cast<float>(u), static_cast<float>(v)))) continue;
    const Eigen::Vector3d ray = X_w - center;
    const double distance = ray.norm();
    if (distance < point->minDistance() || distance > point->maxDistance()) continue;
    if (ray.dot(point->normal()) < 0.5 * distance) continue;
    const int level = point->predictScale(distance, pyramid);
    const float window = radius * static_cast<float>(pyramid.scale(level));
    const auto candidates = features.grid->featuresInArea(
        cv::Point2f(static_cast<float>(u), static_cast<float>(v)), window);
    const auto descriptor = point->descriptor();
    int best = feature::kThLow + 1;
    int best_index = -1;
    for (const std::size_t i : candidates) {
      const int octave = features.keypoints[i].octave;
      if (octave < level - 1 || octave > level || features.isMoving(i)) continue;
      const Eigen::Vector2d uv(features.undistorted[i].x, features.undistorted[i].y);
      if (!reprojectionAcceptable(X_w, T_c_w, k, uv, features.u_right[i], pyramid.sigma2(octave))) {
        continue;
      }
      const int d = feature::hammingDistance(
          descriptor.data(), features.descriptors.ptr<std::uint8_t>(static_cast<int>(i)));
      if (d < best) {
        best = d;
        best_index = static_cast<int>(i);
      }
    }
    if (best_index < 0) continue;
    const auto slot = static_cast<std::size_t>(best_index);
    if (auto existing = target->mapPoint(slot); existing && !existing->isBad()) {
      if (existing->observationCount() > point->observationCount()) {
        map.replaceMapPoint(point, existing);
      } else {
        map.replaceMapPoint(existing, point);
      }
    } else {
      point->addObservation(target, best_index);
      target->setMapPoint(slot, point);
    }
    ++fused;
  }
  return fused;
}

}  // namespace lumaslam::mapping
