#include "lumaslam/loop/loop_closer_settings.h"

#include "lumaslam/core/settings_section.h"

namespace lumaslam::loop {
namespace {

using core::Range;

template <typename Keys>
void visitLoopClosingKeys(Keys& keys, LoopCloserParams& p) {
  keys("queueCapacity", p.queue_capacity, Range::atLeast(1));
  keys("minKeyframesBetweenLoops", p.min_keyframes_between_loops, Range::atLeast(0));
  keys("consistencyThreshold", p.detector.consistency_threshold, Range::atLeast(1));
  keys("groupNeighbours", p.detector.group_neighbours, Range::atLeast(1));
  keys("minBowMatches", p.min_bow_matches, Range::atLeast(3));
  keys("minInliers", p.min_inliers, Range::atLeast(3));
  keys("projectionRadius", p.projection_radius_px, Range::above(0.0));
  keys("fusionRadius", p.fusion_radius_px, Range::above(0.0));
  keys("strongCovisibility", p.strong_covisibility, Range::atLeast(1));
  keys("poseGraphIterations", p.pose_graph_iterations, Range::atLeast(1));
  keys("globalBundleAdjustment", p.global_bundle_adjustment);
  keys("globalBaIterations", p.global_ba_iterations, Range::atLeast(1));
}

}  // namespace

void readLoopClosingSettings(const core::SettingsFile& file, LoopCloserParams& params) {
  core::readSection(file, "Loop", params,
                    [](auto& keys, auto& p) { visitLoopClosingKeys(keys, p); });
}

std::string printLoopClosingSettings(const LoopCloserParams& params) {
  return core::printSection("Loop", params,
                            [](auto& keys, auto& p) { visitLoopClosingKeys(keys, p); });
}

}  // namespace lumaslam::loop
