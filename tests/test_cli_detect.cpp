// Runs the built `lumaslam detect`: --evaluate on the labelled daylight images, boxes and
// annotated output for a video with stride, recall on a synthetic sequence at strides, and
// clear errors for bad models and inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
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

// A sequence evaluation's summary "recall R precision P (tp T fp F fn N, ...)".
struct Summary {
  double recall = -1.0;
  int tp = -1, fp = -1, fn = -1;
};

Summary summaryOf(const std::string& output) {
  Summary s;
  const auto at = output.find("\nrecall ");
  if (at == std::string::npos) return s;
  std::sscanf(output.c_str() + at, "\nrecall %lf precision %*f (tp %d fp %d fn %d", &s.recall,
              &s.tp, &s.fp, &s.fn);
  return s;
}

struct ScoredBox {
  float score = 1.0f;
  cv::Rect2f box;
};
using BoxesByFrame = std::map<std::string, std::vector<ScoredBox>>;

// Lines "FRAME person [SCORE] x y w h" of a detections.txt (no score) or of `detect` on a
// folder (FRAME = image file name, the extension dropped so it is the timestamp).
BoxesByFrame personBoxes(const std::string& text, bool with_score) {
  BoxesByFrame frames;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string frame, name;
    ScoredBox b;
    if (!(fields >> frame >> name) || name != "person" || (with_score && !(fields >> b.score)))
      continue;
    if (!(fields >> b.box.x >> b.box.y >> b.box.width >> b.box.height)) continue;
    frames[frame.substr(0, frame.rfind(".png"))].push_back(b);
  }
  return frames;
}

// The test's own greedy IoU >= 0.5 matching, highest score first (the VOC rule).
Summary countMatches(const BoxesByFrame& truth, BoxesByFrame detected) {
  Summary s{0.0, 0, 0, 0};
  for (const auto& [frame, truth_boxes] : truth) {
    auto& boxes = detected[frame];
    std::stable_sort(boxes.begin(), boxes.end(),
                     [](const ScoredBox& a, const ScoredBox& b) { return a.score > b.score; });
    std::vector<bool> used(truth_boxes.size(), false);
    for (const auto& d : boxes) {
      int best = -1;
      float best_iou = 0.5f;
      for (std::size_t i = 0; i < truth_boxes.size(); ++i) {
        const cv::Rect2f t = truth_boxes[i].box;
        const float inter = (t & d.box).area();
        const float iou = inter / (t.area() + d.box.area() - inter);
        if (!used[i] && iou >= best_iou) best = static_cast<int>(i), best_iou = iou;
      }
      if (best < 0)
        ++s.fp;
      else
        used[static_cast<std::size_t>(best)] = true, ++s.tp;
    }
    s.fn += static_cast<int>(std::count(used.begin(), used.end(), false));
  }
  for (const auto& [frame, boxes] : detected)  // frames without any truth box
    if (!truth.count(frame)) s.fp += static_cast<int>(boxes.size());
  s.recall = s.tp + s.fn > 0 ? static_cast<double>(s.tp) / (s.tp + s.fn) : 1.0;
  return s;
}

// 20 frames of photo walkers. At stride 1 the sequence evaluation must count exactly what the
// test counts itself from the single-image boxes of the same frames (`detect rgb/`) against
// detections.txt; at stride 2 (detections propagated to every other frame) the recall stays
// close to it; a missing or malformed truth file is an error naming it.
TEST(CliDetect, SequenceEvaluationCountsAsTheSingleImageBoxesAndStridesStayClose) {
  test::TempDir dir("cli_detect_sequence");
  const auto data = dir.path() / "pw";
  const auto synth =
      runCli("synth " + data.string() +
             " --preset walking-xyz-rgbd --frames 20 --seed 1 --moving-boxes 0" +
             " --people-images " + (test::dataDir() / "labels" / "person_boxes.txt").string());
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const std::string evaluate = "detect " + data.string() + " --model " + model("yolov5n-320.onnx") +
                               " --evaluate " + (data / "detections.txt").string();
  const auto stride1 = runCli(evaluate + " --stride 1");
  ASSERT_EQ(stride1.exit_code, 0) << stride1.output;
  const Summary sequence = summaryOf(stride1.output);

  const auto single =
      runCli("detect --model " + model("yolov5n-320.onnx") + " " + (data / "rgb").string());
  ASSERT_EQ(single.exit_code, 0) << single.output;
  const auto truth = personBoxes(test::readTextFile(data / "detections.txt"), false);
  const Summary oracle = countMatches(truth, personBoxes(single.output, true));
  std::printf("stride 1: recall %.3f (tp %d fp %d fn %d), oracle tp %d fp %d fn %d\n",
              sequence.recall, sequence.tp, sequence.fp, sequence.fn, oracle.tp, oracle.fp,
              oracle.fn);
  ASSERT_GE(oracle.tp + oracle.fn, 15);  // people are in view on most frames
  EXPECT_GE(oracle.tp, 5);
  EXPECT_EQ(sequence.tp, oracle.tp) << stride1.output;
  EXPECT_EQ(sequence.fp, oracle.fp) << stride1.output;
  EXPECT_EQ(sequence.fn, oracle.fn) << stride1.output;

  const auto stride2 = runCli(evaluate + " --stride 2");
  ASSERT_EQ(stride2.exit_code, 0) << stride2.output;
  const Summary propagated = summaryOf(stride2.output);
  std::printf("stride 2: recall %.3f (tp %d fp %d fn %d)\n", propagated.recall, propagated.tp,
              propagated.fp, propagated.fn);
  EXPECT_EQ(propagated.tp + propagated.fn, sequence.tp + sequence.fn);  // same truth
  EXPECT_GE(propagated.recall, sequence.recall - 0.2);
  EXPECT_LE(propagated.recall, sequence.recall + 0.1);
  EXPECT_NE(stride2.output.find("(10 frames, stride 2)"), std::string::npos) << stride2.output;

  auto run = runCli("detect " + data.string() + " --model " + model("yolov5n-320.onnx") +
                    " --evaluate " + (dir.path() / "absent.txt").string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("absent.txt"), std::string::npos) << run.output;
  const auto bad = dir.path() / "bad.txt";
  std::ofstream(bad) << "# comment\n1.0 person 1 2 3\n";
  run = runCli("detect tum:" + data.string() + " --model " + model("yolov5n-320.onnx") +
               " --evaluate " + bad.string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("bad.txt:2"), std::string::npos) << run.output;
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
