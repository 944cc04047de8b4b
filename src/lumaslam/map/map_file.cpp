#include "lumaslam/map/map_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>
#include <cereal/archives/portable_binary.hpp>

#include "lumaslam/core/checksum.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/read_file.h"
#include "lumaslam/io/output_file.h"
#include "lumaslam/map/map_file_checks.h"
#include "lumaslam/map/map_file_records.h"

namespace lumaslam::map {

namespace {

constexpr std::array<char, 8> kMagic = {'L', 'U', 'M', 'A', 'M', 'A', 'P', '\0'};

struct Header {
  std::array<char, 8> magic = kMagic;
  std::uint32_t version = kMapFileVersion;
  std::uint32_t reserved = 0;
  std::uint64_t payload_size = 0;
  std::uint64_t checksum = 0;
};
static_assert(sizeof(Header) == 32);

// ---- map -> records ----------------------------------------------------------------------

FeatureRecord recordOf(const FeatureSet& features) {
  FeatureRecord r;
  for (const auto& kp : features.keypoints) {
    r.x.push_back(kp.pt.x);
    r.y.push_back(kp.pt.y);
    r.size.push_back(kp.size);
    r.angle.push_back(kp.angle);
    r.response.push_back(kp.response);
    r.octave.push_back(kp.octave);
    r.class_id.push_back(kp.class_id);
  }
  for (const auto& p : features.undistorted) {
    r.undistorted_x.push_back(p.x);
    r.undistorted_y.push_back(p.y);
  }
  r.u_right = features.u_right;
  r.depth = features.depth;
  const cv::Mat descriptors =
      features.descriptors.isContinuous() ? features.descriptors : features.descriptors.clone();
  r.descriptors.assign(descriptors.datastart, descriptors.dataend);
  r.moving = features.moving;
  if (features.grid) {
    const auto& b = features.grid->bounds();
    r.grid_bounds = {b.x, b.y, b.width, b.height};
    r.grid_columns = features.grid->columns();
    r.grid_rows = features.grid->rows();
  }
  return r;
}

std::vector<std::pair<Id, std::int32_t>> connectionsOf(const KeyFrame& keyframe) {
  std::vector<std::pair<Id, std::int32_t>> result;
  for (const auto& other : keyframe.covisibles()) {
    result.emplace_back(other->id(), keyframe.weight(other->id()));
  }
  std::sort(result.begin(), result.end());
  return result;
}

template <typename Range>
std::vector<Id> idsOf(const Range& keyframes) {
  std::vector<Id> ids;
  for (const auto& keyframe : keyframes) ids.push_back(keyframe->id());
  std::sort(ids.begin(), ids.end());
  return ids;
}

KeyFrameRecord recordOf(const KeyFrame& keyframe) {
  KeyFrameRecord r;
  r.id = keyframe.id();
  r.frame_index = keyframe.frameIndex();
  r.timestamp = keyframe.timestamp();
  r.map_id = keyframe.mapId();
  const SE3 T = keyframe.T_c_w();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r.T_c_w[3 * i + j] = T.linear()(i, j);
    r.T_c_w[9 + i] = T.translation()(i);
  }
  const auto& k = keyframe.intrinsics();
  r.intrinsics = {k.fx, k.fy, k.cx, k.cy, k.bf};
  r.features = recordOf(keyframe.features());
  for (const auto& point : keyframe.mapPoints()) {
    r.points.push_back(point && !point->isBad() ? point->id() : kNoId);
  }
  r.connections = connectionsOf(keyframe);
  if (const auto parent = keyframe.parent()) r.parent = parent->id();
  r.children = idsOf(keyframe.children());
  r.loop_edges = idsOf(keyframe.loopEdges());
  return r;
}

MapPointRecord recordOf(const MapPoint& point) {
  MapPointRecord r;
  r.id = point.id();
  r.reference = point.referenceKeyFrameId();
  const Eigen::Vector3d position = point.position();
  const auto derived = point.derivedState();
  for (int i = 0; i < 3; ++i) {
    r.position[i] = position(i);
    r.normal[i] = derived.normal(i);
  }
  r.min_distance = derived.min_distance;
  r.max_distance = derived.max_distance;
  r.descriptor = derived.descriptor;
  r.visible = derived.visible;
  r.found = derived.found;
  for (const auto& [keyframe, index] : point.observations()) {
    r.observations.emplace_back(keyframe->id(), index);
  }
  std::sort(r.observations.begin(), r.observations.end());
  return r;
}

// Only what is in the map: references to retired objects are dropped, so the file is closed.
MapRecord recordOf(const Map& map) {
  MapRecord r;
  const auto bookkeeping = map.bookkeeping();
  r.next_keyframe_id = bookkeeping.next_keyframe_id;
  r.next_point_id = bookkeeping.next_point_id;
  r.next_map_id = bookkeeping.next_map_id;
  r.origins = bookkeeping.origins;
  for (const auto& keyframe : map.keyFrames()) r.keyframes.push_back(recordOf(*keyframe));
  for (const auto& point : map.mapPoints()) r.points.push_back(recordOf(*point));
  std::unordered_set<Id> keyframes, points;
  for (const auto& k : r.keyframes) keyframes.insert(k.id);
  for (const auto& p : r.points) points.insert(p.id);
  const auto missing_keyframe = [&](Id id) { return !keyframes.contains(id); };
  for (auto& k : r.keyframes) {
    for (auto& id : k.points) {
      if (id != kNoId && !points.contains(id)) id = kNoId;
    }
    std::erase_if(k.connections, [&](const auto& c) { return missing_keyframe(c.first); });
    if (k.parent != kNoId && missing_keyframe(k.parent)) k.parent = kNoId;
    std::erase_if(k.children, missing_keyframe);
    std::erase_if(k.loop_edges, missing_keyframe);
  }
  for (auto& p : r.points) {
    std::erase_if(p.observations, [&](const auto& o) { return missing_keyframe(o.first); });
  }
  return r;
}

// ---- bytes -------------------------------------------------------------------------------

std::string encode(const MapFingerprint& fingerprint, MapRecord& record) {
  std::ostringstream payload_stream(std::ios::binary);
  {
    cereal::PortableBinaryOutputArchive archive(payload_stream);
    archive(fingerprint, record);
  }
  const std::string payload = payload_stream.str();
  Header header;
  header.payload_size = payload.size();
  core::Checksum checksum;
  checksum.update(payload.data(), payload.size());
  header.checksum = checksum.value();
  std::string bytes(sizeof(header), '\0');
  std::memcpy(bytes.data(), &header, sizeof(header));
  return bytes + payload;
}

// The payload after the header checks: a clear message for each way a file can be wrong.
std::string_view checkedPayload(const std::string& bytes, const std::string& name) {
  Header header;
  if (bytes.size() < sizeof(header) ||
      std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0) {
    fail("{}: not a lumaslam map file (no LUMAMAP header)", name);
  }
  std::memcpy(&header, bytes.data(), sizeof(header));
  if (header.version != kMapFileVersion) {
    fail("{}: map file format version {}, this lumaslam reads version {}", name, header.version,
         kMapFileVersion);
  }
  const std::uint64_t available = bytes.size() - sizeof(header);
  if (available < header.payload_size) {
    fail("{}: truncated map file ({} of {} bytes)", name, bytes.size(),
         sizeof(header) + header.payload_size);
  }
  if (available > header.payload_size) {
    fail("{}: {} unexpected bytes after the map", name, available - header.payload_size);
  }
  const std::string_view payload(bytes.data() + sizeof(header), header.payload_size);
  core::Checksum checksum;
  checksum.update(payload.data(), payload.size());
  if (checksum.value() != header.checksum) {
    fail("{}: checksum mismatch (stored {:016x}, computed {:016x}): the map file is corrupt", name,
         header.checksum, checksum.value());
  }
  return payload;
}

struct Decoded {
  MapFingerprint fingerprint;
  MapRecord record;
};

Decoded decode(const std::string& bytes, const std::string& name) {
  const std::string_view payload = checkedPayload(bytes, name);
  Decoded decoded;
  try {
    std::istringstream in(std::string(payload), std::ios::binary);
    BoundedInputArchive archive(in, payload.size());
    archive(decoded.fingerprint, decoded.record);
  } catch (const std::exception& e) {
    fail("{}: malformed map content ({})", name, e.what());
  }
  return decoded;
}

// ---- records -> map ----------------------------------------------------------------------

std::shared_ptr<FeatureSet> featuresFrom(const FeatureRecord& r) {
  auto features = std::make_shared<FeatureSet>();
  const std::size_t n = r.x.size();
  std::vector<cv::KeyPoint> undistorted_keypoints;
  for (std::size_t i = 0; i < n; ++i) {
    features->keypoints.emplace_back(cv::Point2f(r.x[i], r.y[i]), r.size[i], r.angle[i],
                                     r.response[i], r.octave[i], r.class_id[i]);
    features->undistorted.emplace_back(r.undistorted_x[i], r.undistorted_y[i]);
    undistorted_keypoints.push_back(features->keypoints.back());
    undistorted_keypoints.back().pt = features->undistorted.back();
  }
  features->u_right = r.u_right;
  features->depth = r.depth;
  features->descriptors = cv::Mat(static_cast<int>(n), 32, CV_8U);
  if (n > 0) std::memcpy(features->descriptors.data, r.descriptors.data(), r.descriptors.size());
  features->moving = r.moving;
  if (r.grid_columns > 0 && r.grid_rows > 0) {
    const cv::Rect2f bounds(r.grid_bounds[0], r.grid_bounds[1], r.grid_bounds[2], r.grid_bounds[3]);
    features->grid = std::make_shared<const feature::FeatureGrid>(
        std::move(undistorted_keypoints), bounds, r.grid_columns, r.grid_rows);
  }
  return features;
}

SE3 poseFrom(const std::array<double, 12>& m) {
  SE3 T = SE3::Identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) T.linear()(i, j) = m[3 * i + j];
    T.translation()(i) = m[9 + i];
  }
  return T;
}

using KeyFrames = std::unordered_map<Id, std::shared_ptr<KeyFrame>>;
using MapPoints = std::unordered_map<Id, std::shared_ptr<MapPoint>>;

KeyFrames keyFramesFrom(const MapRecord& r,
                        const std::shared_ptr<const feature::ScaleLevels>& pyramid) {
  KeyFrames keyframes;
  for (const auto& k : r.keyframes) {
    const CameraIntrinsics intrinsics{k.intrinsics[0], k.intrinsics[1], k.intrinsics[2],
                                      k.intrinsics[3], k.intrinsics[4]};
    auto keyframe = std::make_shared<KeyFrame>(k.id, k.frame_index, k.timestamp, poseFrom(k.T_c_w),
                                               featuresFrom(k.features), pyramid, intrinsics);
    keyframe->setMapId(k.map_id);
    keyframes.emplace(k.id, std::move(keyframe));
  }
  return keyframes;
}

MapPoints mapPointsFrom(const MapRecord& r, const KeyFrames& keyframes) {
  MapPoints points;
  for (const auto& p : r.points) {
    const auto reference = keyframes.find(p.reference);
    auto point = std::make_shared<MapPoint>(
        p.id, Eigen::Vector3d(p.position[0], p.position[1], p.position[2]), p.reference,
        reference == keyframes.end() ? nullptr : reference->second);
    for (const auto& [keyframe, index] : p.observations) {
      point->addObservation(keyframes.at(keyframe), index);
    }
    point->restoreDerivedState({Eigen::Vector3d(p.normal[0], p.normal[1], p.normal[2]),
                                p.min_distance, p.max_distance, p.descriptor, p.visible, p.found});
    points.emplace(p.id, std::move(point));
  }
  return points;
}

void linkKeyFrames(const MapRecord& r, const KeyFrames& keyframes, const MapPoints& points) {
  for (const auto& k : r.keyframes) {
    const auto& keyframe = keyframes.at(k.id);
    for (std::size_t i = 0; i < k.points.size(); ++i) {
      if (k.points[i] != kNoId) keyframe->setMapPoint(i, points.at(k.points[i]));
    }
    for (const auto& [other, weight] : k.connections) {
      keyframe->addConnection(keyframes.at(other), weight);
    }
    if (k.parent != kNoId) keyframe->setParent(keyframes.at(k.parent));
    for (const Id child : k.children) keyframe->addChild(keyframes.at(child));
    for (const Id other : k.loop_edges) keyframe->addLoopEdge(keyframes.at(other));
  }
}

void install(const MapRecord& r, const KeyFrames& keyframes, const MapPoints& points, Map& map) {
  for (const auto& k : r.keyframes) map.addKeyFrame(keyframes.at(k.id));  // in id order
  for (const auto& p : r.points) map.addMapPoint(points.at(p.id));
  map.restoreBookkeeping({r.next_keyframe_id, r.next_point_id, r.next_map_id, r.origins});
}

std::string describe(double map_value, double run_value) {
  return fmt::format("map {}, this run {}", map_value, run_value);
}

}  // namespace

std::vector<std::string> MapFingerprint::differences(const MapFingerprint& run) const {
  std::vector<std::string> result;
  const auto compare = [&](const char* what, double map_value, double run_value) {
    if (map_value != run_value)
      result.push_back(fmt::format("{}: {}", what, describe(map_value, run_value)));
  };
  if (sensor != run.sensor) {
    result.push_back(fmt::format("sensor: map {}, this run {}", sensor, run.sensor));
  }
  compare("image width", image_width, run.image_width);
  compare("image height", image_height, run.image_height);
  compare("camera fx", camera.fx, run.camera.fx);
  compare("camera fy", camera.fy, run.camera.fy);
  compare("camera cx", camera.cx, run.camera.cx);
  compare("camera cy", camera.cy, run.camera.cy);
  compare("camera bf", camera.bf, run.camera.bf);
  compare("ORBextractor.nFeatures", orb_features, run.orb_features);
  compare("ORBextractor.scaleFactor", orb_scale_factor, run.orb_scale_factor);
  compare("ORBextractor.nLevels", orb_levels, run.orb_levels);
  compare("ORBextractor.iniThFAST", orb_ini_fast, run.orb_ini_fast);
  compare("ORBextractor.minThFAST", orb_min_fast, run.orb_min_fast);
  if (vocabulary != run.vocabulary) {
    result.push_back(fmt::format("vocabulary: map {} ({:016x}), this run {} ({:016x})",
                                 vocabulary_name.empty() ? "none" : vocabulary_name, vocabulary,
                                 run.vocabulary_name.empty() ? "none" : run.vocabulary_name,
                                 run.vocabulary));
  }
  return result;
}

void saveMapFile(const Map& map, const MapFingerprint& fingerprint,
                 const std::filesystem::path& file) {
  MapRecord record = recordOf(map);
  const std::string bytes = encode(fingerprint, record);
  io::OutputFile out(file);
  out.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.commit();
}

void loadMapFile(const std::filesystem::path& file, const MapFingerprint& run,
                 std::shared_ptr<const feature::ScaleLevels> pyramid, Map& map) {
  const std::string name = file.string();
  if (map.keyFrameCount() > 0) fail("{}: a map file can only be loaded into an empty map", name);
  const Decoded decoded = decode(core::readWholeFile(file, "map file"), name);
  if (const auto differences = decoded.fingerprint.differences(run); !differences.empty()) {
    std::string lines;
    for (const auto& d : differences) lines += "\n  " + d;
    fail("{}: the map was made with other settings than this run's:{}", name, lines);
  }
  checkMapRecord(decoded.fingerprint, decoded.record, name);
  const auto keyframes = keyFramesFrom(decoded.record, pyramid);
  const auto points = mapPointsFrom(decoded.record, keyframes);
  linkKeyFrames(decoded.record, keyframes, points);
  install(decoded.record, keyframes, points, map);
}

MapFileInfo readMapFileInfo(const std::filesystem::path& file) {
  const std::string name = file.string();
  const std::string bytes = core::readWholeFile(file, "map file");
  const Decoded decoded = decode(bytes, name);
  checkMapRecord(decoded.fingerprint, decoded.record, name);
  MapFileInfo info;
  info.version = kMapFileVersion;
  info.bytes = bytes.size();
  info.fingerprint = decoded.fingerprint;
  info.keyframes = decoded.record.keyframes.size();
  info.points = decoded.record.points.size();
  std::map<MapId, std::size_t> per_map;
  bool first = true;
  for (const auto& k : decoded.record.keyframes) {
    if (k.map_id == kDiscardedMap) continue;
    ++per_map[k.map_id];
    const Eigen::Vector3d centre = poseFrom(k.T_c_w).inverse().translation();
    info.centre_min = first ? centre : info.centre_min.cwiseMin(centre);
    info.centre_max = first ? centre : info.centre_max.cwiseMax(centre);
    info.first_timestamp = first ? k.timestamp : std::min(info.first_timestamp, k.timestamp);
    info.last_timestamp = first ? k.timestamp : std::max(info.last_timestamp, k.timestamp);
    first = false;
  }
  info.maps.assign(per_map.begin(), per_map.end());
  return info;
}

}  // namespace lumaslam::map
