// The Tracking.*, Initializer.*, Dynamic.*, LocalMapping.* and Loop.* sections (issue 21), with
// Camera.*, Enhancement.* and Detector.* in the printed settings: each key reaches its stage
// over the defaults the Pipeline picks for the sensor, a value out of range is an Error naming
// the key, a typo is reported with the key it misses, the printed settings read back to the
// same values, and a changed key changes what a run does.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/pipeline_params.h"
#include "lumaslam/track/tracker_settings.h"
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

TEST(StageSettings, MotionEvidenceAndInitializerKeysAreRead) {
  const auto defaults = stageParamsOf(settingsOf("xyz-rgbd", "", io::SensorType::Monocular));
  const auto edited = stageParamsOf(settingsOf("xyz-rgbd",
                                               "Dynamic.dynamicBelow: -3.5\n"
                                               "Dynamic.forget: 0.9\n"
                                               "Dynamic.regionCellSize: 32\n"
                                               "Dynamic.flowRadius: 16.5\n"
                                               "Initializer.minParallax: 2.0\n"
                                               "Initializer.ransacIterations: 120\n"
                                               "Initializer.matchRatio: 0.8\n"
                                               "Initializer.minMatches: 80\n",
                                               io::SensorType::Monocular));
  const auto& dynamic = edited.tracker.motion_evidence;
  EXPECT_EQ(dynamic.dynamic_below, -3.5);
  EXPECT_EQ(dynamic.forget, 0.9);
  EXPECT_EQ(dynamic.region_cell_px, 32);
  EXPECT_FLOAT_EQ(dynamic.flow_radius_px, 16.5F);
  EXPECT_EQ(dynamic.confirmed_above, defaults.tracker.motion_evidence.confirmed_above);
  const auto& init = edited.tracker.monocular;
  EXPECT_EQ(init.two_view.min_parallax_deg, 2.0);
  EXPECT_EQ(init.two_view.ransac_iterations, 120);
  EXPECT_FLOAT_EQ(init.ratio, 0.8F);
  EXPECT_EQ(init.min_matches, 80);
  EXPECT_EQ(init.min_features, defaults.tracker.monocular.min_features);  // untouched
  EXPECT_FALSE(init.two_view.threaded);  // follows System.sequential, not a key
}

// Today's numbers are the defaults: a file without the keys runs as before issue 21.
TEST(StageSettings, MotionEvidenceAndInitializerDefaultsAreTheStructDefaults) {
  const auto params = stageParamsOf(settingsOf("xyz-rgbd", "", io::SensorType::Monocular));
  track::MotionEvidenceParams dynamic;
  dynamic.enabled = false;
  EXPECT_EQ(track::printDynamicSettings(params.tracker.motion_evidence),
            track::printDynamicSettings(dynamic));
  EXPECT_EQ(track::printInitializerSettings(params.tracker.monocular),
            track::printInitializerSettings(track::MonocularInitParams{}));
}

TEST(StageSettings, AValueOutOfRangeIsAnErrorNamingFileAndKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"Tracking.minInlierFractionOfLast: 1.5\n", "must be in [0, 1], found 1.5"},
      {"Tracking.maxFramesBetweenKeyframes: 0\n", "must be >= 1, found 0"},
      {"LocalMapping.redundancy: 0\n", "must be in (0, 1], found 0"},
      {"Loop.projectionRadius: -2.0\n", "must be > 0, found -2"},
      {"Tracking.minLocalMapInliers: 12.5\n", "expected integer"},
      {"Dynamic.forget: 0.99\n", "must be in [0, 0.96], found 0.99"},
      {"Dynamic.dynamicBelow: 1.0\n", "must be in [-20, 0], found 1"},
      {"Dynamic.regionCellSize: 4\n", "must be >= 8, found 4"},
      {"Dynamic.flowRatio: 0\n", "must be in (0, 1], found 0"},
      {"Initializer.minParallax: -1.0\n", "must be in [0, 90], found -1"},
      {"Initializer.sigma: 0\n", "must be > 0, found 0"},
      {"Initializer.minMatches: 5\n", "must be >= 8, found 5"},
  };
  for (const auto& [line, why] : cases) {
    const std::string message =
        test::errorOf([&] { (void)stageParamsOf(settingsOf("xyz-rgbd", line)); });
    const std::string key = line.substr(0, line.find(':'));
    EXPECT_NE(message.find("xyz-rgbd.yaml"), std::string::npos) << "for " << line << message;
    EXPECT_NE(message.find(key), std::string::npos) << "for " << line << message;
    EXPECT_NE(message.find(why), std::string::npos) << "for " << line << message;
  }
}

TEST(StageSettings, ATypoIsReportedWithTheKeyItMisses) {
  const auto settings = settingsOf("xyz-rgbd",
                                   "Tracking.minLocalMapInlier: 40\n"
                                   "LocalMapping.baIteration: 5\n"
                                   "Dynamic.dynamicBellow: -3\n"
                                   "Initializer.minParalax: 2\n");
  PipelineOptions options;
  options.sequential = true;
  options.vocabulary = "none";
  const Pipeline pipeline(settings, options);
  std::map<std::string, std::string> found;
  for (const auto& [key, suggestion] : core::unknownKeys(*settings.file)) found[key] = suggestion;
  EXPECT_EQ(found["Tracking.minLocalMapInlier"], "Tracking.minLocalMapInliers");
  EXPECT_EQ(found["LocalMapping.baIteration"], "LocalMapping.baIterations");
  EXPECT_EQ(found["Dynamic.dynamicBellow"], "Dynamic.dynamicBelow");
  EXPECT_EQ(found["Initializer.minParalax"], "Initializer.minParallax");
}

// The generator's file without the keys effectiveSettings prints, so that the printed lines
// can be appended without setting a key twice.
std::string withoutPrintedSections(std::string yaml) {
  const std::regex printed(
      "(ORBextractor|Tracking|Initializer|Dynamic|LocalMapping|Loop|Enhancement|Detector)\\."
      "[A-Za-z_.]+: .*\n|System\\.(sensor|sequential|newMapAfter): .*\n|"
      "Camera1?\\.(type|fx|fy|cx|cy|k1|k2|p1|p2|k3|width|height|newWidth|newHeight|fps|RGB): "
      ".*\n");
  return std::regex_replace(yaml, printed, "");
}

TEST(StageSettings, PrintedSettingsReadBackToTheSameValues) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 2, 1);
  const auto edited = test::presetSettings(sequence, [](std::string yaml) {
    return withoutPrintedSections(yaml) +
           "Camera.fx: 535.4\nCamera.fy: 539.2\nCamera.cx: 320.1\nCamera.cy: 247.6\n"
           "Camera.width: 640\nCamera.height: 480\nCamera.newWidth: 320\n"
           "Camera.newHeight: 240\nCamera.RGB: 0\n"
           "Tracking.minInlierFractionOfLast: 0.3\nTracking.motionSearchRadius: 7.3\n"
           "LocalMapping.redundancy: 0.85\nLoop.globalBundleAdjustment: 0\n"
           "ORBextractor.nFeatures: 1100\nDynamic.dynamicBelow: -2.5\n"
           "Initializer.minParallax: 1.5\nEnhancement.clahe.tilesX: 4\n"
           "Detector.type: box_file\nDetector.boxFile: boxes.txt\nDetector.stride: 3\n";
  });
  PipelineOptions options;
  options.sequential = true;
  const std::string printed = effectiveSettings(edited, options);
  for (const char* line :
       {"Tracking.minInlierFractionOfLast: 0.3\n", "Tracking.motionSearchRadius: 7.3\n",
        "Loop.globalBundleAdjustment: false\n", "ORBextractor.nFeatures: 1100\n",
        "System.sequential: true\n", "System.sensor: \"rgbd\"\n",
        "LocalMapping.triangulationNeighbours: 10\n", "Dynamic.motionEvidence: true\n",
        "Dynamic.dynamicBelow: -2.5\n", "Dynamic.forget: 0.95\n", "Initializer.minParallax: 1.5\n",
        "Initializer.ransacIterations: 200\n", "Enhancement.clahe.tilesX: 4\n",
        "Detector.type: \"box_file\"\n", "Detector.stride: 3\n", "Camera1.fx: 535.4\n",
        "Camera.newWidth: 320\n", "Camera.RGB: false\n", "Camera.type: \"PinHole\"\n"}) {
    EXPECT_NE(printed.find(line), std::string::npos) << line << " not in\n" << printed;
  }

  const auto reread = test::presetSettings(
      sequence, [&](std::string yaml) { return withoutPrintedSections(yaml) + printed; });
  EXPECT_EQ(effectiveSettings(reread, PipelineOptions{}), printed);
  for (const auto& [key, suggestion] : core::unknownKeys(*reread.file)) {
    EXPECT_EQ(printed.find(key + ":"), std::string::npos) << "printed a key nothing reads: " << key;
  }
}

TEST(StageSettings, WithoutADetectorTheTypeIsPrintedAsNone) {
  PipelineOptions options;
  const std::string printed = effectiveSettings(settingsOf("xyz-rgbd", ""), options);
  EXPECT_NE(printed.find("Detector.type: \"none\"\n"), std::string::npos) << printed;
  EXPECT_EQ(printed.find("Detector.stride"), std::string::npos);
  options.enhance_preset = "off";
  EXPECT_NE(
      effectiveSettings(settingsOf("xyz-rgbd", ""), options).find("Enhancement.preset: \"off\"\n"),
      std::string::npos);
}

// A sequential run of `frames` frames of `preset` (seed 1) with `extra` settings lines.
test::RunResult runWith(const std::string& preset, int frames, const std::string& extra,
                        std::optional<io::SensorType> sensor = std::nullopt) {
  test::RunConfig config;
  config.edit = [extra](std::string yaml) { return yaml + "\n" + extra; };
  config.sensor = sensor;
  return test::runOnPreset(preset, frames, 1, config);
}

// Effects on a run (sequential, deterministic: the mapper is always idle, so
// Tracking.maxFramesBetweenKeyframes, which applies to a busy mapper, has none): fewer
// keyframes when they come no sooner than 20 frames apart unless tracking is weak (the close
// points rule still makes some sooner, as in ORB-SLAM3: docs/settings.md), and local bundle
// adjustment off changes the poses.
TEST(StageSettings, ChangedKeysChangeWhatARunDoes) {
  const auto with = [](const std::string& extra) { return runWith("xyz-rgbd", 80, extra); };
  const auto defaults = with("");
  const auto spaced = with("Tracking.minFramesBetweenKeyframes: 20\n");
  const auto no_ba = with("LocalMapping.bundleAdjustment: false\n");
  EXPECT_EQ(defaults.tracked, 80U);
  EXPECT_EQ(spaced.tracked, 80U);
  EXPECT_LT(spaced.keyframes, defaults.keyframes);
  EXPECT_NE(no_ba.report.ate.stats.rmse, defaults.report.ate.stats.rmse);
}

// Dynamic.dynamicBelow: the log-odds under which a feature counts as moving. On a walking
// sequence (RGB-D, motion evidence on by default) a threshold nearer 0 flags more features.
TEST(StageSettings, DynamicBelowChangesTheMovingFeatures) {
  const auto with = [](const std::string& extra) { return runWith("walking-xyz-rgbd", 40, extra); };
  const auto defaults = with("");
  const auto eager = with("Dynamic.dynamicBelow: -0.5\n");
  EXPECT_GT(defaults.moving_features, 0U);
  EXPECT_GT(eager.moving_features, defaults.moving_features);
}

// Initializer.minParallax: the monocular two-view start waits for more parallax (xyz-rgbd's
// colour stream as a monocular camera).
TEST(StageSettings, InitializerMinParallaxDelaysTheMonocularStart) {
  const auto with = [](const std::string& extra) {
    return runWith("xyz-rgbd", 40, extra, io::SensorType::Monocular);
  };
  const auto defaults = with("");
  const auto patient = with("Initializer.minParallax: 3.0\n");
  ASSERT_TRUE(defaults.first_tracked.has_value());
  ASSERT_TRUE(patient.first_tracked.has_value());
  EXPECT_GT(*patient.first_tracked, *defaults.first_tracked);  // frame 13 -> 19 when written
}

}  // namespace
}  // namespace lumaslam
