// Runs the built `lumaslam detect`: --evaluate on the labelled daylight images, boxes and
// annotated output for a video with stride, and clear errors for bad models and inputs.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include "test_cli.h"
#include "test_paths.h"

namespace lumaslam {
namespace {

using test::runCli;
using RunResult = test::CliResult;

std::string model(const char* file) {
  return (test::modelsDir() / file).string();
}

TEST(CliDetect, EvaluatesTheDaylightLabels) {
  const auto labels = test::dataDir() / "labels" / "person_boxes.txt";
  const auto run =
      runCli("detect --model " + model("yolov5n.onnx") + " --evaluate " + labels.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("bus.jpg truth 4"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("zidane.jpg truth 2"), std::string::npos) << run.output;
  // The summary line: "recall R precision P (...)"; R >= 0.9 is the acceptance bar.
  const auto at = run.output.find("recall ");
  ASSERT_NE(at, std::string::npos) << run.output;
  EXPECT_GE(std::stod(run.output.substr(at + 7)), 0.9) << run.output;
}

TEST(CliDetect, VideoWithStrideWritesBoxesAndAnnotatedFrames) {
  test::TempDir out("cli_detect_video");
  const auto video = test::dataDir() / "opencv_samples/vtest/vtest.avi";
  const auto run =
      runCli("detect --model " + model("yolov5n-320.onnx") +
             " --stride 3 --max-frames 6 --output " + out.path().string() + " " + video.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("000000 person"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("000004 person"), std::string::npos)
      << run.output;  // a propagated frame
  EXPECT_TRUE(std::filesystem::exists(out.path() / "000005.jpg"));
  EXPECT_FALSE(std::filesystem::exists(out.path() / "000006.jpg"));
}

TEST(CliDetect, BadModelOrInputIsOneClearError) {
  test::TempDir dir("cli_detect_bad");
  const auto garbage = dir.path() / "x.onnx";
  std::ofstream(garbage) << "not a model";
  const auto image = test::dataDir() / "ultralytics_yolov5/data/images/bus.jpg";
  auto run = runCli("detect --model " + garbage.string() + " " + image.string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("lumaslam detect: error:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("x.onnx"), std::string::npos) << run.output;

  run = runCli("detect --model " + model("yolov5n-320.onnx") + " " +
               (dir.path() / "absent.jpg").string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("absent.jpg"), std::string::npos) << run.output;

  run = runCli("detect --model " + garbage.string() + " " + image.string() + " --max-frames 1e20");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.output.find("--max-frames: expected a whole number from 0 to 1000000000, "
                            "found '1e20'"),
            std::string::npos)
      << run.output;
}

}  // namespace
}  // namespace lumaslam
