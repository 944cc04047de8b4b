#pragma once
// Loop candidate detection (ORB-SLAM's LoopClosing::DetectLoop):
//  1. the lowest BoW score between the new keyframe and its covisible neighbours is the bar
//     a loop candidate must pass (places seen from a neighbour look at least this similar);
//  2. the keyframe database returns candidates above that bar, excluding the keyframe's
//     connected keyframes, grouped by covisibility;
//  3. a candidate is accepted only when its covisibility group (candidate + neighbours) is
//     connected to a group that was a candidate for each of the previous
//     `consistency_threshold` keyframes, i.e. the place was recognised consecutively.
// Reads the map and database only; keeps the consistent groups between calls.
#include <memory>
#include <set>
#include <vector>

#include "lumaslam/loop/keyframe_database.h"
#include "lumaslam/map/map.h"

namespace lumaslam::loop {

struct LoopDetectorParams {
  int consistency_threshold = 3;  // ORB-SLAM: 3 consecutive keyframes
  int score_neighbours = 0;       // 0: all covisibles (min weight 15) set the score bar
  int group_neighbours = 10;      // covisibles that form a candidate's group (ORB-SLAM: 10)
};

struct LoopDetection {
  int candidates = 0;  // database candidates before the consistency check
  std::vector<std::shared_ptr<map::KeyFrame>> consistent;  // candidates passing it
};

class LoopDetector {
 public:
  // Keeps references: both must outlive the detector.
  LoopDetector(const KeyFrameDatabase& database, const map::Map& map,
               const LoopDetectorParams& params = {});

  // `keyframe` must have a database entry (otherwise nothing is detected).
  LoopDetection detect(const std::shared_ptr<map::KeyFrame>& keyframe);
  // Forget the consistency history (e.g. after a loop was closed).
  void reset() { groups_.clear(); }

 private:
  struct ConsistentGroup {
    std::set<map::Id> keyframes;
    int consistency = 0;
  };

  const KeyFrameDatabase& database_;
  const map::Map& map_;
  LoopDetectorParams params_;
  std::vector<ConsistentGroup> groups_;
};

}  // namespace lumaslam::loop
