// Issue 20 item 6, settings typos: a key no part of the Pipeline reads (Enhancement.presett,
// Camera.fxx, ORBextractor.nfeatures) is reported with the closest known key, a warning by
// default and an Error with strict_settings; every shipped config and the generator's settings
// have no such key (ORB-SLAM3 keys lumaslam ignores on purpose, e.g. Camera.type, are not
// reported).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "test_system_run.h"

namespace lumaslam {
namespace {

io::Settings synthSettingsWith(const std::string& extra) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 2, 1);
  return test::presetSettings(sequence, [&](std::string yaml) { return yaml + "\n" + extra; });
}

std::vector<core::UnknownKey> unknownAfterConstruction(const io::Settings& settings) {
  PipelineOptions options;
  options.sequential = true;
  const Pipeline system(settings, options);
  return core::unknownKeys(*settings.file);
}

TEST(SettingsKeys, TyposAreReportedWithTheClosestKnownKey) {
  const auto settings = synthSettingsWith(
      "Enhancement.presett: \"clahe\"\nCamera.fxx: 500.0\nORBextractor.nfeatures: 2000\n"
      "Viewer.KeyFrameSize: 0.05\nTotally.unrelated: 1\n");
  const auto unknown = unknownAfterConstruction(settings);
  std::map<std::string, std::string> found;
  for (const auto& [key, suggestion] : unknown) found[key] = suggestion;
  EXPECT_EQ(found.size(), 4U);
  EXPECT_EQ(found["Enhancement.presett"], "Enhancement.preset");
  EXPECT_EQ(found["Camera.fxx"], "Camera.fx");
  EXPECT_EQ(found["ORBextractor.nfeatures"], "ORBextractor.nFeatures");
  EXPECT_TRUE(found.contains("Totally.unrelated"));
  EXPECT_EQ(found["Totally.unrelated"], "");
  EXPECT_FALSE(found.contains("Viewer.KeyFrameSize"));  // ORB-SLAM3's, ignored on purpose
  EXPECT_FALSE(found.contains("Camera.type"));  // the generator's file has it; read by no one
}

TEST(SettingsKeys, StrictSettingsMakeATypoAnErrorNamingTheKeyAndTheFix) {
  const auto settings = synthSettingsWith("Enhancement.presett: \"clahe\"\n");
  PipelineOptions options;
  options.sequential = true;
  options.strict_settings = true;
  const std::string message = test::errorOf([&] { const Pipeline system(settings, options); });
  EXPECT_NE(message.find("Enhancement.presett"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'Enhancement.preset'"), std::string::npos) << message;
}

TEST(SettingsKeys, ShippedConfigsAndGeneratedSettingsHaveNoUnknownKey) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 2, 1);
  EXPECT_TRUE(unknownAfterConstruction(test::presetSettings(sequence)).empty());
  int configs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(LUMASLAM_SOURCE_DIR) / "configs")) {
    if (entry.path().extension() != ".yaml") continue;
    ++configs;
    const auto unknown = unknownAfterConstruction(io::loadSettings(entry.path()));
    for (const auto& [key, suggestion] : unknown) {
      ADD_FAILURE() << entry.path() << ": unknown key " << key << " (closest: " << suggestion
                    << ")";
    }
  }
  EXPECT_GE(configs, 10);
}

}  // namespace
}  // namespace lumaslam
