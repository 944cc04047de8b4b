#pragma once
// The mask a run extracted a frame's ORB features outside of (Pipeline::extractionMask): the
// previous frame's dynamic mask, made again for `lumaslam report` from that frame's boxes in
// moving_features.txt and, for RGB-D, its depth, as Pipeline::removeDynamicFeatures made it.
#include <opencv2/core.hpp>

#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/settings.h"
#include "moving_features_file.h"

namespace lumaslam::cli {

// CV_8U, nonzero where no feature was taken, in pixels of `image_size` (the image the report
// extracts from; the marks are stretched to it should the sizes differ); empty when the
// previous frame had no box. `marks_image`: the size of the marks' pixels.
cv::Mat previousDynamicMask(const FrameMarks& previous, const io::FrameData& previous_frame,
                            const io::Settings& settings, cv::Size marks_image,
                            cv::Size image_size);

}  // namespace lumaslam::cli
