#include "lumaslam/io/folder_reader.h"

#include <algorithm>

#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/image_files.h"
#include "lumaslam/io/text_lines.h"

namespace lumaslam::io {

namespace {
std::vector<std::filesystem::path> imagesInFolder(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> images;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file() && hasImageExtension(entry.path())) images.push_back(entry.path());
  std::sort(images.begin(), images.end());
  return images;
}
}  // namespace

FolderReader::FolderReader(std::filesystem::path folder, ReaderOptions options)
    : ListedFramesReader(std::move(options)), folder_(std::move(folder)) {
  if (!std::filesystem::is_directory(folder_)) fail("{}: image folder not found", folder_.string());
  const auto& times_file = this->options().timestamps;

  if (times_file.empty()) {
    const auto images = imagesInFolder(folder_);
    const double fps = this->options().fps.value_or(1.0);
    if (!(fps > 0.0)) fail("{}: fps must be positive, got {}", folder_.string(), fps);
    for (std::size_t i = 0; i < images.size(); ++i)
      entries_.push_back({static_cast<double>(i) / fps, images[i]});
  } else {
    // Either "timestamp filename" lines (they define the list) or one timestamp per line for
    // the folder's images in name order.
    const auto lines = readDataLines(times_file);
    const auto images = imagesInFolder(folder_);
    const bool one_per_image =
        !lines.empty() && splitFields(lines.front().text, " \t,").size() == 1;
    if (one_per_image && lines.size() != images.size())
      fail("{}: {} timestamps for {} images in {}", times_file.string(), lines.size(),
           images.size(), folder_.string());
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const auto fields = splitFields(lines[i].text, " \t,");
      const double t = fields.empty() ? 0.0 : parseNumber(fields[0], times_file, lines[i]);
      if (fields.size() == 2) {
        entries_.push_back({t, folder_ / std::string(fields[1])});
      } else if (fields.size() == 1 && one_per_image) {
        entries_.push_back({t, images[i]});
      } else {
        fail("{}:{}: expected 'timestamp' or 'timestamp filename', got '{}'", times_file.string(),
             lines[i].number, lines[i].text);
      }
      if (i > 0 && !(t > entries_[i - 1].timestamp))
        fail("{}:{}: timestamp {} does not increase", times_file.string(), lines[i].number, t);
    }
  }
  setFrameCount(entries_.size(), folder_.string() + " (no image files found)");
}

FrameData FolderReader::loadFrame(std::size_t index) const {
  FrameData frame;
  frame.index = index;
  frame.timestamp = entries_[index].timestamp;
  frame.image_path = entries_[index].file;
  frame.image = readImageFile(frame.image_path, imageReadFlags(cv::IMREAD_COLOR));
  return frame;
}

}  // namespace lumaslam::io
