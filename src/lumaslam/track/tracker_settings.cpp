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

// Dynamic.* beside Dynamic.motionEvidence (io::DynamicSettings, which the command line can
// override): the motion test's thresholds, in log-odds that a point is static.
template <typename Keys>
void visitDynamicKeys(Keys& keys, MotionEvidenceParams& p) {
  keys("flowRadius", p.flow_radius_px, Range::above(0.0));
  keys("flowMaxDistance", p.flow_max_distance, Range::between(0, 256));
  keys("flowRatio", p.flow_ratio, Range{0.0, 1.0, false});
  // Beliefs decay over at most 128 frames (MotionEvidence::kDecaySteps): 0.96^128 < 1 %.
  keys("forget", p.forget, Range::between(0.0, 0.96));
  keys("maxLogOdds", p.max_log_odds, Range{0.0, 20.0, false});
  keys("dynamicBelow", p.dynamic_below, Range::between(-20.0, 0.0));
  keys("confirmedAbove", p.confirmed_above, Range::between(0.0, 20.0));
  keys("regionCellSize", p.region_cell_px, Range::atLeast(8));
  keys("regionMinMoving", p.region_min_moving, Range::atLeast(1));
  keys("regionMovingBelow", p.region_moving_below, Range::between(-20.0, 0.0));
  keys("regionRestingAbove", p.region_resting_above, Range::between(0.0, 20.0));
  keys("maxOutlierFraction", p.max_outlier_fraction, Range::between(0.0, 1.0));
  keys("rigidConsensus", p.rigidity);
  keys("mapStartSegmentation", p.origin.enabled);
  keys("mapStartFrames", p.origin.window_frames, Range::atLeast(0));
  keys("mapStartLateralPixels", p.origin.lateral_tolerance_px, Range::above(0.0));
}

// Initializer.*: the monocular two-view start (MonocularInitParams and its TwoViewParams;
// `threaded` follows System.sequential).
template <typename Keys>
void visitInitializerKeys(Keys& keys, MonocularInitParams& p) {
  keys("minFeatures", p.min_features, Range::atLeast(8));
  keys("minMatches", p.min_matches, Range::atLeast(8));
  keys("searchWindow", p.search_window, Range::above(0.0));
  keys("matchRatio", p.ratio, Range{0.0, 1.0, false});
  keys("maxReferenceAge", p.max_reference_age, Range::above(0.0));
  TwoViewParams& v = p.two_view;
  keys("sigma", v.sigma, Range::above(0.0));
  keys("ransacIterations", v.ransac_iterations, Range::atLeast(1));
  keys("homographyRatio", v.homography_ratio, Range::between(0.0, 1.0));
  keys("minParallax", v.min_parallax_deg, Range::between(0.0, 90.0));
  keys("minTriangulated", v.min_triangulated, Range::atLeast(1));
  keys("minGoodFraction", v.min_good_fraction, Range::between(0.0, 1.0));
  keys("maxRunnerUpRatio", v.max_runner_up_ratio, Range::between(0.0, 1.0));
  keys("refineIterations", v.refine_iterations, Range::atLeast(0));
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

void readDynamicSettings(const core::SettingsFile& file, MotionEvidenceParams& params) {
  core::readSection(file, "Dynamic", params,
                    [](auto& keys, auto& p) { visitDynamicKeys(keys, p); });
}

std::string printDynamicSettings(const MotionEvidenceParams& params) {
  core::SectionPrinter printer("Dynamic");
  printer("motionEvidence", params.enabled);
  MotionEvidenceParams copy = params;
  visitDynamicKeys(printer, copy);
  return printer.text();
}

void readInitializerSettings(const core::SettingsFile& file, MonocularInitParams& params) {
  core::readSection(file, "Initializer", params,
                    [](auto& keys, auto& p) { visitInitializerKeys(keys, p); });
}

std::string printInitializerSettings(const MonocularInitParams& params) {
  return core::printSection("Initializer", params,
                            [](auto& keys, auto& p) { visitInitializerKeys(keys, p); });
}

}  // namespace lumaslam::track
