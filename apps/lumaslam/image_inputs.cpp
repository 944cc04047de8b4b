#include "image_inputs.h"

#include <algorithm>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/image_files.h"

namespace lumaslam::cli {

void forEachInputImage(const std::string& input, int max_frames, int stride,
                       const std::function<void(const std::string&, const cv::Mat&)>& visit) {
  namespace fs = std::filesystem;
  const fs::path path(input);
  std::error_code ec;
  if (fs::is_regular_file(path, ec) && io::hasImageExtension(path)) {
    visit(path.stem().string(), io::readImageFile(path, cv::IMREAD_UNCHANGED));
    return;
  }
  const bool is_folder = fs::is_directory(path, ec);
  if (!is_folder && input.find(':') == std::string::npos) {
    fail("{}: no such image file or folder (or give a dataset spec KIND:PATH)", input);
  }
  const std::string spec = is_folder ? "folder:" + input : input;
  io::ReaderOptions reader_options;
  if (spec.rfind("folder:", 0) == 0) reader_options.image_read_flags = cv::IMREAD_UNCHANGED;
  auto reader = io::openDataset(spec, reader_options);
  int index = 0;
  int visited = 0;
  while (auto frame = reader->next()) {
    if (index++ % std::max(stride, 1) != 0) continue;
    if (max_frames > 0 && visited >= max_frames) break;
    ++visited;
    const std::string name = frame->image_path.empty() ? std::to_string(frame->index)
                                                       : frame->image_path.stem().string();
    visit(name, frame->image);
  }
}

}  // namespace lumaslam::cli
