#pragma once
// Relocalization (ORB-SLAM's Tracking::Relocalization) for a frame with no usable pose prior:
// BoW candidates from the keyframe database, descriptor matching within the direct index
// (SearchByBoW), EPnP + RANSAC on the 2D-3D matches, pose-only refinement, then projection
// search of the candidate's other map points for more matches. Accepted with >= 50 inliers.
// Works on the map and database as they are; never writes to either.
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/core/pose.h"
#include "lumaslam/feature/hamming.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/loop/keyframe_database.h"
#include "lumaslam/loop/pose_matching.h"
#include "lumaslam/loop/vocabulary.h"
#include "lumaslam/map/feature_set.h"
#include "lumaslam/map/map.h"

namespace lumaslam::loop {

struct RelocalizerParams {
  int direct_index_levels_up = 4;  // FeatureVector level for SearchByBoW (ORB-SLAM: 4)
  int max_candidates = 10;         // keyframes tried, best BoW groups first
  int min_bow_matches = 15;        // fewer: candidate skipped (ORB-SLAM: 15)
  float bow_ratio = 0.75F;         // nearest / second nearest (ORB-SLAM's relocalization: 0.75)
  int bow_max_distance = feature::kThLow;
  int pnp_iterations = 300;
  float pnp_reprojection_px = 4.0F;  // RANSAC inlier threshold (level-0 pixels)
  int min_pnp_inliers = 10;
  int min_inliers = 50;  // after refinement (ORB-SLAM: 50)
};

// The frame to relocalize: its features (with a FeatureGrid), camera and pyramid.
using RelocalizationFrame = MatchingFrame;

struct RelocalizationResult {
  bool success = false;
  SE3 T_c_w = SE3::Identity();
  // Per feature of the frame: the matched map point (inliers only), null elsewhere.
  std::vector<std::shared_ptr<map::MapPoint>> points;
  int inliers = 0;
  map::Id keyframe = 0;  // the candidate that gave the pose
  int candidates = 0;    // BoW candidates returned by the database
  int tried = 0;         // candidates that reached PnP
};

class Relocalizer {
 public:
  // Keeps references: the three must outlive the Relocalizer.
  Relocalizer(const Vocabulary& vocabulary, const KeyFrameDatabase& database, const map::Map& map,
              const RelocalizerParams& params = {});

  // Throws Error if the frame lacks features, a grid or a pyramid.
  RelocalizationResult relocalize(const RelocalizationFrame& frame) const;

 private:
  const Vocabulary& vocabulary_;
  const KeyFrameDatabase& database_;
  const map::Map& map_;
  RelocalizerParams params_;
};

}  // namespace lumaslam::loop
