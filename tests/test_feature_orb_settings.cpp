// feature::OrbSettings: the ORBextractor.* section, read and checked in this one place (issue
// 21): every key, the defaults, the errors naming file, key and value, the configs' values.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/feature/orb_settings.h"
#include "test_paths.h"

namespace lumaslam::feature {
namespace {

OrbSettings parse(const std::string& lines, const std::string& origin = "orb.yaml") {
  return OrbSettings::fromSettings(core::SettingsFile::fromString("%YAML:1.0\n" + lines, origin));
}

TEST(OrbSettings, ReadsEveryOrbSlamKeyAndTheParallelSwitch) {
  const OrbSettings orb = parse(
      "ORBextractor.nFeatures: 1500\nORBextractor.scaleFactor: 1.25\nORBextractor.nLevels: 6\n"
      "ORBextractor.iniThFAST: 18\nORBextractor.minThFAST: 5\nORBextractor.parallel: 1\n");
  EXPECT_EQ(orb.nFeatures, 1500);
  EXPECT_FLOAT_EQ(orb.scaleFactor, 1.25f);
  EXPECT_EQ(orb.nLevels, 6);
  EXPECT_EQ(orb.iniThFAST, 18);
  EXPECT_EQ(orb.minThFAST, 5);
  EXPECT_TRUE(orb.parallelLevels);
  EXPECT_NE(orb, OrbSettings{});
  EXPECT_EQ(orb.summary(), "1500 features, 6 levels x1.25, FAST 18/5, levels in parallel");
}

TEST(OrbSettings, AbsentKeysKeepTheDefaults) {
  EXPECT_EQ(parse("x: 1\n"), OrbSettings{});
  EXPECT_FALSE(OrbSettings{}.parallelLevels);
}

TEST(OrbSettings, ReadsTheConfigsValues) {
  const auto configs = test::sourceDir() / "configs";
  const auto read = [&](const char* name) {
    return OrbSettings::fromSettings(core::SettingsFile::open(configs / name));
  };
  EXPECT_EQ(read("euroc_stereo.yaml").nFeatures, 1200);
  EXPECT_EQ(read("kitti_00-02_mono.yaml").nFeatures, 2000);
}

struct BadCase {
  std::string lines;
  std::vector<std::string> mentions;  // substrings the message must contain
};

TEST(OrbSettings, BadValuesNameFileKeyAndValue) {
  const std::vector<BadCase> cases = {
      {"ORBextractor.nFeatures: 0\n", {"bad.yaml: key 'ORBextractor.nFeatures'", "> 0", "0"}},
      {"ORBextractor.scaleFactor: 1.0\n", {"bad.yaml: key 'ORBextractor.scaleFactor'", "> 1"}},
      {"ORBextractor.scaleFactor: 0.8\n", {"ORBextractor.scaleFactor", "0.8"}},
      {"ORBextractor.scaleFactor: 5\n", {"ORBextractor.scaleFactor", "<= 4", "5"}},
      {"ORBextractor.nLevels: 0\n", {"ORBextractor.nLevels", "0"}},
      {"ORBextractor.nLevels: 40\n", {"ORBextractor.nLevels", "<= 32", "40"}},
      {"ORBextractor.iniThFAST: 300\n", {"ORBextractor.iniThFAST", "300"}},
      {"ORBextractor.minThFAST: 0\n", {"ORBextractor.minThFAST", "> 0"}},
      {"ORBextractor.minThFAST: 30\n",
       {"key 'ORBextractor.minThFAST'", "must be <= ORBextractor.iniThFAST (20), found 30"}},
      {"ORBextractor.iniThFAST: 5\nORBextractor.minThFAST: 9\n", {"ORBextractor.minThFAST", "9"}},
      {"ORBextractor.nFeatures: \"many\"\n", {"ORBextractor.nFeatures", "many"}},
      // cv::FileStorage keeps 32-bit integers: the value as written, not -1294967296.
      {"ORBextractor.nFeatures: 3000000000\n",
       {"bad.yaml", "ORBextractor.nFeatures", "3000000000 is out of range"}},
  };
  for (const auto& bad : cases) {
    const std::string message = test::errorOf([&] { (void)parse(bad.lines, "bad.yaml"); });
    ASSERT_FALSE(message.empty()) << "no error for: " << bad.lines;
    for (const auto& text : bad.mentions) {
      EXPECT_NE(message.find(text), std::string::npos) << message << "\n(expected: " << text << ")";
    }
  }
}

TEST(OrbSettings, TheExtractorChecksSettingsMadeInCode) {
  OrbSettings zero;
  zero.nFeatures = 0;
  const std::string message = test::errorOf([&] { OrbExtractor{zero}; });
  EXPECT_NE(message.find("key 'ORBextractor.nFeatures': must be > 0, found 0"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace lumaslam::feature
