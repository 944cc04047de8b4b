#include "lumaslam/io/listed_frames_reader.h"

#include <spdlog/spdlog.h>

#include "lumaslam/core/error.h"

namespace lumaslam::io {

void ListedFramesReader::setFrameCount(std::size_t count, const std::string& origin) {
  if (count == 0) fail("{}: empty sequence (no frames listed)", origin);
  if (options_.first_frame >= count)
    fail("{}: first frame {} is past the end of the {} frames", origin, options_.first_frame,
         count);
  first_ = options_.first_frame;
  end_ = count;
  if (options_.max_frames) end_ = std::min(end_, first_ + *options_.max_frames);
  if (end_ == first_) fail("{}: max_frames is 0, nothing to read", origin);
  cursor_ = first_;
}

std::optional<FrameData> ListedFramesReader::next() {
  while (cursor_ < end_) {
    const std::size_t index = cursor_++;
    try {
      return loadFrame(index);
    } catch (const Error& e) {
      if (!options_.skip_unreadable_images) throw;
      spdlog::warn("skipping frame {}: {}", index, e.what());
    }
  }
  return std::nullopt;
}

}  // namespace lumaslam::io
