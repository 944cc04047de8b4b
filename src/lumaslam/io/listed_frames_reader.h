#pragma once
// Base of the readers whose frames are a list of files known up front (TUM, EuRoC, KITTI,
// folder): applies first_frame/max_frames and the skip-unreadable-images policy; subclasses
// only load one frame by its index.
#include "lumaslam/io/dataset_reader.h"

namespace lumaslam::io {

class ListedFramesReader : public DatasetReader {
 public:
  std::optional<FrameData> next() final;
  std::size_t size() const final { return end_ - first_; }

 protected:
  explicit ListedFramesReader(ReaderOptions options) : options_(std::move(options)) {}
  // Call once from the subclass constructor with the length of the full frame list; throws
  // Error (naming `origin`) if no frame is left to deliver.
  void setFrameCount(std::size_t count, const std::string& origin);
  // Reads frame `index` of the full list; throws Error naming the file when it cannot.
  virtual FrameData loadFrame(std::size_t index) const = 0;
  const ReaderOptions& options() const { return options_; }
  int imageReadFlags(int natural_flags) const {
    return options_.image_read_flags.value_or(natural_flags);
  }

 private:
  ReaderOptions options_;
  std::size_t first_ = 0;
  std::size_t end_ = 0;
  std::size_t cursor_ = 0;
};

}  // namespace lumaslam::io
