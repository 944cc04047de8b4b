// `lumaslam detect`: run the dynamic-object detector on an image, a folder of images or a
// video (through the asynchronous DetectionWorker, with its stride), print the boxes, write
// annotated images; or, with --evaluate, measure recall/precision against labelled boxes:
// single images (box list, VOC folder) or a TUM-layout sequence with its detections.txt,
// detected every stride-th frame and propagated in between as the SLAM pipeline does.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "cli_checks.h"
#include "command_registry.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/detect/box_file_detector.h"
#include "lumaslam/detect/box_labels.h"
#include "lumaslam/detect/detection_eval.h"
#include "lumaslam/detect/detection_worker.h"
#include "lumaslam/detect/detector_factory.h"
#include "lumaslam/detect/dynamic_mask.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/io/dataset_reader.h"

namespace {

using namespace lumaslam;
namespace fs = std::filesystem;

struct DetectOptions {
  std::string input;
  std::string settings;
  std::string model;
  std::string names;
  std::string classes;
  std::optional<float> confidence;
  std::optional<int> threads;
  std::optional<int> stride;
  std::string output_dir;
  std::string evaluate;
  std::vector<std::string> image_dirs;
  float min_iou = 0.5f;
  std::string enhance_preset;
  int max_frames = 0;
  bool draw_features = false;
};

detect::DetectorParams paramsFrom(const DetectOptions& options) {
  detect::DetectorParams params;
  if (!options.settings.empty()) {
    params = detect::DetectorParams::fromSettings(core::SettingsFile::open(options.settings));
  }
  if (!options.model.empty()) params.model = options.model;
  if (!options.names.empty()) params.names = options.names;
  if (!options.classes.empty()) params.classes = detect::splitClassList(options.classes);
  if (options.confidence) params.confidence_threshold = *options.confidence;
  if (options.threads) params.threads = *options.threads;
  if (options.stride) params.stride = *options.stride;
  if (params.type == "yolo" && params.model.empty())
    fail("detect: give --model or --settings with Detector.model");
  return params;
}

// The image the detector sees: the input, or its enhanced colour version.
class Preprocessor {
 public:
  explicit Preprocessor(const std::string& preset) {
    if (!preset.empty()) enhancer_.emplace(enhance::EnhancerParams::forPreset(preset));
  }
  cv::Mat operator()(const cv::Mat& image) {
    return enhancer_ ? enhancer_->enhance(image).colour : image;
  }

 private:
  std::optional<enhance::Enhancer> enhancer_;
};

cv::Mat readImage(const fs::path& path) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (image.empty()) fail("{}: cannot read image", path.string());
  return image;
}

bool isImageFile(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".bmp" || ext == ".tif" ||
         ext == ".tiff";
}

void printDetections(const std::string& frame, const detect::Detections& detections) {
  for (const auto& d : detections) {
    std::printf("%s %s %.3f %.1f %.1f %.1f %.1f\n", frame.c_str(), d.class_name.c_str(), d.score,
                d.box.x, d.box.y, d.box.width, d.box.height);
  }
}

void drawDetections(cv::Mat& image, const detect::Detections& detections,
                    const cv::Scalar& colour) {
  for (const auto& d : detections) {
    cv::rectangle(image, cv::Rect(d.box), colour, 2);
    cv::putText(image, fmt::format("{} {:.2f}", d.class_name, d.score),
                cv::Point(d.box.tl()) + cv::Point(2, 14), cv::FONT_HERSHEY_SIMPLEX, 0.5, colour, 1);
  }
}

// What dynamic-object removal does to a frame: ORB features (1000, as tracking) kept in green,
// the ones the dynamic mask (boxes grown by the margin) drops in red.
void drawFeatures(cv::Mat& image, const cv::Mat& source, const detect::Detections& detections,
                  int margin_px) {
  cv::Mat gray = source;
  if (source.channels() == 3) cv::cvtColor(source, gray, cv::COLOR_BGR2GRAY);
  const auto keypoints = feature::OrbExtractor(feature::OrbSettings{}).extract(gray).keypoints;
  const cv::Mat mask = detect::makeDynamicMask(gray.size(), detect::boxesOf(detections), margin_px);
  const auto kept = detect::filterKeypoints(keypoints, mask);
  std::vector<bool> is_kept(keypoints.size(), false);
  for (const int i : kept) is_kept[static_cast<std::size_t>(i)] = true;
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    cv::circle(image, keypoints[i].pt, 3,
               is_kept[i] ? cv::Scalar(0, 220, 0) : cv::Scalar(0, 0, 255), is_kept[i] ? 1 : -1);
  }
  cv::putText(
      image,
      fmt::format("{} features, {} dropped", keypoints.size(), keypoints.size() - kept.size()),
      {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.6, {255, 255, 255}, 2);
}

void writeAnnotated(const fs::path& dir, const std::string& name, cv::Mat image,
                    const detect::Detections& detections) {
  drawDetections(image, detections, {0, 255, 0});
  const fs::path path = dir / name;
  if (!cv::imwrite(path.string(), image)) fail("{}: cannot write annotated image", path.string());
}

int runOnImages(const DetectOptions& options, const std::vector<fs::path>& images) {
  const auto params = paramsFrom(options);
  const int margin_px = params.mask.margin_px;
  auto detector = detect::makeDetector(params);
  Preprocessor preprocess(options.enhance_preset);
  for (std::size_t i = 0; i < images.size(); ++i) {
    const cv::Mat image = preprocess(readImage(images[i]));
    const auto detections = detector->detect(image, static_cast<double>(i));
    printDetections(images[i].filename().string(), detections);
    if (!options.output_dir.empty()) {
      cv::Mat annotated = image.clone();
      if (options.draw_features) drawFeatures(annotated, image, detections, margin_px);
      writeAnnotated(options.output_dir, images[i].filename().string(), annotated, detections);
    }
  }
  return 0;
}

int runOnVideo(const DetectOptions& options) {
  const auto params = paramsFrom(options);
  cv::VideoCapture capture(options.input);
  if (!capture.isOpened()) fail("{}: cannot open video", options.input);
  const double fps = capture.get(cv::CAP_PROP_FPS) > 0 ? capture.get(cv::CAP_PROP_FPS) : 30.0;
  detect::DetectionWorker worker(detect::makeDetector(params), detect::WorkerParams::from(params));
  Preprocessor preprocess(options.enhance_preset);

  std::int64_t index = 0;
  double detect_ms = 0.0;
  int detected_frames = 0;
  cv::Mat frame;
  while ((options.max_frames <= 0 || index < options.max_frames) && capture.read(frame) &&
         !frame.empty()) {
    const cv::Mat image = preprocess(frame);
    worker.push(index, static_cast<double>(index) / fps, image);
    const auto result = worker.take(index);
    if (!result.propagated) {
      detect_ms += result.compute_ms;
      ++detected_frames;
    }
    printDetections(fmt::format("{:06d}", index), result.detections);
    if (!options.output_dir.empty()) {
      cv::Mat annotated = image.clone();
      if (options.draw_features)
        drawFeatures(annotated, image, result.detections, params.mask.margin_px);
      drawDetections(annotated, result.detections,
                     result.propagated ? cv::Scalar(0, 200, 255) : cv::Scalar(0, 255, 0));
      // PNG with features: the dots must stay sharp.
      writeAnnotated(options.output_dir,
                     fmt::format("{:06d}.{}", index, options.draw_features ? "png" : "jpg"),
                     annotated, {});
    }
    ++index;
  }
  if (index == 0) fail("{}: no frame could be decoded", options.input);
  spdlog::info("detect: {} frames, {} detected (stride {}), {:.1f} ms per inference", index,
               detected_frames, params.stride,
               detected_frames > 0 ? detect_ms / detected_frames : 0.0);
  return 0;
}

// Labelled images: (image path, truth boxes of the wanted classes).
std::vector<std::pair<fs::path, std::vector<cv::Rect2f>>> labelledImages(
    const DetectOptions& options, const std::vector<std::string>& classes) {
  const auto wanted = [&](const detect::LabeledBox& b) {
    return std::find(classes.begin(), classes.end(), b.class_name) != classes.end();
  };
  std::vector<std::pair<fs::path, std::vector<cv::Rect2f>>> images;
  const fs::path labels = options.evaluate;
  if (fs::is_directory(labels)) {  // Pascal VOC annotations, images looked up in --images
    if (options.image_dirs.empty()) fail("{}: VOC annotations need --images DIR", labels.string());
    std::vector<fs::path> xml_files;
    for (const auto& entry : fs::directory_iterator(labels)) {
      if (entry.path().extension() == ".xml") xml_files.push_back(entry.path());
    }
    std::sort(xml_files.begin(), xml_files.end());
    if (xml_files.empty()) fail("{}: no .xml annotation in the folder", labels.string());
    for (const auto& xml : xml_files) {
      const auto annotation = detect::readVocAnnotation(xml);
      std::optional<fs::path> image;
      for (const auto& dir : options.image_dirs) {
        if (fs::exists(fs::path(dir) / annotation.filename))
          image = fs::path(dir) / annotation.filename;
      }
      if (!image)
        fail("{}: image {} is in none of the --images folders", xml.string(), annotation.filename);
      std::vector<cv::Rect2f> truth;
      for (const auto& b : annotation.boxes) {
        if (wanted(b)) truth.push_back(b.box);
      }
      images.emplace_back(*image, truth);
    }
    return images;
  }
  // Box list; image paths are relative to --images (default: the folder above the list's).
  const fs::path root = options.image_dirs.empty() ? labels.parent_path().parent_path()
                                                   : fs::path(options.image_dirs[0]);
  for (const auto& [image, boxes] : detect::readBoxList(labels)) {
    std::vector<cv::Rect2f> truth;
    for (const auto& b : boxes) {
      if (wanted(b)) truth.push_back(b.box);
    }
    images.emplace_back(root / image, truth);
  }
  return images;
}

int runEvaluation(const DetectOptions& options) {
  const auto params = paramsFrom(options);
  auto detector = detect::makeDetector(params);
  Preprocessor preprocess(options.enhance_preset);
  detect::MatchCounts total;
  const auto images = labelledImages(options, params.classes);
  for (std::size_t i = 0; i < images.size(); ++i) {
    const auto& [path, truth] = images[i];
    const cv::Mat image = preprocess(readImage(path));
    const auto detections = detector->detect(image, static_cast<double>(i));
    const auto counts = detect::matchDetections(truth, detections, options.min_iou);
    total += counts;
    std::printf("%s truth %zu detected %zu tp %d fp %d fn %d\n", path.filename().string().c_str(),
                truth.size(), detections.size(), counts.true_positives, counts.false_positives,
                counts.false_negatives);
    if (!options.output_dir.empty()) {
      cv::Mat annotated = image.clone();
      for (const auto& box : truth) cv::rectangle(annotated, cv::Rect(box), {255, 0, 0}, 2);
      writeAnnotated(options.output_dir, path.filename().string(), annotated, detections);
    }
  }
  std::printf("recall %.3f precision %.3f (tp %d fp %d fn %d, IoU >= %.2f)\n", total.recall(),
              total.precision(), total.true_positives, total.false_positives, total.false_negatives,
              options.min_iou);
  return 0;
}

// A TUM-layout sequence folder for INPUT "tum:D" or a folder D holding rgb.txt.
std::optional<fs::path> sequenceFolder(const std::string& input) {
  if (input.rfind("tum:", 0) == 0) return fs::path(input.substr(4));
  if (!input.empty() && fs::is_directory(input) && fs::exists(fs::path(input) / "rgb.txt"))
    return fs::path(input);
  return std::nullopt;
}

// The truth boxes per frame timestamp: a detections.txt ("timestamp class x y w h"), read by
// the box-file detector (same parser and errors as `run --detector boxes:FILE`).
detect::BoxFileDetector truthBoxes(const DetectOptions& options,
                                   const detect::DetectorParams& params) {
  if (fs::is_directory(options.evaluate))
    fail("{}: a sequence is evaluated against a box file (its detections.txt), not a folder",
         options.evaluate);
  detect::DetectorParams truth;
  truth.type = "box_file";
  truth.box_file = options.evaluate;
  truth.box_file_tolerance = 0.005;  // the generator writes the image's own timestamp
  truth.classes = params.classes;
  return detect::BoxFileDetector(truth);
}

struct SequenceTotals {
  detect::MatchCounts counts;
  int frames = 0, detected_frames = 0, truth_boxes = 0;
  double all_ms = 0.0, detect_ms = 0.0;
};

void addFrame(SequenceTotals& totals, const detect::FrameDetections& result,
              const detect::MatchCounts& counts, std::size_t truth_boxes) {
  totals.counts += counts;
  ++totals.frames;
  totals.truth_boxes += static_cast<int>(truth_boxes);
  totals.all_ms += result.compute_ms;
  if (!result.propagated) {
    ++totals.detected_frames;
    totals.detect_ms += result.compute_ms;
  }
}

void printSequenceSummary(const SequenceTotals& t, const DetectOptions& options, int stride) {
  std::printf("recall %.3f precision %.3f (tp %d fp %d fn %d, IoU >= %.2f)\n", t.counts.recall(),
              t.counts.precision(), t.counts.true_positives, t.counts.false_positives,
              t.counts.false_negatives, options.min_iou);
  std::printf(
      "detector %.1f ms per frame (%d frames, propagation included), %.1f ms per detected frame "
      "(%d frames, stride %d)\n",
      t.all_ms / std::max(t.frames, 1), t.frames, t.detect_ms / std::max(t.detected_frames, 1),
      t.detected_frames, stride);
}

// The worker as the pipeline runs it with System.sequential: no thread, Detector.stride.
detect::DetectionWorker sequentialWorker(const detect::DetectorParams& params) {
  auto worker_params = detect::WorkerParams::from(params);
  worker_params.threaded = false;
  return detect::DetectionWorker(detect::makeDetector(params), worker_params);
}

// One frame's line "NAME truth T detected D tp fp fn [propagated]" and annotated image.
void reportFrame(const DetectOptions& options, const std::string& name, const cv::Mat& image,
                 const std::vector<cv::Rect2f>& truth, const detect::FrameDetections& result,
                 const detect::MatchCounts& counts) {
  std::printf("%s truth %zu detected %zu tp %d fp %d fn %d%s\n", name.c_str(), truth.size(),
              result.detections.size(), counts.true_positives, counts.false_positives,
              counts.false_negatives, result.propagated ? " propagated" : "");
  if (options.output_dir.empty()) return;
  cv::Mat annotated = image.clone();
  for (const auto& box : truth) cv::rectangle(annotated, cv::Rect(box), {255, 0, 0}, 2);
  writeAnnotated(options.output_dir, name + ".jpg", annotated, result.detections);
}

// Recall/precision on a sequence: frames in rgb.txt order through the DetectionWorker in
// sequential mode (detect every stride-th frame, propagate between), against the truth boxes.
int runSequenceEvaluation(const DetectOptions& options, const fs::path& folder) {
  const auto params = paramsFrom(options);
  auto truth_file = truthBoxes(options, params);
  io::ReaderOptions reader_options;
  if (options.max_frames > 0) reader_options.max_frames = options.max_frames;
  auto reader = io::openDataset("tum-mono:" + folder.string(), reader_options);
  auto worker = sequentialWorker(params);
  Preprocessor preprocess(options.enhance_preset);
  SequenceTotals totals;
  while (auto frame = reader->next()) {
    const cv::Mat image = preprocess(frame->image);
    const auto index = static_cast<std::int64_t>(frame->index);
    worker.push(index, frame->timestamp, image);
    const auto result = worker.take(index);
    const auto truth = detect::boxesOf(truth_file.detect(image, frame->timestamp));
    const auto counts = detect::matchDetections(truth, result.detections, options.min_iou);
    addFrame(totals, result, counts, truth.size());
    reportFrame(options, frame->image_path.stem().string(), image, truth, result, counts);
  }
  if (totals.truth_boxes == 0)
    fail("{}: no {} box on any frame of {}", options.evaluate, fmt::join(params.classes, "/"),
         folder.string());
  printSequenceSummary(totals, options, params.stride);
  return 0;
}

int runDetect(const DetectOptions& options) {
  if (!options.output_dir.empty()) fs::create_directories(options.output_dir);
  if (!options.evaluate.empty()) {
    if (const auto folder = sequenceFolder(options.input))
      return runSequenceEvaluation(options, *folder);
    return runEvaluation(options);
  }
  if (options.input.empty())
    fail("detect: give an INPUT (image, folder or video) or --evaluate LABELS");
  const fs::path input = options.input;
  if (fs::is_directory(input)) {
    std::vector<fs::path> images;
    for (const auto& entry : fs::directory_iterator(input)) {
      if (entry.is_regular_file() && isImageFile(entry.path())) images.push_back(entry.path());
    }
    std::sort(images.begin(), images.end());
    if (images.empty()) fail("{}: folder holds no image", input.string());
    return runOnImages(options, images);
  }
  if (!fs::exists(input)) fail("{}: input not found", input.string());
  if (isImageFile(input)) return runOnImages(options, {input});
  return runOnVideo(options);
}

const bool registered = lumaslam::cli::registerCommand(
    "detect", "Detect dynamic objects (people) in images or a video; --evaluate against labels",
    [](CLI::App& cmd) -> lumaslam::cli::Runner {
      auto options = std::make_shared<DetectOptions>();
      cmd.add_option("INPUT", options->input,
                     "image, folder of images, or video; with --evaluate: a TUM-layout "
                     "sequence (folder with rgb.txt, or tum:PATH)");
      cmd.add_option("--settings", options->settings, "settings file with Detector.* keys");
      cmd.add_option("--model", options->model, "YOLOv5 ONNX model (overrides Detector.model)");
      cmd.add_option("--names", options->names,
                     "class names, one per line (default: coco80.names by the model)");
      cmd.add_option("--classes", options->classes,
                     "comma-separated classes to keep (default: person)");
      cmd.add_option("--confidence", options->confidence,
                     "confidence threshold (objectness * class score)");
      cmd.add_option("--threads", options->threads, "OpenCV threads (cv::setNumThreads)");
      cmd.add_option("--stride", options->stride,
                     "video, sequence: detect every k-th frame, propagate between");
      cmd.add_option("--max-frames", options->max_frames,
                     "video, sequence: stop after this many frames")
          ->check(lumaslam::cli::wholeNumber(0, 1'000'000'000));
      cmd.add_option("--output", options->output_dir, "write annotated images into this folder");
      cmd.add_option("--evaluate", options->evaluate,
                     "box-list file or folder of VOC .xml: print recall/precision; for a "
                     "sequence INPUT its detections.txt (timestamp class x y w h)");
      cmd.add_option("--images", options->image_dirs,
                     "--evaluate: image folder(s) (box list: root of its paths)");
      cmd.add_option("--iou", options->min_iou, "--evaluate: IoU for a hit")
          ->check(CLI::Range(0.0, 1.0));
      cmd.add_option("--enhance", options->enhance_preset,
                     "enhance every image with this preset first");
      cmd.add_flag("--draw-features", options->draw_features,
                   "--output: also draw the ORB features, kept (green) and dropped by the "
                   "dynamic mask (red); video frames are then written as PNG");
      return [options] { return runDetect(*options); };
    });

}  // namespace
