// BoxFileDetector (boxes from a text file matched to frames by timestamp), the
// Detector.* settings, and the label readers used by `detect --evaluate`.
#include <fstream>

#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/detect/box_file_detector.h"
#include "lumaslam/detect/box_labels.h"
#include "lumaslam/detect/detection_eval.h"
#include "lumaslam/detect/detector_factory.h"
#include "test_paths.h"

namespace lumaslam::detect {
namespace {

std::filesystem::path writeFile(const test::TempDir& dir, const std::string& name,
                                const std::string& text) {
  const auto path = dir.path() / name;
  std::ofstream(path) << text;
  return path;
}

using test::errorOf;

TEST(BoxFileDetector, MatchesFramesToTheNearestTimestampWithinTolerance) {
  test::TempDir dir("detect_box_file");
  DetectorParams params;
  params.type = "box_file";
  params.box_file = writeFile(dir, "detections.txt",
                              "# timestamp class x y w h\n"
                              "1.000 person 10 20 30 40\n"
                              "1.000 person 100 20 30 40   # second person\n"
                              "1.000 chair 5 5 5 5\n"
                              "\n"
                              "1.100 person 12 20 30 40\n"
                              "2.000 chair 1 1 1 1\n");
  params.box_file_tolerance = 0.02;
  auto detector = makeDetector(params);
  const cv::Mat no_image;

  auto at_one = detector->detect(no_image, 1.005);
  ASSERT_EQ(at_one.size(), 2u);  // chair filtered out (classes = person)
  EXPECT_EQ(at_one[0].class_name, "person");
  EXPECT_EQ(at_one[0].box, cv::Rect2f(10, 20, 30, 40));
  EXPECT_EQ(at_one[1].box, cv::Rect2f(100, 20, 30, 40));

  const auto near_second = detector->detect(no_image, 1.09);  // 1.1 is nearer than 1.0
  ASSERT_EQ(near_second.size(), 1u);
  EXPECT_EQ(near_second[0].box.x, 12.0f);

  EXPECT_TRUE(detector->detect(no_image, 1.05).empty());  // 0.05 s from both: beyond tolerance
  EXPECT_TRUE(detector->detect(no_image, 2.0).empty());   // only a chair there
  EXPECT_TRUE(detector->detect(no_image, -10.0).empty());
  EXPECT_TRUE(detector->detect(no_image, 100.0).empty());

  params.classes = {"person", "chair"};
  BoxFileDetector both(params);
  EXPECT_EQ(both.frameCount(), 3u);
  EXPECT_EQ(both.detect(no_image, 1.0).size(), 3u);
}

TEST(BoxFileDetector, NumericClassesUseTheNamesFile) {
  test::TempDir dir("detect_box_ids");
  DetectorParams params;
  params.type = "box_file";
  params.box_file = writeFile(dir, "ids.txt", "0.5 0 1 2 3 4\n0.5 2 1 2 3 4\n");
  EXPECT_NE(errorOf([&] { BoxFileDetector d(params); }).find("ids.txt:1"), std::string::npos);

  params.names = test::modelsDir() / "coco80.names";
  BoxFileDetector detector(params);
  const auto boxes = detector.detect({}, 0.5);
  ASSERT_EQ(boxes.size(), 1u);  // class 2 is "car"
  EXPECT_EQ(boxes[0].class_id, 0);
  EXPECT_EQ(boxes[0].class_name, "person");
}

TEST(BoxFileDetector, ClassIdBeyondIntRangeIsAnError) {
  // Found by fuzz/box_file_fuzz.cpp: std::stoi's std::out_of_range escaped instead of an Error.
  test::TempDir dir("detect_box_big_id");
  DetectorParams params;
  params.type = "box_file";
  params.names = test::modelsDir() / "coco80.names";
  params.box_file = writeFile(dir, "ids.txt", "0.5 0 1 2 3 4\n0.5 99999999999 1 2 3 4\n");
  const std::string message = errorOf([&] { BoxFileDetector d(params); });
  EXPECT_NE(message.find("ids.txt:2: class id 99999999999"), std::string::npos) << message;
}

TEST(BoxFileDetector, GarbageLinesNameFileAndLine) {
  test::TempDir dir("detect_box_garbage");
  DetectorParams params;
  params.type = "box_file";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"1.0 person 1 2 3 4\nhello world\n", ":2:"},
      {"1.0 person 1 2 3\n", ":1:"},
      {"# ok\n1.0 person 1 2 3 4 5\n", ":2:"},
      {"1.0 person 1 2 -3 4\n", ":1:"},
      {"1.0 person 1 2 x 4\n", ":1:"},
  };
  for (const auto& [text, where] : cases) {
    params.box_file = writeFile(dir, "bad.txt", text);
    const std::string message = errorOf([&] { BoxFileDetector d(params); });
    EXPECT_NE(message.find("bad.txt" + where), std::string::npos) << text << " -> " << message;
  }
  params.box_file = dir.path() / "missing.txt";
  EXPECT_NE(errorOf([&] { BoxFileDetector d(params); }).find("missing.txt"), std::string::npos);
}

TEST(DetectorParams, ReadsSettingsAndNamesTheBadKey) {
  const auto settings = core::SettingsFile::fromString(
      "Detector.model: \"m.onnx\"\n"
      "Detector.classes: \"person, bicycle\"\n"
      "Detector.confidence: 0.4\n"
      "Detector.stride: 3\n"
      "Detector.maskMargin: 5\n",
      "test.yaml");
  const auto params = DetectorParams::fromSettings(settings);
  EXPECT_EQ(params.model, "m.onnx");
  EXPECT_EQ(params.namesPath(), "coco80.names");
  EXPECT_EQ(params.classes, (std::vector<std::string>{"person", "bicycle"}));
  EXPECT_FLOAT_EQ(params.confidence_threshold, 0.4f);
  EXPECT_EQ(params.stride, 3);
  EXPECT_EQ(params.mask.margin_px, 5);
  EXPECT_FLOAT_EQ(params.nms_threshold, 0.45f);  // default kept

  const std::vector<std::pair<std::string, std::string>> bad{
      {"Detector.model: m.onnx\nDetector.stride: 0\n", "Detector.stride"},
      {"Detector.model: m.onnx\nDetector.confidence: 1.5\n", "Detector.confidence"},
      {"Detector.model: m.onnx\nDetector.inputSize: 300\n", "Detector.inputSize"},
      {"Detector.model: m.onnx\nDetector.type: magic\n", "Detector.type"},
      {"Detector.confidence: 0.5\n", "Detector.model"},
      {"Detector.type: box_file\n", "Detector.boxFile"},
  };
  for (const auto& [text, key] : bad) {
    const std::string message = errorOf(
        [&] { DetectorParams::fromSettings(core::SettingsFile::fromString(text, "bad.yaml")); });
    EXPECT_NE(message.find("bad.yaml"), std::string::npos) << message;
    EXPECT_NE(message.find(key), std::string::npos) << message;
  }
}

TEST(BoxLabels, ReadsTheSharedLabelsAndVocAnnotations) {
  const auto labels = readBoxList(test::dataDir() / "labels" / "person_boxes.txt");
  ASSERT_EQ(labels.size(), 2u);
  const auto& bus = labels.at("ultralytics_yolov5/data/images/bus.jpg");
  ASSERT_EQ(bus.size(), 5u);
  EXPECT_EQ(bus[0].class_name, "person");
  EXPECT_EQ(bus[0].box, cv::Rect2f(50, 398, 195, 507));

  const auto voc =
      readVocAnnotation(test::dataDir() / "llvip/night_people_sample/Annotations/190001.xml");
  EXPECT_EQ(voc.filename, "190001.jpg");
  ASSERT_EQ(voc.boxes.size(), 2u);
  EXPECT_EQ(voc.boxes[1].class_name, "person");
  EXPECT_EQ(voc.boxes[1].box, cv::Rect2f(1204, 304, 76, 227));

  test::TempDir dir("detect_labels");
  const auto bad = writeFile(dir, "labels.txt", "a.jpg person 1 2 3 4\nb.jpg person 5 5 1 1\n");
  EXPECT_NE(errorOf([&] { readBoxList(bad); }).find("labels.txt:2"), std::string::npos);
  const auto bad_xml = writeFile(dir, "a.xml",
                                 "<filename>a.jpg</filename><object><name>person</name>"
                                 "<bndbox><xmin>1</xmin><ymin>q</ymin></bndbox></object>");
  EXPECT_NE(errorOf([&] { readVocAnnotation(bad_xml); }).find("a.xml"), std::string::npos);
}

// Found by fuzzing (fuzz/regressions/box_labels): std::regex recursed once per character and
// overflowed the stack on a long element; the plain search reads it, same rules as before.
TEST(BoxLabels, VocAnnotationWithLongElementsAndRegexRules) {
  test::TempDir dir("detect_labels_long");
  const std::string long_name(200000, 'a');
  const auto xml =
      writeFile(dir, "long.xml",
                "<filename>\n " + long_name + " \t</filename><object>" + std::string(200000, ' ') +
                    "<name>person</name><bndbox><xmin>1</xmin><ymin>2</ymin>"
                    "<xmax>4</xmax><ymax>7</ymax></bndbox></object><object>");
  const auto voc = readVocAnnotation(xml);
  EXPECT_EQ(voc.filename, long_name);
  ASSERT_EQ(voc.boxes.size(), 1u);  // an <object> without </object> is not one
  EXPECT_EQ(voc.boxes[0].box, cv::Rect2f(1, 2, 3, 5));
  // The first <tag> whose text has no '<' and ends at </tag> counts.
  const auto nested =
      writeFile(dir, "nested.xml", "<filename><b>x</b></filename><filename> c.jpg </filename>");
  EXPECT_EQ(readVocAnnotation(nested).filename, "c.jpg");
}

TEST(MatchDetections, CountsHitsMissesAndDuplicates) {
  const std::vector<cv::Rect2f> truth{{0, 0, 10, 10}, {100, 100, 10, 10}};
  Detections detections{
      {0, "person", 0.9f, {1, 0, 10, 10}},      // hit (IoU 0.82)
      {0, "person", 0.8f, {0, 1, 10, 10}},      // duplicate of the same truth: false positive
      {0, "person", 0.7f, {105, 105, 10, 10}},  // IoU 0.14: false positive
  };
  const auto counts = matchDetections(truth, detections, 0.5f);
  EXPECT_EQ(counts.true_positives, 1);
  EXPECT_EQ(counts.false_positives, 2);
  EXPECT_EQ(counts.false_negatives, 1);
  EXPECT_DOUBLE_EQ(counts.recall(), 0.5);
  EXPECT_DOUBLE_EQ(counts.precision(), 1.0 / 3.0);
}

}  // namespace
}  // namespace lumaslam::detect
