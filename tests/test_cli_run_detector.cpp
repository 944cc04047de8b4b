// `lumaslam run --detector`: dynamic-object removal on a synthetic walking dataset with its
// own detections.txt; sequential runs with YOLO in the loop are byte-identical; bad specs and
// missing files give a clear error and a non-zero exit.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_cli.h"
#include "test_paths.h"

namespace {

using lumaslam::test::readRunSummary;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

TEST(CliRunDetector, RemovesTheBoxesOfASyntheticWalkingDataset) {
  TempDir dir("cli_run_detector");
  const auto data = dir.path() / "data";
  const auto out = dir.path() / "out";
  const auto synth =
      runCli("synth " + data.string() + " --preset walking-xyz-rgbd --frames 40 --seed 1");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const auto run = runCli("run --dataset tum:" + data.string() +
                          " --detector boxes:" + (data / "detections.txt").string() +
                          " --sequential --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;

  const auto summary = readRunSummary(out);
  EXPECT_NE(summary["detector"]["name"].get<std::string>().find("box_file"), std::string::npos);
  EXPECT_GT(summary["detector"]["dropped_features_per_frame"].get<double>(), 10.0);
  EXPECT_EQ(summary["tracked"].get<int>(), 40);

  std::ifstream timing(out / "timing.csv");
  std::string header;
  std::getline(timing, header);
  EXPECT_NE(header.find("detection_wait_ms,detection_ms,boxes,dropped_features"), std::string::npos)
      << header;
  const auto split = [](const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream in(line);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    return fields;
  };
  const auto columns = split(header);
  const auto dropped = static_cast<std::size_t>(
      std::find(columns.begin(), columns.end(), "dropped_features") - columns.begin());
  ASSERT_LT(dropped, columns.size()) << header;
  std::string row;
  int rows_with_drops = 0;
  while (std::getline(timing, row)) {
    const auto fields = split(row);
    if (dropped < fields.size() && fields[dropped] != "0") ++rows_with_drops;
  }
  EXPECT_GT(rows_with_drops, 10);
}

// System.sequential runs detection in the caller's thread like every other stage (issue 21),
// so two runs with YOLO in the loop write the same bytes.
TEST(CliRunDetector, SequentialRunsWithYoloAreByteIdentical) {
  const auto model = lumaslam::test::modelsDir() / "yolov5n-320.onnx";
  ASSERT_TRUE(std::filesystem::exists(model)) << "no YOLO model at " << model;
  TempDir dir("cli_run_detector_yolo_sequential");
  const auto data = dir.path() / "data";
  const auto synth =
      runCli("synth " + data.string() + " --preset walking-xyz-rgbd --frames 40 --seed 3");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  // The generator's settings list its box class too, which YOLO's COCO model does not know.
  const std::string settings =
      std::regex_replace(readTextFile(data / "settings.yaml"), std::regex("Detector.classes: .*"),
                         "Detector.classes: \"person\"");
  std::ofstream(dir.path() / "settings.yaml") << settings;
  std::vector<std::string> trajectories;
  for (const char* name : {"a", "b"}) {
    const auto out = dir.path() / name;
    const auto run =
        runCli("run --dataset tum:" + data.string() + " --settings " +
               (dir.path() / "settings.yaml").string() + " --detector yolo:" + model.string() +
               " --sequential --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_GT(readRunSummary(out)["detector"]["dropped_features_per_frame"].get<double>(), 10.0);
    trajectories.push_back(readTextFile(out / "trajectory.txt"));
  }
  EXPECT_GT(std::count(trajectories[0].begin(), trajectories[0].end(), '\n'), 30);
  EXPECT_EQ(trajectories[0], trajectories[1]);
}

TEST(CliRunDetector, BadDetectorSpecOrMissingFileIsAClearError) {
  TempDir dir("cli_run_detector_bad");
  const auto data = dir.path() / "data";
  ASSERT_EQ(runCli("synth " + data.string() + " --preset walking-xyz-rgbd --frames 3").exit_code,
            0);
  const std::string run = "run --dataset tum:" + data.string() + " --out " +
                          (dir.path() / "out").string() + " --detector ";
  const auto magic = runCli(run + "magic");
  EXPECT_NE(magic.exit_code, 0);
  EXPECT_NE(magic.output.find("--detector 'magic'"), std::string::npos) << magic.output;
  const auto missing = runCli(run + "boxes:" + (dir.path() / "absent.txt").string());
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("absent.txt"), std::string::npos) << missing.output;
  const auto no_model = runCli(run + "yolo:" + (dir.path() / "absent.onnx").string());
  EXPECT_NE(no_model.exit_code, 0);
  EXPECT_NE(no_model.output.find("absent.onnx"), std::string::npos) << no_model.output;
}

}  // namespace

namespace {

// The class-free motion test (issue 16) is on for RGB-D with no detector at all; summary.json
// says so and how much it flagged, timing.csv has its columns; --no-motion-evidence turns it off.
TEST(CliRunDetector, MotionEvidenceIsReportedAndCanBeTurnedOff) {
  TempDir dir("cli_run_motion");
  const auto data = dir.path() / "data";
  const auto synth =
      runCli("synth " + data.string() + " --preset walking-xyz-rgbd --frames 40 --seed 1");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  for (const bool off : {false, true}) {
    const auto out = dir.path() / (off ? "off" : "on");
    const auto run =
        runCli("run --dataset tum:" + data.string() + " --detector none" +
               (off ? " --no-motion-evidence" : "") + " --sequential --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto summary = readRunSummary(out);
    EXPECT_EQ(summary["motion_evidence"]["on"].get<bool>(), !off);
    const double moving = summary["motion_evidence"]["moving_features_per_frame"].get<double>();
    if (off) {
      EXPECT_EQ(moving, 0.0);
    } else {
      EXPECT_GT(moving, 5.0);  // the crate and the walkers
    }
    std::ifstream timing(out / "timing.csv");
    std::string header;
    std::getline(timing, header);
    EXPECT_NE(header.find(",moving_features,motion_ms"), std::string::npos) << header;
  }
}

}  // namespace
