#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/detect/detector_spec.h"

namespace {

using namespace lumaslam;
using detect::detectorParamsFor;
using test::errorOf;

core::SettingsFile settings(const std::string& text) {
  return core::SettingsFile::fromString(text, "run.yaml");
}

TEST(DetectorSpec, SettingsDecideWithoutASpec) {
  EXPECT_FALSE(detectorParamsFor(nullptr, std::nullopt));
  const auto tuning_only = settings("Detector.maskMargin: 4\n");
  EXPECT_FALSE(detectorParamsFor(&tuning_only, std::nullopt));  // names no detector
  const auto off = settings("Detector.type: none\nDetector.model: m.onnx\n");
  EXPECT_FALSE(detectorParamsFor(&off, std::nullopt));
  const auto yolo = settings("Detector.model: m.onnx\nDetector.image: enhanced\n");
  const auto params = detectorParamsFor(&yolo, std::nullopt);
  ASSERT_TRUE(params);
  EXPECT_EQ(params->type, "yolo");
  EXPECT_EQ(params->model, "m.onnx");
  EXPECT_EQ(params->image, "enhanced");
  EXPECT_EQ(detect::describeChoice(params), "yolo m.onnx");
  const auto bad_image = settings("Detector.model: m.onnx\nDetector.image: both\n");
  EXPECT_THROW(detectorParamsFor(&bad_image, std::nullopt), Error);
}

TEST(DetectorSpec, ASpecReplacesTheSourceAndKeepsTheTuning) {
  const auto file = settings("Detector.maskMargin: 4\nDetector.classes: \"person, box\"\n");
  const auto boxes = detectorParamsFor(&file, std::string("boxes:/data/detections.txt"));
  ASSERT_TRUE(boxes);
  EXPECT_EQ(boxes->type, "box_file");
  EXPECT_EQ(boxes->box_file, "/data/detections.txt");
  EXPECT_EQ(boxes->mask.margin_px, 4);
  EXPECT_EQ(boxes->classes, (std::vector<std::string>{"person", "box"}));
  EXPECT_EQ(detect::describeChoice(boxes), "box_file /data/detections.txt");

  const auto yolo = detectorParamsFor(nullptr, std::string("yolo:models/y.onnx"));
  ASSERT_TRUE(yolo);
  EXPECT_EQ(yolo->type, "yolo");
  EXPECT_EQ(yolo->model, "models/y.onnx");

  const auto named = settings("Detector.model: m.onnx\n");
  EXPECT_FALSE(detectorParamsFor(&named, std::string("none")));
  EXPECT_EQ(detect::describeChoice(std::nullopt), "none");
}

TEST(DetectorSpec, MalformedSpecsNameTheSpec) {
  for (const std::string spec : {"magic", "yolo", "yolo:", "boxes", "box:f.txt", ""}) {
    const std::string message = errorOf([&] { detectorParamsFor(nullptr, spec); });
    EXPECT_NE(message.find("--detector '" + spec + "'"), std::string::npos)
        << "for '" << spec << "': " << message;
  }
}

}  // namespace
