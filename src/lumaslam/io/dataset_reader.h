#pragma once
// Streaming access to the frames of a dataset (TUM RGB-D, EuRoC, KITTI odometry, an image
// folder, a video): images are read one frame at a time in next(), never the whole sequence.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/camera/camera_settings.h"
#include "lumaslam/core/pose.h"

namespace lumaslam::io {

struct FrameData {
  std::size_t index = 0;   // position in the dataset's full frame list (before first_frame)
  double timestamp = 0.0;  // seconds
  cv::Mat image;           // left / rgb, as read (see ReaderOptions::image_read_flags)
  cv::Mat right;           // stereo only, empty otherwise
  cv::Mat depth;           // RGB-D only: raw CV_16U as stored (TUM: 5000 units per metre)
  std::filesystem::path image_path;
};

// The cameras a dataset describes (EuRoC sensor.yaml, KITTI calib.txt), in the one camera
// description the settings use (camera::CameraSettings: model, intrinsics, distortion, image
// size, frame rate).
struct CalibrationHint {
  camera::CameraSettings left;
  std::optional<camera::CameraSettings> right;
  std::optional<SE3> T_left_right;  // maps right-camera points into the left camera
  double baseline() const { return T_left_right ? T_left_right->translation().norm() : 0.0; }
};

struct ReaderOptions {
  double max_association_dt = 0.02;     // seconds, TUM rgb/depth association
  bool skip_unreadable_images = false;  // true: log a warning and go on; false: throw Error
  // cv::imread flags; unset = the dataset's natural choice: colour for TUM rgb, folders and
  // videos, grayscale for EuRoC and KITTI. Depth is always read as stored (16-bit).
  std::optional<int> image_read_flags;
  std::size_t first_frame = 0;            // frames before it are not delivered
  std::optional<std::size_t> max_frames;  // at most this many frames
  // EuRoC/KITTI: ground-truth file instead of the one found in the dataset.
  std::filesystem::path ground_truth;
  // Folder: "timestamp" per line (images in name order) or "timestamp filename" per line.
  std::filesystem::path timestamps;
  // Folder without timestamps: t = index / fps (unset: t = index). Video: overrides the
  // file's own timing.
  std::optional<double> fps;
};

class DatasetReader {
 public:
  virtual ~DatasetReader() = default;
  DatasetReader() = default;
  DatasetReader(const DatasetReader&) = delete;
  DatasetReader& operator=(const DatasetReader&) = delete;

  // The next frame, or nullopt at the end. Throws Error naming the file if an image is missing
  // or unreadable (unless ReaderOptions::skip_unreadable_images).
  virtual std::optional<FrameData> next() = 0;
  // Frames this reader will deliver (after first_frame/max_frames); for a video, the count
  // the container reports.
  virtual std::size_t size() const = 0;
  virtual std::string name() const = 0;  // e.g. "euroc:/data/V1_01_easy"
  virtual bool isStereo() const { return false; }
  virtual bool hasDepth() const { return false; }
  // Camera poses T_w_c (left / rgb camera), empty if the dataset has none. Reads the file on
  // each call.
  virtual Trajectory groundTruth() const { return {}; }
  virtual std::optional<CalibrationHint> calibration() const { return std::nullopt; }
};

// spec: "tum:PATH" (RGB-D), "tum-mono:PATH", "euroc:PATH" (folder containing mav0/; stereo),
// "euroc-mono:PATH", "kitti:PATH" (…/sequences/07; stereo when image_1/ exists),
// "kitti-mono:PATH", "folder:PATH", "video:FILE". Throws Error for an unknown kind, a missing
// path, a malformed list file or an empty sequence.
std::unique_ptr<DatasetReader> openDataset(const std::string& spec,
                                           const ReaderOptions& options = {});

// The PATH of a spec as above, unchecked; throws Error for an unknown (or no) KIND.
std::filesystem::path datasetPathOf(const std::string& spec);

// Ground truth of a dataset spec as above (camera poses), or of a plain trajectory file
// (TUM/EuRoC csv/KITTI, detected by content). Throws Error if there is none.
Trajectory loadGroundTruth(const std::string& spec);

}  // namespace lumaslam::io
