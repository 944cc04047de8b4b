#include "lumaslam/viewer/map_snapshot.h"

#include <cmath>
#include <unordered_map>

#include <nlohmann/json.hpp>

namespace lumaslam::viewer {
namespace {

// Millimetres are enough for drawing and keep the JSON small.
double rounded(double value) {
  return std::round(value * 1000.0) / 1000.0;
}

struct KeyFrameTable {
  std::vector<std::shared_ptr<map::KeyFrame>> keyframes;
  std::unordered_map<map::Id, std::size_t> index_of;
};

KeyFrameTable goodKeyFrames(const map::Map& map) {
  KeyFrameTable table;
  for (auto& keyframe : map.keyFrames()) {
    if (keyframe->isBad()) continue;
    table.index_of.emplace(keyframe->id(), table.keyframes.size());
    table.keyframes.push_back(std::move(keyframe));
  }
  return table;
}

void addPoses(const KeyFrameTable& table, nlohmann::json& out) {
  auto& poses = out["poses"] = nlohmann::json::array();
  auto& maps = out["keyframe_maps"] = nlohmann::json::array();
  for (const auto& keyframe : table.keyframes) {
    const SE3 T_w_c = keyframe->T_w_c();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) poses.push_back(rounded(T_w_c.linear()(r, c)));
    }
    for (int r = 0; r < 3; ++r) poses.push_back(rounded(T_w_c.translation()(r)));
    maps.push_back(keyframe->mapId());
  }
}

// Each edge once (i < j).
void addEdges(const KeyFrameTable& table, const MapSnapshotLimits& limits, nlohmann::json& out) {
  auto& covisibility = out["covisibility"] = nlohmann::json::array();
  auto& loops = out["loops"] = nlohmann::json::array();
  const auto add = [&](nlohmann::json& edges, std::size_t i, const map::KeyFrame& other) {
    const auto j = table.index_of.find(other.id());
    if (j == table.index_of.end() || j->second <= i) return;
    edges.push_back(i);
    edges.push_back(j->second);
  };
  for (std::size_t i = 0; i < table.keyframes.size(); ++i) {
    const auto& keyframe = *table.keyframes[i];
    for (const auto& other : keyframe.covisiblesWithMinWeight(limits.min_covisibility_weight)) {
      add(covisibility, i, *other);
    }
    for (const auto& other : keyframe.loopEdges()) add(loops, i, *other);
  }
}

void addPoints(const map::Map& map, const KeyFrameTable& table, const MapSnapshotLimits& limits,
               nlohmann::json& out) {
  const auto points = map.mapPoints();
  const std::size_t stride = points.size() / std::max<std::size_t>(limits.max_points, 1) + 1;
  auto& xyz = out["points"] = nlohmann::json::array();
  auto& point_maps = out["point_maps"] = nlohmann::json::array();
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const auto& point = *points[i];
    if (point.isBad()) continue;
    const Eigen::Vector3d p = point.position();
    xyz.push_back(rounded(p.x()));
    xyz.push_back(rounded(p.y()));
    xyz.push_back(rounded(p.z()));
    const auto reference = table.index_of.find(point.referenceKeyFrameId());
    point_maps.push_back(
        reference == table.index_of.end() ? 0u : table.keyframes[reference->second]->mapId());
  }
}

}  // namespace

std::string mapSnapshotJson(const map::Map& map, const MapSnapshotLimits& limits) {
  const KeyFrameTable table = goodKeyFrames(map);
  nlohmann::json out;
  out["keyframes"] = table.keyframes.size();
  addPoses(table, out);
  addEdges(table, limits, out);
  addPoints(map, table, limits, out);
  return out.dump();
}

}  // namespace lumaslam::viewer
