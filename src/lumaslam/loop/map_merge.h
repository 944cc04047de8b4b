#pragma once
// Map merging (ORB-SLAM3's Atlas merge, for the loop closer): when a keyframe of one map
// recognises a place of another, the newer map moves rigidly (SE3; Sim3 for monocular, which
// also rescales it) into the older map's world and takes its id; the loop closer then fuses
// the duplicated points and optimises the essential graph of the joined map as for a loop.
#include "lumaslam/loop/loop_closer.h"
#include "lumaslam/map/map.h"
#include "lumaslam/optimize/sim3.h"

namespace lumaslam::loop {

struct MapMerge {
  map::MapId moved = 0;  // the newer map of the two
  map::MapId into = 0;   // the older one, whose world the joined map keeps
  // X_moved = S_wmoved_winto * X_into: the older map's world in the newer map's.
  optimize::Sim3 S_wmoved_winto{};
};

// The merge a match between keyframes of two maps asks for. The match's S_c_w is the current
// keyframe's pose in the loop keyframe's world.
MapMerge mergeFor(const LoopMatch& match);

// Moves every keyframe and point of `merge.moved` into the world of `merge.into` and relabels
// its keyframes. The caller holds the map's update mutex with local mapping paused.
void moveMapInto(map::Map& map, const MapMerge& merge);

}  // namespace lumaslam::loop
