#pragma once
// KITTI odometry sequence folder (…/sequences/XX): image_0/NNNNNN.png (+ image_1 for stereo),
// times.txt, calib.txt (P0..P3); ground truth in …/poses/XX.txt.
#include <filesystem>
#include <vector>

#include "lumaslam/io/listed_frames_reader.h"

namespace lumaslam::io {

class KittiReader final : public ListedFramesReader {
 public:
  // stereo: use image_1 when it exists (mono otherwise).
  KittiReader(std::filesystem::path sequence_dir, bool stereo, ReaderOptions options);

  std::string name() const override;
  bool isStereo() const override { return stereo_; }
  Trajectory groundTruth() const override;
  std::optional<CalibrationHint> calibration() const override { return calibration_; }

  // Left-camera poses from `explicit_file` or SEQUENCE/../../poses/XX.txt, timed by
  // SEQUENCE/times.txt. Empty if no pose file exists.
  static Trajectory readGroundTruth(const std::filesystem::path& sequence_dir,
                                    const std::filesystem::path& explicit_file = {});

  // calib.txt: fx, fy, cx, cy from P0; T_left_right from P1 (right camera at +baseline on x).
  static CalibrationHint readCalibration(const std::filesystem::path& calib_file);

 private:
  FrameData loadFrame(std::size_t index) const override;
  std::filesystem::path imagePath(const char* camera_folder, std::size_t index) const;

  std::filesystem::path sequence_dir_;
  bool stereo_;
  std::vector<double> times_;
  CalibrationHint calibration_;
};

}  // namespace lumaslam::io
