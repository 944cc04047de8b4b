#pragma once
// Every `Detector.*` setting: which detector, its thresholds, the asynchronous worker's
// stride and queue, and the dynamic mask. Defaults suit YOLOv5n on people.
#include <filesystem>
#include <string>
#include <vector>

#include "lumaslam/core/settings_file.h"

namespace lumaslam::detect {

struct PropagationParams {
  int max_features = 30;         // good features tracked per box
  float inner_fraction = 0.6f;   // features come from this central part of each box
  int min_tracked = 3;           // fewer tracked features: the box stays where it was
  int min_scale_tracked = 6;     // fewer tracked features: the box keeps its size
  float max_scale_step = 1.25f;  // per frame a box grows/shrinks at most this much (1: never)
};

struct MaskParams {
  int margin_px = 8;                  // boxes grow by this much on every side
  double depth_tolerance_m = 0.4;     // pixels farther than person depth + this are static
  int depth_edge_px = 8;              // ... and at least this far from the person's pixels
  double depth_percentile = 0.25;     // person depth: this percentile of the central depths
  float depth_inner_fraction = 0.5f;  // person depth is read from this central part of the box
};

struct DetectorParams {
  std::string type = "yolo";    // Detector.type: yolo | box_file | none
  std::filesystem::path model;  // Detector.model (ONNX)
  std::filesystem::path names;  // Detector.names (default: coco80.names next to the model)
  int input_size = 0;           // Detector.inputSize: 0 = read from the model
  float confidence_threshold =
      0.15f;                    // Detector.confidence: objectness * class score (docs/dynamic.md)
  float nms_threshold = 0.45f;  // Detector.nms: IoU above which boxes are merged
  std::vector<std::string> classes{"person"};  // Detector.classes: comma-separated names
  int threads = 0;                             // Detector.threads: cv::setNumThreads, 0 = keep
  std::filesystem::path box_file;              // Detector.boxFile (type box_file)
  double box_file_tolerance = 0.02;            // Detector.boxFileTolerance [s]
  int stride = 1;                              // Detector.stride: detect every k-th frame
  int queue_capacity = 4;                      // Detector.queueCapacity: frames waiting
  PropagationParams propagation;               // Detector.propagationFeatures/InnerFraction
  MaskParams mask;                             // Detector.maskMargin, Detector.depth*
  // Detector.memoryFrames / memoryStrikes: tracking's memory of recent boxes; a map point
  // failing the chi-square test this many times near one is dynamic (0 frames = off).
  int memory_frames = 15;
  int memory_strikes = 2;
  // Detector.image: what the detector sees in a SLAM run, "raw" (the camera image) or
  // "enhanced" (the enhanced colour image); raw by default (measured, docs/dynamic.md).
  std::string image = "raw";

  // Reads every Detector.* key present; absent keys keep their defaults. Throws Error
  // naming the file and key for a wrong type or an out-of-range value, and (unless
  // require_source is false) for a yolo type without Detector.model / box_file type without
  // Detector.boxFile.
  static DetectorParams fromSettings(const core::SettingsFile& settings,
                                     bool require_source = true);

  // Every Detector.* key as settings lines that fromSettings reads back to these values.
  std::string settingsLines() const;

  // names, or coco80.names in the model's folder when names is empty.
  std::filesystem::path namesPath() const;
};

// "person, car" -> {"person", "car"}; empty items are dropped.
std::vector<std::string> splitClassList(const std::string& text);

}  // namespace lumaslam::detect
