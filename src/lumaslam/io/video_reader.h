#pragma once
// A video file through cv::VideoCapture; timestamps from the container (CAP_PROP_POS_MSEC),
// or index / fps when ReaderOptions::fps is set or the container's times do not increase.
#include <filesystem>

#include <opencv2/videoio.hpp>

#include "lumaslam/io/dataset_reader.h"

namespace lumaslam::io {

class VideoReader final : public DatasetReader {
 public:
  VideoReader(std::filesystem::path file, ReaderOptions options);

  std::optional<FrameData> next() override;
  std::size_t size() const override { return size_; }
  std::string name() const override { return "video:" + file_.string(); }

 private:
  std::filesystem::path file_;
  ReaderOptions options_;
  cv::VideoCapture capture_;
  double fps_ = 0.0;  // the container's rate, 0 if unknown
  std::size_t size_ = 0;
  std::size_t next_index_ = 0;
  std::size_t delivered_ = 0;
  double last_timestamp_ = -1.0;
};

}  // namespace lumaslam::io
