#include "lumaslam/feature/orb_settings.h"

#include <fmt/format.h>

#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_section.h"

namespace lumaslam::feature {

std::optional<OrbSettingProblem> OrbSettings::firstProblem() const {
  const auto problem = [](std::string_view key, std::string why) {
    return std::optional<OrbSettingProblem>(OrbSettingProblem{key, std::move(why)});
  };
  if (nFeatures <= 0) {
    return problem("ORBextractor.nFeatures", fmt::format("must be > 0, found {}", nFeatures));
  }
  if (!(scaleFactor > 1.0f) || scaleFactor > 4.0f) {
    return problem("ORBextractor.scaleFactor",
                   fmt::format("must be > 1 and <= 4, found {}", scaleFactor));
  }
  if (nLevels < 1 || nLevels > 32) {
    return problem("ORBextractor.nLevels",
                   fmt::format("must be >= 1 and <= 32, found {}", nLevels));
  }
  if (iniThFAST < 1 || iniThFAST > 255) {
    return problem("ORBextractor.iniThFAST",
                   fmt::format("must be > 0 and <= 255, found {}", iniThFAST));
  }
  if (minThFAST < 1) {
    return problem("ORBextractor.minThFAST", fmt::format("must be > 0, found {}", minThFAST));
  }
  if (minThFAST > iniThFAST) {
    return problem(
        "ORBextractor.minThFAST",
        fmt::format("must be <= ORBextractor.iniThFAST ({}), found {}", iniThFAST, minThFAST));
  }
  return std::nullopt;
}

void OrbSettings::validate(std::string_view origin) const {
  if (const auto problem = firstProblem()) {
    fail("{}: key '{}': {}", origin, problem->key, problem->why);
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
  if (const auto problem = orb.firstProblem()) settings.invalid(problem->key, problem->why);
  return orb;
}

std::string OrbSettings::summary() const {
  return fmt::format("{} features, {} levels x{}, FAST {}/{}, levels {}", nFeatures, nLevels,
                     scaleFactor, iniThFAST, minThFAST,
                     parallelLevels ? "in parallel" : "in sequence");
}

std::string OrbSettings::settingsLines() const {
  core::SectionPrinter printer("ORBextractor");
  printer("nFeatures", nFeatures);
  printer("scaleFactor", scaleFactor);
  printer("nLevels", nLevels);
  printer("iniThFAST", iniThFAST);
  printer("minThFAST", minThFAST);
  printer("parallel", parallelLevels);
  return printer.text();
}

}  // namespace lumaslam::feature
