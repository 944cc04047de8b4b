#pragma once
// Images for CLI commands that take "an image, a folder or a dataset": an image file, each
// image of a folder, or each frame of a dataset spec ("euroc:PATH", "tum:PATH", ... see
// io/dataset_reader.h).
#include <functional>
#include <string>

#include <opencv2/core.hpp>

namespace lumaslam::cli {

// Calls visit(name, image) for every `stride`-th frame, at most `max_frames` (0: all). Images
// from files and folders are read unchanged (colour, alpha, 16-bit kept). Throws Error for a
// path that is neither an image, a folder nor a dataset spec.
void forEachInputImage(const std::string& input, int max_frames, int stride,
                       const std::function<void(const std::string&, const cv::Mat&)>& visit);

}  // namespace lumaslam::cli
