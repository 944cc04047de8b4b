#pragma once
// The plain records a map file stores (map_file.h) and their cereal serialization, every length
// through sized() (bounded_lengths.h). Everything is by value and by id, so that reading a file
// builds nothing until it has been checked.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <cereal/types/array.hpp>
#include <cereal/types/string.hpp>
#include <cereal/types/utility.hpp>
#include <cereal/types/vector.hpp>

#include "lumaslam/map/bounded_lengths.h"
#include "lumaslam/map/ids.h"
#include "lumaslam/map/map_file.h"

namespace lumaslam::map {

inline constexpr Id kNoId = ~Id{0};

struct FeatureRecord {
  // keypoints as detected, one entry per feature in each vector
  std::vector<float> x, y, size, angle, response;
  std::vector<std::int32_t> octave, class_id;
  std::vector<float> undistorted_x, undistorted_y, u_right, depth;
  std::vector<std::uint8_t> descriptors;  // 32 bytes per feature
  std::vector<std::uint8_t> moving;
  std::array<float, 4> grid_bounds{};  // x, y, width, height
  std::int32_t grid_columns = 0, grid_rows = 0;
};

struct KeyFrameRecord {
  Id id = 0;
  std::uint64_t frame_index = 0;
  double timestamp = 0.0;
  MapId map_id = 0;
  std::array<double, 12> T_c_w{};      // rotation rows then translation
  std::array<double, 5> intrinsics{};  // fx fy cx cy bf
  FeatureRecord features;
  std::vector<Id> points;                                // per feature: map point id or kNoId
  std::vector<std::pair<Id, std::int32_t>> connections;  // keyframe id, weight
  Id parent = kNoId;
  std::vector<Id> children, loop_edges;
};

struct MapPointRecord {
  Id id = 0;
  Id reference = 0;
  std::array<double, 3> position{}, normal{};
  double min_distance = 0.0, max_distance = 0.0;
  Descriptor descriptor{};
  std::int32_t visible = 1, found = 1;
  std::vector<std::pair<Id, std::int32_t>> observations;  // keyframe id, feature index
};

struct MapRecord {
  Id next_keyframe_id = 0, next_point_id = 0;
  MapId next_map_id = 1;
  std::vector<std::pair<MapId, Id>> origins;
  std::vector<KeyFrameRecord> keyframes;  // sorted by id
  std::vector<MapPointRecord> points;     // sorted by id
};

template <class Archive>
void serialize(Archive& ar, MapFingerprint& f) {
  ar(sized(f.sensor), f.image_width, f.image_height, f.camera.fx, f.camera.fy, f.camera.cx,
     f.camera.cy, f.camera.bf, f.orb_features, f.orb_scale_factor, f.orb_levels, f.orb_ini_fast,
     f.orb_min_fast, f.vocabulary, sized(f.vocabulary_name));
}

template <class Archive>
void serialize(Archive& ar, FeatureRecord& f) {
  ar(sized(f.x), sized(f.y), sized(f.size), sized(f.angle), sized(f.response), sized(f.octave),
     sized(f.class_id), sized(f.undistorted_x), sized(f.undistorted_y), sized(f.u_right),
     sized(f.depth), sized(f.descriptors), sized(f.moving), f.grid_bounds, f.grid_columns,
     f.grid_rows);
}

template <class Archive>
void serialize(Archive& ar, KeyFrameRecord& k) {
  ar(k.id, k.frame_index, k.timestamp, k.map_id, k.T_c_w, k.intrinsics, k.features, sized(k.points),
     sized(k.connections), k.parent, sized(k.children), sized(k.loop_edges));
}

template <class Archive>
void serialize(Archive& ar, MapPointRecord& p) {
  ar(p.id, p.reference, p.position, p.normal, p.min_distance, p.max_distance, p.descriptor,
     p.visible, p.found, sized(p.observations));
}

template <class Archive>
void serialize(Archive& ar, MapRecord& m) {
  ar(m.next_keyframe_id, m.next_point_id, m.next_map_id, sized(m.origins), sized(m.keyframes),
     sized(m.points));
}

}  // namespace lumaslam::map
