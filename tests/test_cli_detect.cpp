// Runs the built `lumaslam detect`: --evaluate on the labelled daylight images, boxes and
// annotated output for a video with stride, and clear errors for bad models and inputs.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

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

// --draw-features on bus.jpg (4 people), as PNG so the drawn colours stay exact. The image
// drawn with the flag has the input's size and differs from the one without only by ORB
// features: dropped ones (filled red) inside the printed boxes grown by the mask margin
// (8 px, Detector.mask.margin_px) plus the circle radius, kept ones (green rings) outside
// them, and the white count line.
TEST(CliDetect, DrawFeaturesMarksFeaturesKeptOutsideAndDroppedInsideTheBoxes) {
  test::TempDir dir("cli_detect_features");
  const cv::Mat input = cv::imread(
      (test::dataDir() / "ultralytics_yolov5/data/images/bus.jpg").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(input.empty());
  const auto image = dir.path() / "bus.png";
  ASSERT_TRUE(cv::imwrite(image.string(), input));
  const std::string detect = "detect --model " + model("yolov5n.onnx") + " " + image.string();
  const auto plain = runCli(detect + " --output " + (dir.path() / "plain").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const auto drawn =
      runCli(detect + " --draw-features --output " + (dir.path() / "features").string());
  ASSERT_EQ(drawn.exit_code, 0) << drawn.output;

  // Boxes "bus.png person SCORE x y w h", the same in both runs.
  std::vector<cv::Rect2f> boxes;
  std::istringstream lines(drawn.output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string frame, name;
    float score = 0.0f;
    cv::Rect2f box;
    if (fields >> frame >> name >> score >> box.x >> box.y >> box.width >> box.height &&
        frame == "bus.png")
      boxes.push_back(box);
  }
  ASSERT_GE(boxes.size(), 3u) << drawn.output;
  const auto inBoxes = [&](cv::Point p, float grow) {
    for (const auto& b : boxes)
      if (p.x >= b.x - grow && p.x <= b.br().x + grow && p.y >= b.y - grow &&
          p.y <= b.br().y + grow)
        return true;
    return false;
  };

  const cv::Mat without = cv::imread((dir.path() / "plain/bus.png").string(), cv::IMREAD_COLOR);
  const cv::Mat with = cv::imread((dir.path() / "features/bus.png").string(), cv::IMREAD_COLOR);
  ASSERT_EQ(with.size(), input.size());
  ASSERT_EQ(without.size(), input.size());
  const cv::Vec3b red(0, 0, 255), green(0, 220, 0), white(255, 255, 255);
  const float margin = 8.0f, radius = 3.0f;
  int red_pixels = 0, green_pixels = 0, other_pixels = 0;
  for (int y = 0; y < with.rows; ++y) {
    for (int x = 0; x < with.cols; ++x) {
      const cv::Vec3b pixel = with.at<cv::Vec3b>(y, x);
      if (pixel == without.at<cv::Vec3b>(y, x)) continue;
      if (pixel == red) {
        ++red_pixels;
        EXPECT_TRUE(inBoxes({x, y}, margin + radius + 1)) << x << "," << y;
      } else if (pixel == green) {
        ++green_pixels;
        EXPECT_FALSE(inBoxes({x, y}, margin - radius - 1)) << x << "," << y;
      } else if (pixel != white) {
        ++other_pixels;
      }
    }
  }
  EXPECT_GT(red_pixels, 100);
  EXPECT_GT(green_pixels, 1000);
  EXPECT_EQ(other_pixels, 0);
}

}  // namespace
}  // namespace lumaslam
