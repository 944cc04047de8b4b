// Night recall of the person detector on the 3 annotated LLVIP night images (6 people),
// raw and after enhance::Enhancer ("best" preset). The numbers go to docs/dynamic.md; the
// assertions are floors below what was measured (0.667 raw and enhanced at IoU 0.5).
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/detect/box_labels.h"
#include "lumaslam/detect/detection_eval.h"
#include "lumaslam/detect/yolo_detector.h"
#include "lumaslam/enhance/enhancer.h"
#include "test_paths.h"

namespace lumaslam::detect {
namespace {

namespace fs = std::filesystem;

struct NightImage {
  cv::Mat bgr;
  std::vector<cv::Rect2f> people;
};

std::vector<NightImage> nightImages() {
  const fs::path root = test::dataDir() / "llvip/night_people_sample";
  std::vector<NightImage> images;
  for (const char* id : {"010005", "190001", "190005"}) {
    const auto annotation = readVocAnnotation(root / "Annotations" / (std::string(id) + ".xml"));
    NightImage image;
    for (const char* split : {"visible/test", "visible/train"}) {
      const fs::path path = root / split / annotation.filename;
      if (fs::exists(path)) image.bgr = cv::imread(path.string());
    }
    EXPECT_FALSE(image.bgr.empty()) << annotation.filename;
    for (const auto& box : annotation.boxes) {
      if (box.class_name == "person") image.people.push_back(box.box);
    }
    images.push_back(image);
  }
  return images;
}

TEST(NightRecall, RawAndEnhancedLlvipPeople) {
  DetectorParams params;
  params.model = test::modelsDir() / "yolov5n.onnx";
  YoloDetector detector(params);
  enhance::Enhancer enhancer(enhance::EnhancerParams::forPreset("best"));

  MatchCounts raw;
  MatchCounts enhanced;
  for (const auto& image : nightImages()) {
    raw += matchDetections(image.people, detector.detect(image.bgr, 0.0));
    const cv::Mat bright = enhancer.enhance(image.bgr).colour;
    ASSERT_EQ(bright.size(), image.bgr.size());
    enhanced += matchDetections(image.people, detector.detect(bright, 0.0));
  }
  ASSERT_EQ(raw.true_positives + raw.false_negatives, 6);
  std::printf("night recall raw %.3f (precision %.3f), enhanced %.3f (precision %.3f)\n",
              raw.recall(), raw.precision(), enhanced.recall(), enhanced.precision());
  RecordProperty("night_recall_raw", std::to_string(raw.recall()));
  RecordProperty("night_recall_enhanced", std::to_string(enhanced.recall()));
  EXPECT_GE(raw.recall(), 0.5);
  EXPECT_GE(enhanced.recall(), 0.5);
}

}  // namespace
}  // namespace lumaslam::detect
