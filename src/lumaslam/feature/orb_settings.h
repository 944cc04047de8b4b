#pragma once
// Settings of the ORB extractor: the ORBextractor.* section of the settings file, named and
// defaulted as in ORB-SLAM's files. The feature module is the one place that reads and checks
// that section (docs/settings.md "ORB extractor"); the Pipeline builds its extractor and the
// map-file fingerprint from the one OrbSettings it reads.
#include <optional>
#include <string>
#include <string_view>

#include "lumaslam/core/settings_file.h"

namespace lumaslam::feature {

// A setting out of range: its key and what is wrong with it ("must be > 1, found 0.8").
struct OrbSettingProblem {
  std::string_view key;
  std::string why;
};

struct OrbSettings {
  int nFeatures = 1000;         // ORBextractor.nFeatures
  float scaleFactor = 1.2f;     // ORBextractor.scaleFactor
  int nLevels = 8;              // ORBextractor.nLevels
  int iniThFAST = 20;           // ORBextractor.iniThFAST: tried first in every grid cell
  int minThFAST = 7;            // ORBextractor.minThFAST: for cells where iniThFAST finds none
  bool parallelLevels = false;  // ORBextractor.parallel: pyramid levels with cv::parallel_for_

  // The first setting out of range, nullopt when every one is valid. The one set of rules
  // both validate() and fromSettings() apply.
  std::optional<OrbSettingProblem> firstProblem() const;

  // Throws Error "ORIGIN: key 'K': WHY" for the first setting out of range.
  void validate(std::string_view origin) const;

  // Reads the ORBextractor.* keys (absent keys keep the defaults above) and checks them;
  // an error names the file and the key, as every settings error does.
  static OrbSettings fromSettings(const core::SettingsFile& settings);

  // One line for logs: "1000 features, 8 levels x1.2, FAST 20/7, levels in sequence".
  std::string summary() const;
  // The ORBextractor.* keys as settings lines ("ORBextractor.nFeatures: 1000\n...").
  std::string settingsLines() const;

  friend bool operator==(const OrbSettings&, const OrbSettings&) = default;
};

}  // namespace lumaslam::feature
