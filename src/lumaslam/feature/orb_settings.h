#pragma once
// Settings of the ORB extractor, named and defaulted as in ORB-SLAM's settings files
// (ORBextractor.nFeatures, .scaleFactor, .nLevels, .iniThFAST, .minThFAST).
#include <string_view>

#include "lumaslam/core/settings_file.h"

namespace lumaslam::feature {

struct OrbSettings {
  int nFeatures = 1000;
  float scaleFactor = 1.2f;
  int nLevels = 8;
  int iniThFAST = 20;           // FAST threshold tried first in every grid cell
  int minThFAST = 7;            // fallback threshold for cells where iniThFAST finds nothing
  bool parallelLevels = false;  // process pyramid levels with cv::parallel_for_

  // Throws Error naming `origin` and the offending value if a setting is out of range.
  void validate(std::string_view origin) const;

  // Reads the ORBextractor.* keys (absent keys keep the defaults above; ORBextractor.parallel
  // maps to parallelLevels) and validates them.
  static OrbSettings fromSettings(const core::SettingsFile& settings);
};

}  // namespace lumaslam::feature
