#pragma once
// The Tracking.* section of the settings file (docs/settings.md): TrackerParams read over the
// defaults the Pipeline chose for the sensor, and printed back as settings lines; likewise the
// tracker's motion test (Dynamic.*) and monocular initializer (Initializer.*).
#include <string>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/track/tracker.h"

namespace lumaslam::track {

// Sets every Tracking.* key the file has; throws Error naming the key for a value out of range.
void readTrackingSettings(const core::SettingsFile& file, TrackerParams& params);
// "Tracking.minLocalMapInliers: 30\n..." for every key, as readTrackingSettings reads them.
std::string printTrackingSettings(const TrackerParams& params);

// Dynamic.* except Dynamic.motionEvidence (io::DynamicSettings, overridden by the command line);
// printed with it, from params.enabled.
void readDynamicSettings(const core::SettingsFile& file, MotionEvidenceParams& params);
std::string printDynamicSettings(const MotionEvidenceParams& params);

// Initializer.*: the monocular two-view initializer (read for every sensor, used by mono).
void readInitializerSettings(const core::SettingsFile& file, MonocularInitParams& params);
std::string printInitializerSettings(const MonocularInitParams& params);

}  // namespace lumaslam::track
