// `lumaslam run --print-settings` (issue 21): the effective values of a shipped settings file
// for its sensor, with the command line's overrides, as a settings file that reads back; no
// dataset is opened and nothing is run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/loop/vocabulary_choice.h"
#include "test_cli.h"

namespace {

using lumaslam::test::runCli;
using lumaslam::test::sourceDir;

std::string printed(const std::string& config, const std::string& flags = "") {
  const auto result =
      runCli("run --dataset tum:/nowhere --settings " +
             (sourceDir() / "configs" / config).string() + " --print-settings " + flags);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const auto start = result.output.find("%YAML:1.0");
  EXPECT_NE(start, std::string::npos) << result.output;
  return start == std::string::npos ? "" : result.output.substr(start);
}

// Writes `text` (printed settings) to FILE, prints the settings of FILE, and expects the same
// lines again (the comment naming the file aside).
void expectPrintsTheSameAgain(const std::string& text, const std::filesystem::path& file) {
  std::ofstream(file) << text;
  const auto result =
      runCli("run --dataset tum:/nowhere --settings " + file.string() + " --print-settings");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto body = [](const std::string& s) {
    const auto from = s.find("\nCamera.");
    return from == std::string::npos ? s : s.substr(from);
  };
  EXPECT_EQ(body(result.output.substr(result.output.find("%YAML:1.0"))), body(text)) << file;
}

TEST(CliPrintSettings, ShowsTheSensorDefaultsOfAMonocularFile) {
  const std::string text = printed("kitti_04-12_mono.yaml");
  EXPECT_NE(text.find("Tracking.waitForBusyMapper: true\n"), std::string::npos) << text;
  EXPECT_NE(text.find("LocalMapping.triangulationNeighbours: 20\n"), std::string::npos);
  EXPECT_NE(text.find("Tracking.maxFramesBetweenKeyframes: 10\n"), std::string::npos);  // 10 Hz
  EXPECT_NE(text.find("ORBextractor.nFeatures: 2000\n"), std::string::npos);
  EXPECT_NE(text.find("System.sequential: false\n"), std::string::npos);
  EXPECT_EQ(text.find("lumaslam_out"), std::string::npos);  // nothing was run
}

TEST(CliPrintSettings, ShowsEverySection) {
  const std::string text = printed("kitti_04-12_mono.yaml");
  for (const char* line :
       {"System.sensor: \"mono\"\n", "Camera.type: \"Rectified\"\n", "Camera1.fx: 707.0912\n",
        "Camera.fps: 10.0\n", "Enhancement.preset: \"best\"\n", "Detector.type: \"none\"\n",
        "Initializer.minParallax: 1.0\n", "Initializer.ransacIterations: 200\n",
        "Dynamic.motionEvidence: false\n", "Dynamic.dynamicBelow: -2.0\n",
        "Dynamic.confirmedAbove: 0.9\n", "Dynamic.forget: 0.95\n"}) {
    EXPECT_NE(text.find(line), std::string::npos) << line << " not in\n" << text;
  }
  EXPECT_EQ(text.find("Camera1.k1"), std::string::npos);  // a Rectified camera has none
}

// A monocular file's printed settings are a settings file of their own (camera 1, sensor and
// every printed section): given as --settings, they print the same lines again.
TEST(CliPrintSettings, PrintedSettingsPrintTheSameAgain) {
  lumaslam::test::TempDir dir("print_settings_again");
  expectPrintsTheSameAgain(printed("kitti_04-12_mono.yaml", "--sequential --no-motion-evidence"),
                           dir.path() / "again.yaml");
}

TEST(CliPrintSettings, ABadNewKeyIsAnErrorNamingIt) {
  lumaslam::test::TempDir dir("print_settings_bad_dynamic");
  const auto settings = dir.path() / "bad.yaml";
  std::ofstream(settings) << lumaslam::test::readTextFile(sourceDir() / "configs" /
                                                          "tum_fr1_rgbd.yaml")
                          << "\nDynamic.dynamicBelow: 0.5\n";
  const auto result =
      runCli("run --dataset tum:/nowhere --settings " + settings.string() + " --print-settings");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("bad.yaml"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("key 'Dynamic.dynamicBelow': must be in [-20, 0], found 0.5"),
            std::string::npos)
      << result.output;
}

TEST(CliPrintSettings, ShowsCommandLineOverrides) {
  const std::string text = printed("tum_fr1_rgbd.yaml", "--sequential --no-motion-evidence");
  EXPECT_NE(text.find("System.sequential: true\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Dynamic.motionEvidence: false\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Tracking.waitForBusyMapper: false\n"), std::string::npos) << text;
}

TEST(CliPrintSettings, TheOutputIsASettingsFile) {
  const std::string text = printed("euroc_stereo.yaml");
  const auto file = lumaslam::core::SettingsFile::fromString(text, "printed");
  EXPECT_EQ(file.get<int>("Tracking.minInitialFeatures"), 250);  // the stereo default
  EXPECT_EQ(file.get<bool>("LocalMapping.bundleAdjustment"), true);
  EXPECT_EQ(file.get<int>("Loop.minInliers"), 40);
}

TEST(CliPrintSettings, ShowsTheSecondCameraAndTheStereoKeys) {
  const std::string stereo = printed("euroc_stereo.yaml");
  for (const char* line :
       {"Camera2.fx: 457.587\n", "Camera2.p2: -3.555907e-05\n", "Stereo.ThDepth: 60.0\n",
        "Stereo.T_c1_c2: !!opencv-matrix\n", "System.newMapAfter: 1.0\n"}) {
    EXPECT_NE(stereo.find(line), std::string::npos) << line << " not in\n" << stereo;
  }
  EXPECT_NE(stereo.find("Stereo.b: "), std::string::npos) << stereo;
  const std::string rgbd = printed("tum_fr1_rgbd.yaml");
  for (const char* line : {"RGBD.DepthMapFactor: 5000.0\n", "Stereo.ThDepth: 40.0\n"}) {
    EXPECT_NE(rgbd.find(line), std::string::npos) << line << " not in\n" << rgbd;
  }
  EXPECT_EQ(rgbd.find("Camera2."), std::string::npos);
  const std::string mono = printed("kitti_04-12_mono.yaml");
  EXPECT_EQ(mono.find("Stereo."), std::string::npos);
  EXPECT_EQ(mono.find("RGBD."), std::string::npos);
}

// Stereo (an unrectified pair with Camera2.* and T_c1_c2, a rectified pair) and RGB-D: the
// printed lines alone are a settings file that prints the same lines again.
TEST(CliPrintSettings, PrintedStereoAndRgbdSettingsPrintTheSameAgain) {
  lumaslam::test::TempDir dir("print_settings_sensors");
  for (const char* config : {"euroc_stereo.yaml", "kitti_04-12_stereo.yaml", "tum_fr1_rgbd.yaml"}) {
    expectPrintsTheSameAgain(printed(config), dir.path() / (std::string("again_") + config));
  }
}

// Where a run's data and vocabulary come from: the dataset folder and the vocabulary as absolute
// paths (relative ones are resolved against the settings file's folder), the default vocabulary
// when nothing is named, and the command line over the file.
TEST(CliPrintSettings, ShowsTheDatasetRootTheVocabularyAndLoopClosing) {
  lumaslam::test::TempDir dir("print_settings_sources");
  const auto settings = dir.path() / "sources.yaml";
  std::ofstream(settings) << lumaslam::test::readTextFile(sourceDir() / "configs" /
                                                          "tum_fr1_rgbd.yaml")
                          << "\nSystem.datasetRoot: \"data\"\nLoop.vocabulary: \"none\"\n"
                             "Loop.closing: 0\n";
  const auto result =
      runCli("run --dataset tum:/nowhere --settings " + settings.string() + " --print-settings");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::string text = result.output.substr(result.output.find("%YAML:1.0"));
  for (const std::string line :
       {"System.datasetRoot: \"" + (dir.path() / "data").string() + "\"\n",
        std::string("Loop.vocabulary: \"none\"\n"), std::string("Loop.closing: false\n")}) {
    EXPECT_NE(text.find(line), std::string::npos) << line << " not in\n" << text;
  }
  expectPrintsTheSameAgain(text, dir.path() / "again.yaml");

  const std::string shipped = printed("tum_fr1_rgbd.yaml");
  EXPECT_EQ(shipped.find("System.datasetRoot"), std::string::npos);
  const auto vocabulary = shipped.find("Loop.vocabulary: \"/");
  ASSERT_NE(vocabulary, std::string::npos) << shipped;
  EXPECT_NE(shipped.find(lumaslam::loop::defaultVocabularyName() + "\"\n", vocabulary),
            std::string::npos)
      << shipped;
  EXPECT_NE(shipped.find("Loop.closing: true\n"), std::string::npos) << shipped;

  const std::string overridden =
      printed("tum_fr1_rgbd.yaml", "--vocabulary none --no-loop-closing");
  EXPECT_NE(overridden.find("Loop.vocabulary: \"none\"\n"), std::string::npos) << overridden;
  EXPECT_NE(overridden.find("Loop.closing: false\n"), std::string::npos) << overridden;
}

// An unrectified pair is tracked in its rectified images; their camera is shown as a comment
// (the same numbers the run logs), a rectified pair has none.
TEST(CliPrintSettings, ShowsTheRectifiedCameraOfAnUnrectifiedPair) {
  const std::string euroc = printed("euroc_stereo.yaml");
  EXPECT_NE(euroc.find("\n# rectified pair, as tracked: fx "), std::string::npos) << euroc;
  EXPECT_EQ(printed("kitti_04-12_stereo.yaml").find("# rectified pair"), std::string::npos);
  EXPECT_EQ(printed("tum_fr1_rgbd.yaml").find("# rectified pair"), std::string::npos);
}

TEST(CliPrintSettings, ABadValueIsAnErrorNamingTheKey) {
  lumaslam::test::TempDir dir("print_settings");
  const auto settings = dir.path() / "bad.yaml";
  std::ofstream(settings) << lumaslam::test::readTextFile(sourceDir() / "configs" /
                                                          "tum_fr1_rgbd.yaml")
                          << "\nTracking.minLocalMapInliers: 0\n";
  const auto result =
      runCli("run --dataset tum:/nowhere --settings " + settings.string() + " --print-settings");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("key 'Tracking.minLocalMapInliers': must be >= 1, found 0"),
            std::string::npos)
      << result.output;
}

}  // namespace
