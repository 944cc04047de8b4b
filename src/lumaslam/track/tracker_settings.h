#pragma once
// The Tracking.* section of the settings file (docs/settings.md): TrackerParams read over the
// defaults the Pipeline chose for the sensor, and printed back as settings lines.
#include <string>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/track/tracker.h"

namespace lumaslam::track {

// Sets every Tracking.* key the file has; throws Error naming the key for a value out of range.
void readTrackingSettings(const core::SettingsFile& file, TrackerParams& params);
// "Tracking.minLocalMapInliers: 30\n..." for every key, as readTrackingSettings reads them.
std::string printTrackingSettings(const TrackerParams& params);

}  // namespace lumaslam::track
