#pragma once
// Reading a dataset from disk for the public API (TUM RGB-D, EuRoC, KITTI, image folders,
// videos): the readers `lumaslam run --dataset` uses, one frame at a time.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/core/mat.hpp>

#include "lumaslam/camera_pose.h"
#include "lumaslam/export.h"

namespace lumaslam {

struct DatasetFrame {
  std::size_t index = 0;
  double timestamp = 0.0;  // seconds
  cv::Mat image;           // left / rgb: BGR for TUM, folders and videos, gray for EuRoC, KITTI
  cv::Mat right;           // stereo only
  cv::Mat depth;           // RGB-D only: CV_16U as stored (TUM: 5000 per metre)
};

class LUMASLAM_API Dataset {
 public:
  // spec as `lumaslam run --dataset`: "tum:PATH", "euroc:PATH", "kitti:PATH", "folder:PATH",
  // "video:FILE", ... (README, "CLI tour"). Throws std::runtime_error naming the missing file.
  explicit Dataset(const std::string& spec, std::optional<std::size_t> max_frames = {});
  ~Dataset();
  Dataset(Dataset&&) noexcept;
  Dataset& operator=(Dataset&&) noexcept;

  std::optional<DatasetFrame> next();  // nullopt at the end
  std::size_t size() const;
  std::string name() const;
  bool isStereo() const;
  bool hasDepth() const;
  CameraTrajectory groundTruth() const;  // empty when the dataset has none

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lumaslam
