#include "lumaslam/track/tracker_settings.h"

#include "lumaslam/core/settings_section.h"

namespace lumaslam::track {
namespace {

using core::Range;

template <typename Keys>
void visitTrackingKeys(Keys& keys, TrackerParams& p) {
  keys("minInitialFeatures", p.min_initial_features, Range::atLeast(1));
  keys("maxFramesBetweenKeyframes", p.max_frames_between_keyframes, Range::atLeast(1));
  keys("minFramesBetweenKeyframes", p.min_frames_between_keyframes, Range::atLeast(0));
  keys("waitForBusyMapper", p.wait_for_busy_mapper);
  keys("minLocalMapInliers", p.min_local_map_inliers, Range::atLeast(1));
  keys("minInlierFractionOfLast", p.min_inlier_fraction_of_last, Range::between(0.0, 1.0));
  keys("inlierReferenceFrames", p.inlier_reference_frames, Range::atLeast(1));
  keys("inlierReferenceHalfLife", p.inlier_reference_half_life, Range::atLeast(1));
  keys("motionSearchRadius", p.motion_search_radius, Range::above(0.0));
  keys("localMapSearchRadius", p.local_map_search_radius, Range::above(0.0));
  keys("lostSearchRadius", p.lost_search_radius, Range::above(0.0));
  keys("maxLocalKeyframes", p.max_local_keyframes, Range::atLeast(1));
  keys("minInitialMonocularPoints", p.min_initial_monocular_points, Range::atLeast(1));
  keys("minConfirmedPoints", p.min_confirmed_points, Range::atLeast(0));
  keys("monocularResetBelowKeyframes", p.monocular_reset_below_keyframes, Range::atLeast(0));
}

}  // namespace

void readTrackingSettings(const core::SettingsFile& file, TrackerParams& params) {
  core::readSection(file, "Tracking", params,
                    [](auto& keys, auto& p) { visitTrackingKeys(keys, p); });
}

std::string printTrackingSettings(const TrackerParams& params) {
  return core::printSection("Tracking", params,
                            [](auto& keys, auto& p) { visitTrackingKeys(keys, p); });
}

}  // namespace lumaslam::track
