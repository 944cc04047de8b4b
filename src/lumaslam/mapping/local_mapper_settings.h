#pragma once
// The LocalMapping.* section of the settings file (docs/settings.md).
#include <string>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/mapping/local_mapper.h"

namespace lumaslam::mapping {

// Sets every LocalMapping.* key the file has; throws Error naming the key for a bad value.
void readLocalMappingSettings(const core::SettingsFile& file, LocalMapperParams& params);
std::string printLocalMappingSettings(const LocalMapperParams& params);

}  // namespace lumaslam::mapping
