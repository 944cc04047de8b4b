// A Pipeline built with default settings and options loads the default vocabulary (data/
// vocabulary/): relocalization and loop closing are on. "none" and Loop.closing: 0 turn them
// off.
#include <gtest/gtest.h>

#include "lumaslam/loop/place_recognition.h"
#include "lumaslam/loop/vocabulary_choice.h"
#include "scoped_env.h"
#include "test_paths.h"
#include "test_system_run.h"

namespace {

using namespace lumaslam;

io::Settings rgbdSettings(const test::SettingsEdit& edit = {}) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 10, 1);
  return test::presetSettings(sequence, edit);
}

TEST(SystemDefaultVocabulary, DefaultSettingsHaveRelocalizationAndLoopClosing) {
  const test::ScopedEnv env(loop::kVocabularyEnvironment, std::nullopt);
  const Pipeline system(rgbdSettings(), PipelineOptions{});
  ASSERT_NE(system.placeRecognition(), nullptr);
  EXPECT_NE(system.loopCloser(), nullptr);
  EXPECT_EQ(std::filesystem::path(system.vocabularyDescription()).filename(),
            loop::defaultVocabularyName());
}

TEST(SystemDefaultVocabulary, NoneTurnsTheVocabularyOff) {
  PipelineOptions options;
  options.vocabulary = "none";
  const Pipeline by_option(rgbdSettings(), options);
  EXPECT_EQ(by_option.placeRecognition(), nullptr);
  EXPECT_EQ(by_option.loopCloser(), nullptr);
  EXPECT_EQ(by_option.vocabularyDescription(), "none");

  const Pipeline by_settings(
      rgbdSettings([](std::string yaml) { return yaml + "\nLoop.vocabulary: none\n"; }),
      PipelineOptions{});
  EXPECT_EQ(by_settings.placeRecognition(), nullptr);
}

TEST(SystemDefaultVocabulary, LoopClosingOffKeepsRelocalization) {
  PipelineOptions options;
  options.loop_closing = false;
  const Pipeline system(rgbdSettings(), options);
  EXPECT_NE(system.placeRecognition(), nullptr);
  EXPECT_EQ(system.loopCloser(), nullptr);
}

}  // namespace
