// Keys renamed to camelCase (issue 21, core/settings_spellings.h): every old snake_case spelling
// reaches its module (Enhancement.*, Detector.*) as the new name does, so a file with the old
// spellings runs with the same effective settings, with one warning per old key naming the file,
// the old and the new key, and none of them counts as unknown.
#include <gtest/gtest.h>

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <map>
#include <string>

#include "lumaslam/core/settings_spellings.h"
#include "lumaslam/pipeline_params.h"
#include "test_system_run.h"

namespace lumaslam {
namespace {

// A value for every renamed key, none of them its default.
const std::map<std::string, std::string> kValues = {
    {"Enhancement.clahe.tilesX", "4"},
    {"Enhancement.clahe.tilesY", "2"},
    {"Enhancement.clahe.limitMode", "\"local\""},
    {"Enhancement.clahe.fixedLimit", "3.5"},
    {"Enhancement.clahe.sigmaMax", "55.5"},
    {"Enhancement.clahe.dMax", "1234.5"},
    {"Detector.inputSize", "320"},
    {"Detector.boxFile", "\"boxes.txt\""},
    {"Detector.boxFileTolerance", "0.05"},
    {"Detector.queueCapacity", "7"},
    {"Detector.propagationFeatures", "20"},
    {"Detector.propagationInnerFraction", "0.5"},
    {"Detector.maskMargin", "5"},
    {"Detector.depthTolerance", "0.3"},
    {"Detector.depthEdge", "6"},
    {"Detector.depthPercentile", "0.3"},
    {"Detector.memoryFrames", "10"},
    {"Detector.memoryStrikes", "3"},
};

// The synthetic RGB-D settings with a box-file detector and every renamed key, spelled old or new.
io::Settings settingsWith(bool old_spelling) {
  std::string extra = "Detector.type: \"box_file\"\n";
  for (const auto& [old_key, new_key] : core::keySpellings()) {
    const std::string value = kValues.at(std::string(new_key));
    extra += std::string(old_spelling ? old_key : new_key) + ": " + value + "\n";
  }
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 2, 1);
  return test::presetSettings(sequence, [&](std::string yaml) { return yaml + "\n" + extra; });
}

TEST(SettingsSpellings, EveryRenamedKeyHasAValueHere) {
  EXPECT_EQ(core::keySpellings().size(), kValues.size());
}

TEST(SettingsSpellings, OldSpellingsGiveTheSameEffectiveSettings) {
  const auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(64);
  spdlog::default_logger()->sinks().push_back(sink);
  const auto old_settings = settingsWith(true);
  const std::string from_old = effectiveSettings(old_settings, PipelineOptions{});
  spdlog::default_logger()->sinks().pop_back();
  const std::string from_new = effectiveSettings(settingsWith(false), PipelineOptions{});
  EXPECT_EQ(from_old, from_new);
  for (const auto& [key, value] : kValues) {  // the values were read, not the defaults
    EXPECT_NE(from_new.find(key + ": "), std::string::npos) << key << " not printed";
  }
  EXPECT_NE(from_new.find("Enhancement.clahe.limitMode: \"local\"\n"), std::string::npos);
  EXPECT_NE(from_new.find("Detector.queueCapacity: 7\n"), std::string::npos);

  std::string logged;
  for (const auto& line : sink->last_formatted()) logged += line;
  for (const auto& [old_key, new_key] : core::keySpellings()) {
    const std::string warning =
        fmt::format("xyz-rgbd.yaml: '{}' is an old spelling; use '{}'", old_key, new_key);
    const auto first = logged.find(warning);
    EXPECT_NE(first, std::string::npos) << warning << " not in\n" << logged;
    EXPECT_EQ(logged.find(warning, first + 1), std::string::npos) << "warned twice: " << old_key;
  }
  EXPECT_TRUE(core::unknownKeys(*old_settings.file).empty());
}

}  // namespace
}  // namespace lumaslam
