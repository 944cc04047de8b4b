#pragma once
// Sample frames of a run for `lumaslam report`: the first, middle and last tracked frame read
// again from the run's dataset, raw and enhanced as the pipeline enhances them, with the ORB
// keypoints tracking would extract, downscaled and encoded for an inline <img>.
#include <cstddef>
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
  std::string raw_uri;       // data:image/jpeg;base64,...
  std::string enhanced_uri;  // the image ORB sees, with its keypoints drawn
  std::size_t keypoints = 0;
};

struct SampleFrames {
  std::vector<SampleFrame> frames;
  std::string enhancement;  // the preset used, e.g. "best" or "off"
  std::string problem;      // why there are no (or fewer) frames, e.g. the dataset is gone
};

// Never throws for a dataset or settings file that cannot be read: says so in `problem`.
SampleFrames loadSampleFrames(const nlohmann::json& summary, const TimingTable& timing);

// "data:image/jpeg;base64,..." of `image` (8-bit gray or BGR) scaled down to at most
// `max_width` pixels wide; throws Error when it cannot be encoded.
std::string jpegDataUri(const cv::Mat& image, int max_width = 480);

}  // namespace lumaslam::cli
