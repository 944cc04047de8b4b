#include "lumaslam/io/image_files.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::io {

cv::Mat readImageFile(const std::filesystem::path& file, int imread_flags) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) fail("{}: image file not found", file.string());
  cv::Mat image = cv::imread(file.string(), imread_flags);
  if (image.empty()) fail("{}: cannot decode image (corrupt or unsupported format)", file.string());
  return image;
}

cv::Mat readDepthFile(const std::filesystem::path& file) {
  cv::Mat depth = readImageFile(file, cv::IMREAD_ANYDEPTH);
  if (depth.type() != CV_16UC1)
    fail("{}: depth image must be 16-bit single-channel, got {}", file.string(),
         cv::typeToString(depth.type()));
  return depth;
}

bool hasImageExtension(const std::filesystem::path& file) {
  static constexpr std::array<std::string_view, 9> kExtensions = {
      ".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm", ".ppm", ".webp"};
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::find(kExtensions.begin(), kExtensions.end(), extension) != kExtensions.end();
}

}  // namespace lumaslam::io
