#pragma once
// The loop-closing keys of the Loop.* section (docs/settings.md); Loop.vocabulary and
// Loop.closing, which decide whether there is a loop closer at all, are io::LoopSettings.
#include <string>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/loop/loop_closer.h"

namespace lumaslam::loop {

// Sets every loop-closer key the file has; throws Error naming the key for a bad value.
void readLoopClosingSettings(const core::SettingsFile& file, LoopCloserParams& params);
std::string printLoopClosingSettings(const LoopCloserParams& params);

}  // namespace lumaslam::loop
