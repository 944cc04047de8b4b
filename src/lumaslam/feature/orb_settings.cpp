#include "lumaslam/feature/orb_settings.h"

#include "lumaslam/core/error.h"

namespace lumaslam::feature {

void OrbSettings::validate(std::string_view origin) const {
  if (nFeatures <= 0) fail("{}: ORBextractor.nFeatures must be > 0, got {}", origin, nFeatures);
  if (!(scaleFactor > 1.0f) || scaleFactor > 4.0f) {
    fail("{}: ORBextractor.scaleFactor must be in (1, 4], got {}", origin, scaleFactor);
  }
  if (nLevels < 1 || nLevels > 32) {
    fail("{}: ORBextractor.nLevels must be in [1, 32], got {}", origin, nLevels);
  }
  if (iniThFAST < 1 || iniThFAST > 255) {
    fail("{}: ORBextractor.iniThFAST must be in [1, 255], got {}", origin, iniThFAST);
  }
  if (minThFAST < 1 || minThFAST > iniThFAST) {
    fail("{}: ORBextractor.minThFAST must be in [1, iniThFAST={}], got {}", origin, iniThFAST,
         minThFAST);
  }
}

OrbSettings OrbSettings::fromSettings(const core::SettingsFile& settings) {
  OrbSettings orb;
  orb.nFeatures = settings.get<int>("ORBextractor.nFeatures", orb.nFeatures);
  orb.scaleFactor = settings.get<float>("ORBextractor.scaleFactor", orb.scaleFactor);
  orb.nLevels = settings.get<int>("ORBextractor.nLevels", orb.nLevels);
  orb.iniThFAST = settings.get<int>("ORBextractor.iniThFAST", orb.iniThFAST);
  orb.minThFAST = settings.get<int>("ORBextractor.minThFAST", orb.minThFAST);
  orb.parallelLevels = settings.get<bool>("ORBextractor.parallel", orb.parallelLevels);
  orb.validate(settings.origin());
  return orb;
}

}  // namespace lumaslam::feature
