#pragma once
// Sample frames of a run for `lumaslam report`: the first, middle and last tracked frame read
// again from the run's dataset and taken as tracking takes them (resized, rectified:
// report_tracked_image.h), raw and enhanced as the pipeline enhances them, with the ORB
// keypoints tracking would extract (outside the previous frame's boxes, as the run did) and,
// from the run's moving_features.txt, the detection boxes and the features the run dropped,
// downscaled and encoded for an inline <img>.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "run_folder.h"

namespace lumaslam::cli {

struct SampleFrame {
  std::string role;  // "first tracked", ...
  std::size_t index = 0;
  double timestamp = 0.0;
  std::string raw_uri;        // data:image/jpeg;base64,...
  std::string enhanced_uri;   // the image ORB sees, with its keypoints drawn
  std::size_t keypoints = 0;  // extracted again here
  std::size_t green = 0;      // of those, drawn green (not at a feature the run dropped)
  // The run's counts from moving_features.txt (nullopt: the file does not have this frame).
  struct Marked {
    std::size_t kept = 0, by_boxes = 0, by_motion_test = 0, boxes = 0;
  };
  std::optional<Marked> marked;
};

struct SampleFrames {
  std::vector<SampleFrame> frames;
  std::string enhancement;  // the preset used, e.g. "best" or "off"
  std::string geometry;     // what was done to the images as read, e.g. "rectified"; or empty
  std::string problem;      // why there are no (or fewer) frames, e.g. the dataset is gone
  // Why no feature is marked: the run folder has no moving_features.txt (an older run), or
  // the file is broken (`marks_broken`, the error); empty when the marks were read.
  std::string unmarked;
  bool marks_broken = false;
};

// Never throws for a dataset, settings or moving_features.txt file that cannot be read: says
// so in `problem` or `unmarked`.
SampleFrames loadSampleFrames(const std::filesystem::path& run_dir, const nlohmann::json& summary,
                              const TimingTable& timing);

// "data:image/jpeg;base64,..." of `image` (8-bit gray or BGR) scaled down to at most
// `max_width` pixels wide; throws Error when it cannot be encoded.
std::string jpegDataUri(const cv::Mat& image, int max_width = 480);

}  // namespace lumaslam::cli
