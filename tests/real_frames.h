#pragma once
// Frames of the real excerpts in ../shared/data that the feature tests share: EuRoC V1_01
// (cam0/cam1) and KITTI 07 (image_0), by index in file-name order.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "test_paths.h"

namespace lumaslam::test {

inline std::filesystem::path eurocFrame(const std::string& camera, int index) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(
           dataDir() / "euroc/V1_01_easy_micro/mav0" / camera / "data")) {
    files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files.at(index);
}

inline std::filesystem::path kittiFrame(int index) {
  char name[16];
  std::snprintf(name, sizeof(name), "%06d.png", index);
  return dataDir() / "kitti/odometry_07_first160/sequences/07/image_0" / name;
}

inline cv::Mat loadGray(const std::filesystem::path& path) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
  if (image.empty()) ADD_FAILURE() << "cannot read " << path;
  return image;
}

}  // namespace lumaslam::test
