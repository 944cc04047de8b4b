#pragma once
// Map files: the whole atlas of a run (keyframes with poses, keypoints, descriptors and depth;
// map points; covisibility, spanning tree and loop edges; each map's origin and the id
// counters) so that a later run can localize in it or extend it (docs/maps.md).
//
// Layout, little-endian: char[8] "LUMAMAP\0" | u32 version | u32 reserved (0) | u64 payload
// size | u64 checksum (core::Checksum over the payload) | payload: a cereal portable binary
// archive of the fingerprint, then the map. Written to FILE.partial and renamed into place.
// The place-recognition database is not stored: the loading Pipeline rebuilds it from the
// stored descriptors with the vocabulary the fingerprint names (the same BoW vectors; a few
// ms per 100 keyframes), so that a map and a database can never disagree.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/map/map.h"

namespace lumaslam::map {

inline constexpr std::uint32_t kMapFileVersion = 1;

// What a map was made with: a map is only usable with the same camera, ORB settings and
// vocabulary (keypoints, scale levels and BoW words would mean something else).
struct MapFingerprint {
  std::string sensor;  // "rgbd", "stereo", "monocular"
  int image_width = 0;
  int image_height = 0;
  CameraIntrinsics camera;  // the camera tracking works in (rectified for a stereo pair)
  int orb_features = 0;
  float orb_scale_factor = 0.0F;
  int orb_levels = 0;
  int orb_ini_fast = 0;
  int orb_min_fast = 0;
  std::uint64_t vocabulary = 0;  // loop::vocabularyFingerprint; 0: made without one
  std::string vocabulary_name;   // the file's name when saved (shown, not compared)

  // One line per difference ("camera fx: map 525.000, this run 520.000"); empty when usable.
  std::vector<std::string> differences(const MapFingerprint& run) const;
};

struct MapFileInfo {
  std::uint32_t version = 0;
  std::uintmax_t bytes = 0;
  MapFingerprint fingerprint;
  std::size_t keyframes = 0;
  std::size_t points = 0;
  std::vector<std::pair<MapId, std::size_t>> maps;  // keyframes per map (discarded ones left out)
  Eigen::Vector3d centre_min = Eigen::Vector3d::Zero();  // bounding box of keyframe centres
  Eigen::Vector3d centre_max = Eigen::Vector3d::Zero();
  double first_timestamp = 0.0;
  double last_timestamp = 0.0;
};

// The caller keeps the map still while it is written (no tracking, mapping or loop closing).
// Throws Error naming the file on any write failure; an old FILE is then left as it was.
void saveMapFile(const Map& map, const MapFingerprint& fingerprint,
                 const std::filesystem::path& file);

// Reads and checks the whole file (magic, version, size, checksum, structure) and its
// fingerprint against `run` before touching `map`, which must be empty: any problem is an
// Error naming the file and the problem, and `map` stays empty. `pyramid`: the run's scale
// levels (the fingerprint guarantees they are the map's).
void loadMapFile(const std::filesystem::path& file, const MapFingerprint& run,
                 std::shared_ptr<const feature::ScaleLevels> pyramid, Map& map);

// The checked file's header and contents in numbers (`lumaslam map info`).
MapFileInfo readMapFileInfo(const std::filesystem::path& file);

}  // namespace lumaslam::map
