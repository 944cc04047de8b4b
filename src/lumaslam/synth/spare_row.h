#pragma once
// SIMD loads of a 3-channel pixel read 4 values: the last pixel's load reaches one value past
// the image. withSpareRow() gives a copy followed by one zeroed row in memory, which makes
// such loads safe anywhere in the image.
#include <opencv2/core.hpp>

namespace lumaslam::synth {

inline cv::Mat withSpareRow(const cv::Mat& image) {
  cv::Mat storage(image.rows + 1, image.cols, image.type());
  storage.row(image.rows).setTo(cv::Scalar::all(0));
  cv::Mat view = storage.rowRange(0, image.rows);
  image.copyTo(view);
  return view;
}

}  // namespace lumaslam::synth
