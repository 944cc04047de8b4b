#pragma once
// The 3D map as the viewer's page draws it, read from the map in the viewer's thread (the
// map's own locks make that safe; see map/map.h): points, keyframe poses, covisibility and
// loop edges, each keyframe's and point's map of the atlas.
#include <cstddef>
#include <string>

#include "lumaslam/map/map.h"

namespace lumaslam::viewer {

struct MapSnapshotLimits {
  std::size_t max_points = 60000;     // more are thinned evenly (the page stays responsive)
  int min_covisibility_weight = 100;  // ORB-SLAM's viewer draws edges of weight >= 100
};

// JSON: {"keyframes": N, "points": [x,y,z,...], "point_maps": [...], "poses": [r00..r22 t0..t2,
// ...] (T_w_c of each keyframe, row-major rotation then translation), "keyframe_maps": [...],
// "covisibility": [i,j,...], "loops": [i,j,...]} with i,j indices into the keyframes.
std::string mapSnapshotJson(const map::Map& map, const MapSnapshotLimits& limits = {});

}  // namespace lumaslam::viewer
