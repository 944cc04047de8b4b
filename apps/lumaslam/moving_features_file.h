#pragma once
// moving_features.txt of a run folder (docs/results.md): for every frame tracked or lost, the
// detector's boxes and where the features were that the run dropped on them and that the
// motion test flagged moving, in pixels of the image tracking used. `lumaslam run` writes it,
// `lumaslam report` draws it on the sample frames.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/io/output_file.h"

namespace lumaslam::cli {

inline constexpr const char* kMovingFeaturesFile = "moving_features.txt";

struct FrameMarks {
  std::size_t frame = 0;
  std::size_t features = 0;          // extracted, before any was dropped
  std::vector<cv::Rect2f> boxes;     // the detector's (rounded to whole pixels in the file)
  std::vector<cv::Point2f> dropped;  // in a box: removed before tracking (timing.csv
                                     // dropped_features)
  std::vector<cv::Point2f> moving;   // flagged by the motion test (timing.csv moving_features)
};

struct MovingFeatures {
  cv::Size image;  // the size the positions are in (Camera.newWidth/newHeight when resized)
  std::map<std::size_t, FrameMarks> frames;
};

class MovingFeaturesWriter {
 public:
  // Writes the header; throws Error when the file cannot be opened.
  MovingFeaturesWriter(const std::filesystem::path& file, cv::Size image);
  // One line, flushed (a write failure is an Error naming the file).
  void add(const FrameMarks& marks);
  // Renames the file into place (io::OutputFile); throws Error on any write failure.
  void commit();

 private:
  io::OutputFile file_;
};

// nullopt when `file` does not exist (a run folder from before the file); throws Error naming
// the file and the line when it cannot be read or is malformed.
std::optional<MovingFeatures> readMovingFeatures(const std::filesystem::path& file);

}  // namespace lumaslam::cli
