// The ORBextractor.* keys reach the Pipeline's extractor and its map-file fingerprint from the
// one place that reads them, feature::OrbSettings (issue 21: ORBextractor.parallel was
// dropped on the way), and a bad value stops the Pipeline naming the key.
#include <gtest/gtest.h>

#include <regex>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "test_system_run.h"

namespace {

using namespace lumaslam;

// The generator's settings with its ORBextractor.iniThFAST / minThFAST lines replaced by
// `thresholds` and `extra` appended.
Pipeline pipelineWith(const std::string& thresholds, const std::string& extra = "") {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 2, 1);
  const auto edit = [&](std::string yaml) {
    const std::regex fast_lines("ORBextractor\\.(iniThFAST|minThFAST): .*\n");
    return std::regex_replace(yaml, fast_lines, "") + thresholds + extra;
  };
  PipelineOptions options;
  options.enhance_preset = "off";
  options.vocabulary = "none";
  options.detector = "none";
  return Pipeline(test::presetSettings(sequence, edit), options);
}

TEST(SystemOrbSettings, EveryKeyReachesTheExtractorAndTheFingerprint) {
  const Pipeline pipeline = pipelineWith("ORBextractor.iniThFAST: 25\nORBextractor.minThFAST: 9\n",
                                         "ORBextractor.parallel: 1\n");
  const feature::OrbSettings& orb = pipeline.orbSettings();
  EXPECT_TRUE(orb.parallelLevels);
  EXPECT_EQ(orb.iniThFAST, 25);
  EXPECT_EQ(orb.minThFAST, 9);
  EXPECT_EQ(orb.nFeatures, pipeline.settings().file->get<int>("ORBextractor.nFeatures"));
  const auto fingerprint = pipeline.mapFingerprint();
  EXPECT_EQ(fingerprint.orb_features, orb.nFeatures);
  EXPECT_EQ(fingerprint.orb_scale_factor, orb.scaleFactor);
  EXPECT_EQ(fingerprint.orb_levels, orb.nLevels);
  EXPECT_EQ(fingerprint.orb_ini_fast, 25);
  EXPECT_EQ(fingerprint.orb_min_fast, 9);
}

TEST(SystemOrbSettings, ParallelLevelsAreOffUnlessAsked) {
  EXPECT_FALSE(pipelineWith("ORBextractor.iniThFAST: 20\n").orbSettings().parallelLevels);
}

TEST(SystemOrbSettings, ABadValueStopsThePipelineNamingTheKey) {
  const std::string message =
      test::errorOf([] { (void)pipelineWith("ORBextractor.minThFAST: 0\n"); });
  EXPECT_NE(message.find("key 'ORBextractor.minThFAST': must be > 0, found 0"), std::string::npos)
      << message;
}

}  // namespace
