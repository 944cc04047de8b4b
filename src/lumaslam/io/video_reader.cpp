#include "lumaslam/io/video_reader.h"

#include <spdlog/spdlog.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::io {

VideoReader::VideoReader(std::filesystem::path file, ReaderOptions options)
    : file_(std::move(file)), options_(std::move(options)) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file_, ec))
    fail("{}: video file not found", file_.string());
  if (options_.fps && !(*options_.fps > 0.0))
    fail("{}: fps must be positive, got {}", file_.string(), *options_.fps);
  if (!capture_.open(file_.string()) || !capture_.isOpened())
    fail("{}: cannot open video (unsupported or corrupt)", file_.string());
  fps_ = capture_.get(cv::CAP_PROP_FPS);
  const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
  const std::size_t frame_count = count > 0.0 ? static_cast<std::size_t>(count) : 0;
  if (frame_count > 0 && options_.first_frame >= frame_count)
    fail("{}: first frame {} is past the end of the {} frames", file_.string(),
         options_.first_frame, frame_count);
  // grab() rather than seeking: seeking is not frame-exact for every codec.
  for (; next_index_ < options_.first_frame; ++next_index_)
    if (!capture_.grab())
      fail("{}: video ends at frame {}, before first frame {}", file_.string(), next_index_,
           options_.first_frame);
  size_ = frame_count > options_.first_frame ? frame_count - options_.first_frame : 0;
  if (options_.max_frames) size_ = std::min(size_, *options_.max_frames);
}

std::optional<FrameData> VideoReader::next() {
  if (options_.max_frames && delivered_ >= *options_.max_frames) return std::nullopt;
  FrameData frame;
  if (!capture_.read(frame.image) || frame.image.empty()) {
    if (delivered_ == 0) fail("{}: empty video (no frame could be decoded)", file_.string());
    return std::nullopt;
  }
  frame.index = next_index_++;
  frame.image_path = file_;
  const double container_time = capture_.get(cv::CAP_PROP_POS_MSEC) * 1e-3;
  if (options_.fps) {
    frame.timestamp = static_cast<double>(frame.index) / *options_.fps;
  } else if (container_time > last_timestamp_) {
    frame.timestamp = container_time;
  } else {
    frame.timestamp = last_timestamp_ + (fps_ > 0.0 ? 1.0 / fps_ : 1.0);
  }
  last_timestamp_ = frame.timestamp;

  const int flags = options_.image_read_flags.value_or(cv::IMREAD_COLOR);
  if (flags == cv::IMREAD_GRAYSCALE && frame.image.channels() == 3)
    cv::cvtColor(frame.image, frame.image, cv::COLOR_BGR2GRAY);
  ++delivered_;
  return frame;
}

}  // namespace lumaslam::io
