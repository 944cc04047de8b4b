#pragma once
// Reading one image file with errors that name the file.
#include <filesystem>

#include <opencv2/core.hpp>

namespace lumaslam::io {

// Throws Error "FILE: image file not found" / "FILE: cannot decode image ...".
cv::Mat readImageFile(const std::filesystem::path& file, int imread_flags);
// A 16-bit single-channel depth image as stored; throws Error if it is anything else.
cv::Mat readDepthFile(const std::filesystem::path& file);

bool hasImageExtension(const std::filesystem::path& file);

}  // namespace lumaslam::io
