// The Tracking.*, LocalMapping.* and Loop.* sections (issue 21): each key reaches its stage
// over the defaults the Pipeline picks for the sensor, a value out of range is an Error naming
// the key, a typo is reported with the key it misses, the printed settings read back to the
// same values, and a changed key changes what a run does.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/pipeline_params.h"
#include "test_system_run.h"

namespace lumaslam {
namespace {

io::Settings settingsOf(const std::string& preset, const std::string& extra,
                        std::optional<io::SensorType> sensor = std::nullopt) {
  const synth::SequenceRenderer sequence(synth::findPreset(preset), 2, 1);
  return test::presetSettings(
      sequence, [&](std::string yaml) { return yaml + "\n" + extra; }, sensor);
}

StageParams stageParamsOf(const io::Settings& settings) {
  return stageParamsFor(settings, /*sequential=*/true, /*motion_evidence=*/false);
}

TEST(StageSettings, DefaultsDependOnTheSensor) {
  const auto rgbd = stageParamsOf(settingsOf("xyz-rgbd", ""));
  EXPECT_FALSE(rgbd.tracker.wait_for_busy_mapper);
  EXPECT_EQ(rgbd.mapper.triangulation_neighbours, 10);
  EXPECT_TRUE(rgbd.loop.fix_scale);
  const auto settings = settingsOf("xyz-rgbd", "");
  EXPECT_EQ(rgbd.tracker.max_frames_between_keyframes, static_cast<int>(settings.camera.fps));

  const auto mono = stageParamsOf(settingsOf("xyz-rgbd", "", io::SensorType::Monocular));
  EXPECT_TRUE(mono.tracker.wait_for_busy_mapper);
  EXPECT_EQ(mono.mapper.triangulation_neighbours, 20);
  EXPECT_FALSE(mono.loop.fix_scale);

  const auto stereo = stageParamsOf(settingsOf("xyz-stereo", ""));
  EXPECT_EQ(stereo.tracker.min_initial_features, 250);
  EXPECT_EQ(rgbd.tracker.min_initial_features, 500);
}

TEST(StageSettings, FileKeysGoOverTheSensorDefaults) {
  const auto params = stageParamsOf(
      settingsOf("xyz-rgbd", "", io::SensorType::Monocular));  // defaults, for comparison
  const auto edited = stageParamsOf(settingsOf("xyz-rgbd",
                                               "Tracking.waitForBusyMapper: false\n"
                                               "Tracking.minLocalMapInliers: 45\n"
                                               "Tracking.localMapSearchRadius: 6.5\n"
                                               "LocalMapping.triangulationNeighbours: 12\n"
                                               "LocalMapping.bundleAdjustment: 0\n"
                                               "Loop.minInliers: 55\n"
                                               "Loop.queueCapacity: 8\n",
                                               io::SensorType::Monocular));
  EXPECT_TRUE(params.tracker.wait_for_busy_mapper);
  EXPECT_FALSE(edited.tracker.wait_for_busy_mapper);
  EXPECT_EQ(edited.tracker.min_local_map_inliers, 45);
  EXPECT_FLOAT_EQ(edited.tracker.local_map_search_radius, 6.5F);
  EXPECT_EQ(edited.mapper.triangulation_neighbours, 12);
  EXPECT_FALSE(edited.mapper.bundle_adjustment);
  EXPECT_EQ(edited.loop.min_inliers, 55);
  EXPECT_EQ(edited.loop.queue_capacity, 8U);
  EXPECT_EQ(edited.tracker.lost_search_radius, params.tracker.lost_search_radius);  // untouched
}

TEST(StageSettings, AValueOutOfRangeIsAnErrorNamingFileAndKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"Tracking.minInlierFractionOfLast: 1.5\n", "must be in [0, 1], found 1.5"},
      {"Tracking.maxFramesBetweenKeyframes: 0\n", "must be >= 1, found 0"},
      {"LocalMapping.redundancy: 0\n", "must be in (0, 1], found 0"},
      {"Loop.projectionRadius: -2.0\n", "must be > 0, found -2"},
      {"Tracking.minLocalMapInliers: 12.5\n", "expected integer"},
  };
  for (const auto& [line, why] : cases) {
    try {
      (void)stageParamsOf(settingsOf("xyz-rgbd", line));
      ADD_FAILURE() << "no error for " << line;
    } catch (const Error& e) {
      const std::string message = e.what();
      const std::string key = line.substr(0, line.find(':'));
      EXPECT_NE(message.find("xyz-rgbd.yaml"), std::string::npos) << message;
      EXPECT_NE(message.find(key), std::string::npos) << message;
      EXPECT_NE(message.find(why), std::string::npos) << message;
    }
  }
}

TEST(StageSettings, ATypoIsReportedWithTheKeyItMisses) {
  const auto settings = settingsOf("xyz-rgbd",
                                   "Tracking.minLocalMapInlier: 40\n"
                                   "LocalMapping.baIteration: 5\n");
  PipelineOptions options;
  options.sequential = true;
  options.vocabulary = "none";
  const Pipeline pipeline(settings, options);
  std::map<std::string, std::string> found;
  for (const auto& [key, suggestion] : core::unknownKeys(*settings.file)) found[key] = suggestion;
  EXPECT_EQ(found["Tracking.minLocalMapInlier"], "Tracking.minLocalMapInliers");
  EXPECT_EQ(found["LocalMapping.baIteration"], "LocalMapping.baIterations");
}

// The generator's file without the keys effectiveSettings prints, so that the printed lines
// can be appended without setting a key twice.
std::string withoutPrintedSections(std::string yaml) {
  const std::regex printed(
      "(ORBextractor|Tracking|LocalMapping|Loop)\\.[A-Za-z]+: .*\n|System\\.sequential: "
      ".*\n|Dynamic\\.motionEvidence: .*\n");
  return std::regex_replace(yaml, printed, "");
}

TEST(StageSettings, PrintedSettingsReadBackToTheSameValues) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 2, 1);
  const auto edited = test::presetSettings(sequence, [](std::string yaml) {
    return withoutPrintedSections(yaml) +
           "Tracking.minInlierFractionOfLast: 0.3\nTracking.motionSearchRadius: 7.3\n"
           "LocalMapping.redundancy: 0.85\nLoop.globalBundleAdjustment: 0\n"
           "ORBextractor.nFeatures: 1100\n";
  });
  PipelineOptions options;
  options.sequential = true;
  const std::string printed = effectiveSettings(edited, options);
  EXPECT_NE(printed.find("Tracking.minInlierFractionOfLast: 0.3\n"), std::string::npos);
  EXPECT_NE(printed.find("Tracking.motionSearchRadius: 7.3\n"), std::string::npos);
  EXPECT_NE(printed.find("Loop.globalBundleAdjustment: false\n"), std::string::npos);
  EXPECT_NE(printed.find("ORBextractor.nFeatures: 1100\n"), std::string::npos);
  EXPECT_NE(printed.find("System.sequential: true\n"), std::string::npos);
  EXPECT_NE(printed.find("LocalMapping.triangulationNeighbours: 10\n"), std::string::npos);

  const auto reread = test::presetSettings(
      sequence, [&](std::string yaml) { return withoutPrintedSections(yaml) + printed; });
  EXPECT_EQ(effectiveSettings(reread, PipelineOptions{}), printed);
  for (const auto& [key, suggestion] : core::unknownKeys(*reread.file)) {
    EXPECT_EQ(printed.find(key + ":"), std::string::npos) << "printed a key nothing reads: " << key;
  }
}

// Effects on a run (sequential, deterministic: the mapper is always idle, so
// Tracking.maxFramesBetweenKeyframes, which applies to a busy mapper, has none): keyframes no
// sooner than 20 frames apart, and local bundle adjustment off changes the poses.
TEST(StageSettings, ChangedKeysChangeWhatARunDoes) {
  const auto with = [](const std::string& extra) {
    test::RunConfig config;
    config.edit = [extra](std::string yaml) { return yaml + "\n" + extra; };
    return test::runOnPreset("xyz-rgbd", 80, 1, config);
  };
  const auto defaults = with("");
  const auto spaced = with("Tracking.minFramesBetweenKeyframes: 20\n");
  const auto no_ba = with("LocalMapping.bundleAdjustment: false\n");
  EXPECT_EQ(defaults.tracked, 80U);
  EXPECT_EQ(spaced.tracked, 80U);
  EXPECT_LE(spaced.keyframes, 80U / 20U + 1U);
  EXPECT_LT(spaced.keyframes, defaults.keyframes);
  EXPECT_NE(no_ba.report.ate.stats.rmse, defaults.report.ate.stats.rmse);
}

}  // namespace
}  // namespace lumaslam
