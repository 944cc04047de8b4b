#pragma once
// A folder of images (png, jpg, bmp, tif, pgm/ppm, webp) in file-name order, timed by an
// optional timestamps file (ReaderOptions::timestamps) or by index / fps.
#include <filesystem>
#include <vector>

#include "lumaslam/io/listed_frames_reader.h"

namespace lumaslam::io {

class FolderReader final : public ListedFramesReader {
 public:
  FolderReader(std::filesystem::path folder, ReaderOptions options);

  std::string name() const override { return "folder:" + folder_.string(); }

 private:
  struct Entry {
    double timestamp;
    std::filesystem::path file;
  };
  FrameData loadFrame(std::size_t index) const override;

  std::filesystem::path folder_;
  std::vector<Entry> entries_;
};

}  // namespace lumaslam::io
