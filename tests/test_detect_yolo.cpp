// YOLOv5 through OpenCV DNN: output decoding and letterbox on synthetic data with known
// answers, then the real models on the labelled daylight images, and bad model files.
#include <fstream>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/detect/box_labels.h"
#include "lumaslam/detect/detection_eval.h"
#include "lumaslam/detect/letterbox.h"
#include "lumaslam/detect/yolo_detector.h"
#include "lumaslam/detect/yolo_output.h"
#include "test_paths.h"

namespace lumaslam::detect {
namespace {

using test::dataDir;
using test::errorOf;
using test::modelsDir;

DetectorParams yoloParams(const std::string& model_file) {
  DetectorParams params;
  params.model = modelsDir() / model_file;
  return params;
}

TEST(Letterbox, KeepsAspectPadsWith114AndMapsBack) {
  const cv::Mat image(1080, 810, CV_8UC3, cv::Scalar(10, 20, 30));
  const Letterboxed boxed = letterbox(image, 640);
  ASSERT_EQ(boxed.image.size(), cv::Size(640, 640));
  const double scale = 640.0 / 1080.0;
  EXPECT_NEAR(boxed.transform.scale, scale, 1e-9);
  EXPECT_EQ(boxed.transform.pad_top, 0);
  EXPECT_EQ(boxed.transform.pad_left, 80);  // (640 - 480) / 2
  EXPECT_EQ(boxed.image.at<cv::Vec3b>(320, 10), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(boxed.image.at<cv::Vec3b>(320, 630), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(boxed.image.at<cv::Vec3b>(320, 320), cv::Vec3b(10, 20, 30));

  // A box drawn in image pixels, moved into input pixels, comes back where it was.
  const cv::Rect2f box(100, 200, 300, 400);
  const float cx = static_cast<float>((box.x + box.width / 2) * scale + 80);
  const float cy = static_cast<float>((box.y + box.height / 2) * scale);
  const cv::Rect2f back = boxed.transform.toImage(cx, cy, static_cast<float>(box.width * scale),
                                                  static_cast<float>(box.height * scale));
  EXPECT_NEAR(back.x, box.x, 0.01);
  EXPECT_NEAR(back.y, box.y, 0.01);
  EXPECT_NEAR(back.width, box.width, 0.01);
  EXPECT_NEAR(back.height, box.height, 0.01);

  // Boxes reaching past the image are clipped to it.
  const cv::Rect2f outside = boxed.transform.toImage(70, 600, 100, 200);
  EXPECT_GE(outside.x, 0.0f);
  EXPECT_LE(outside.y + outside.height, 1080.0f);
}

// One output row: cx, cy, w, h, objectness, class scores.
std::vector<float> row(float cx, float cy, float w, float h, float objectness,
                       std::vector<float> classes) {
  std::vector<float> r{cx, cy, w, h, objectness};
  r.insert(r.end(), classes.begin(), classes.end());
  return r;
}

cv::Mat tensor(const std::vector<std::vector<float>>& rows) {
  const int sizes[] = {1, static_cast<int>(rows.size()), static_cast<int>(rows.front().size())};
  cv::Mat out(3, sizes, CV_32F);
  float* data = out.ptr<float>();
  for (const auto& r : rows) data = std::copy(r.begin(), r.end(), data);
  return out;
}

TEST(YoloOutput, ConfidenceClassFilterClassWiseNmsAndMapping) {
  const std::vector<std::string> names{"person", "car", "dog"};
  LetterboxTransform transform;
  transform.scale = 0.5;
  transform.pad_left = 0;
  transform.pad_top = 20;
  transform.image_size = cv::Size(1000, 1000);
  const cv::Mat output = tensor({
      row(100, 120, 40, 80, 0.9f, {0.9f, 0.1f, 0.0f}),  // person, conf 0.81
      row(102, 121, 40, 80, 0.8f, {0.9f, 0.1f, 0.0f}),  // same person, lower: suppressed
      row(101, 120, 40, 80, 0.9f, {0.1f, 0.8f, 0.0f}),  // a car on it: other class, kept
      row(300, 300, 20, 20, 0.2f, {1.0f, 0.0f, 0.0f}),  // objectness too low
      row(400, 300, 20, 20, 0.9f, {0.2f, 0.0f, 0.0f}),  // person score 0.18: too low
  });
  YoloDecodeParams params;
  const auto all = decodeYoloOutput(output, transform, names, params);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].class_name, "person");
  EXPECT_NEAR(all[0].score, 0.81f, 1e-5);
  EXPECT_EQ(all[1].class_name, "car");
  EXPECT_EQ(all[1].class_id, 1);
  // (cx - w/2 - pad) / scale: x = (100 - 20) / 0.5, y = (120 - 40 - 20) / 0.5.
  EXPECT_NEAR(all[0].box.x, 160.0f, 1e-4);
  EXPECT_NEAR(all[0].box.y, 120.0f, 1e-4);
  EXPECT_NEAR(all[0].box.width, 80.0f, 1e-4);
  EXPECT_NEAR(all[0].box.height, 160.0f, 1e-4);

  params.class_ids = {0};
  const auto people = decodeYoloOutput(output, transform, names, params);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].class_name, "person");

  params.nms_threshold = 0.99f;  // nothing overlaps that much: both persons survive
  EXPECT_EQ(decodeYoloOutput(output, transform, names, params).size(), 2u);
}

TEST(YoloOutput, RejectsRowsThatDoNotMatchTheNames) {
  const cv::Mat output = tensor({row(1, 1, 1, 1, 1, {1, 0, 0})});
  EXPECT_THROW(decodeYoloOutput(output, {}, {"person", "car"}, {}), Error);
}

double daylightRecall(YoloDetector& detector, int& false_positives) {
  MatchCounts total;
  for (const auto& [image, boxes] : readBoxList(dataDir() / "labels" / "person_boxes.txt")) {
    std::vector<cv::Rect2f> people;
    for (const auto& b : boxes) {
      if (b.class_name == "person") people.push_back(b.box);
    }
    const cv::Mat bgr = cv::imread((dataDir() / image).string());
    EXPECT_FALSE(bgr.empty()) << image;
    const auto detections = detector.detect(bgr, 0.0);
    for (const auto& d : detections) {
      EXPECT_EQ(d.class_name, "person") << image;
      EXPECT_GE(d.box.x, 0.0f);
      EXPECT_GE(d.box.y, 0.0f);
      EXPECT_LE(d.box.br().x, static_cast<float>(bgr.cols));
      EXPECT_LE(d.box.br().y, static_cast<float>(bgr.rows));
    }
    total += matchDetections(people, detections, 0.5f);
  }
  false_positives = total.false_positives;
  EXPECT_EQ(total.true_positives + total.false_negatives, 6);  // 4 in bus.jpg, 2 in zidane.jpg
  return total.recall();
}

TEST(YoloDetector, FindsTheLabelledPeopleInDaylight640) {
  YoloDetector detector(yoloParams("yolov5n.onnx"));
  EXPECT_EQ(detector.inputSize(), 640);  // read from the model
  EXPECT_EQ(detector.classNames().size(), 80u);
  int false_positives = 0;
  const double recall = daylightRecall(detector, false_positives);
  RecordProperty("recall_640", std::to_string(recall));
  EXPECT_GE(recall, 0.9);
  EXPECT_LE(false_positives, 1);
}

TEST(YoloDetector, ReadsTheInputSizeOf320Model) {
  YoloDetector detector(yoloParams("yolov5n-320.onnx"));
  EXPECT_EQ(detector.inputSize(), 320);
  const cv::Mat bus = cv::imread((dataDir() / "ultralytics_yolov5/data/images/bus.jpg").string());
  const auto detections = detector.detect(bus, 0.0);
  EXPECT_GE(detections.size(), 3u);  // the 320 model finds at least the 3 big people
}

TEST(YoloDetector, KeepsOnlyConfiguredClassesAndAcceptsGray) {
  auto params = yoloParams("yolov5n-320.onnx");
  params.classes = {"bus"};
  YoloDetector detector(params);
  const cv::Mat bus = cv::imread((dataDir() / "ultralytics_yolov5/data/images/bus.jpg").string(),
                                 cv::IMREAD_GRAYSCALE);
  const auto detections = detector.detect(bus, 0.0);
  ASSERT_FALSE(detections.empty());
  for (const auto& d : detections) EXPECT_EQ(d.class_name, "bus");
}

TEST(YoloDetector, MissingOrGarbageModelIsAClearError) {
  test::TempDir dir("detect_models");
  auto params = yoloParams("yolov5n.onnx");
  params.model = dir.path() / "absent.onnx";
  // A missing model is an error.
  const std::string missing = errorOf([&] { YoloDetector detector(params); });
  EXPECT_NE(missing.find("absent.onnx"), std::string::npos) << missing;
  EXPECT_NE(missing.find("not found"), std::string::npos) << missing;

  params.model = dir.path() / "x.onnx";
  {
    std::ofstream garbage(params.model, std::ios::binary);
    for (int i = 0; i < 4096; ++i) garbage.put(static_cast<char>((i * 7919) % 251));
  }
  // A garbage model is an error.
  const std::string garbled = errorOf([&] { YoloDetector detector(params); });
  EXPECT_NE(garbled.find("x.onnx"), std::string::npos) << garbled;
}

TEST(YoloDetector, NamesThatDoNotFitTheModelAreAClearError) {
  test::TempDir dir("detect_names");
  auto params = yoloParams("yolov5n-320.onnx");
  params.names = dir.path() / "three.names";
  std::ofstream(params.names) << "person\ncar\ndog\n";
  EXPECT_THROW(YoloDetector detector(params), Error);

  params.names = modelsDir() / "coco80.names";
  params.classes = {"unicorn"};
  // An unknown class is an error.
  const std::string message = errorOf([&] { YoloDetector detector(params); });
  EXPECT_NE(message.find("unicorn"), std::string::npos) << message;
}

}  // namespace
}  // namespace lumaslam::detect
