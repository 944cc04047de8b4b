#pragma once
// TUM RGB-D sequence folder: rgb.txt (+ depth.txt, associated one-to-one by nearest timestamp
// within max_association_dt), groundtruth.txt when present.
#include <filesystem>
#include <vector>

#include "lumaslam/io/listed_frames_reader.h"

namespace lumaslam::io {

class TumRgbdReader final : public ListedFramesReader {
 public:
  TumRgbdReader(std::filesystem::path root, bool with_depth, ReaderOptions options);

  std::string name() const override;
  bool hasDepth() const override { return with_depth_; }
  Trajectory groundTruth() const override;

  // Ground truth of a TUM folder (groundtruth.txt); throws Error if it has none.
  static Trajectory readGroundTruth(const std::filesystem::path& root);

 private:
  struct Entry {
    double timestamp;  // of the rgb image
    std::filesystem::path rgb;
    std::filesystem::path depth;  // empty without depth
  };
  FrameData loadFrame(std::size_t index) const override;

  std::filesystem::path root_;
  bool with_depth_;
  std::vector<Entry> entries_;
};

}  // namespace lumaslam::io
