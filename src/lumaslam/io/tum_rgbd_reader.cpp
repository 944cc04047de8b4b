#include "lumaslam/io/tum_rgbd_reader.h"

#include <spdlog/spdlog.h>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/image_files.h"
#include "lumaslam/io/text_lines.h"
#include "lumaslam/io/timestamp_association.h"
#include "lumaslam/io/trajectory_io.h"

namespace lumaslam::io {

namespace {
struct ListedImage {
  double timestamp;
  std::filesystem::path file;
};

// rgb.txt / depth.txt: "timestamp filename" per line, filenames relative to the folder.
std::vector<ListedImage> readImageList(const std::filesystem::path& list,
                                       const std::filesystem::path& root) {
  std::vector<ListedImage> images;
  for (const auto& line : readDataLines(list)) {
    const auto fields = splitFields(line.text, " \t");
    if (fields.size() != 2)
      fail("{}:{}: expected 'timestamp filename', got '{}'", list.string(), line.number, line.text);
    const double timestamp = parseNumber(fields[0], list, line);
    if (!images.empty() && !(timestamp > images.back().timestamp))
      fail("{}:{}: timestamp {} does not increase", list.string(), line.number, fields[0]);
    images.push_back({timestamp, root / std::string(fields[1])});
  }
  if (images.empty()) fail("{}: empty sequence (no images listed)", list.string());
  return images;
}

std::vector<double> timestampsOf(const std::vector<ListedImage>& images) {
  std::vector<double> times;
  times.reserve(images.size());
  for (const auto& image : images) times.push_back(image.timestamp);
  return times;
}
}  // namespace

TumRgbdReader::TumRgbdReader(std::filesystem::path root, bool with_depth, ReaderOptions options)
    : ListedFramesReader(std::move(options)), root_(std::move(root)), with_depth_(with_depth) {
  if (!(this->options().max_association_dt > 0.0))
    fail("{}: max association dt must be positive, got {}", root_.string(),
         this->options().max_association_dt);
  const auto rgb = readImageList(root_ / "rgb.txt", root_);
  if (!with_depth_) {
    for (const auto& image : rgb) entries_.push_back({image.timestamp, image.file, {}});
  } else {
    const auto depth = readImageList(root_ / "depth.txt", root_);
    const auto matches = associateTimestamps(timestampsOf(rgb), timestampsOf(depth),
                                             this->options().max_association_dt);
    for (const auto& match : matches)
      entries_.push_back(
          {rgb[match.first].timestamp, rgb[match.first].file, depth[match.second].file});
    spdlog::info("{}: {} rgb-depth pairs from {} rgb and {} depth images (max dt {} s)",
                 root_.string(), entries_.size(), rgb.size(), depth.size(),
                 this->options().max_association_dt);
    if (entries_.empty())
      fail("{}: no rgb image has a depth image within {} s", root_.string(),
           this->options().max_association_dt);
  }
  setFrameCount(entries_.size(), (root_ / "rgb.txt").string());
}

std::string TumRgbdReader::name() const {
  return (with_depth_ ? "tum:" : "tum-mono:") + root_.string();
}

Trajectory TumRgbdReader::readGroundTruth(const std::filesystem::path& root) {
  return readTrajectory(root / "groundtruth.txt", TrajectoryFormat::Tum);
}

Trajectory TumRgbdReader::groundTruth() const {
  if (!std::filesystem::exists(root_ / "groundtruth.txt")) return {};
  return readGroundTruth(root_);
}

FrameData TumRgbdReader::loadFrame(std::size_t index) const {
  const Entry& entry = entries_[index];
  FrameData frame;
  frame.index = index;
  frame.timestamp = entry.timestamp;
  frame.image_path = entry.rgb;
  frame.image = readImageFile(entry.rgb, imageReadFlags(cv::IMREAD_COLOR));
  if (with_depth_) frame.depth = readDepthFile(entry.depth);
  return frame;
}

}  // namespace lumaslam::io
