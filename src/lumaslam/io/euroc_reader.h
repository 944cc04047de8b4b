#pragma once
// EuRoC MAV sequence in ASL layout: ROOT/mav0/cam0 (+ cam1 for stereo, pairs matched by equal
// timestamps), sensor.yaml calibration, ground truth as cam0 poses.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "lumaslam/io/listed_frames_reader.h"

namespace lumaslam::io {

class EurocReader final : public ListedFramesReader {
 public:
  EurocReader(const std::filesystem::path& root, bool stereo, ReaderOptions options);

  std::string name() const override;
  bool isStereo() const override { return stereo_; }
  Trajectory groundTruth() const override;
  std::optional<CalibrationHint> calibration() const override { return calibration_; }

  // cam0 poses T_w_cam0 from, in order of preference: `explicit_file` (a file inside
  // state_groundtruth_estimate0/ holds body poses and is converted, any other is taken as cam0
  // poses), mav0/state_groundtruth_estimate0/data.csv (body poses, converted with cam0's
  // T_BS: T_w_cam0 = T_w_body * T_BS), a csv in ROOT whose name contains "GT" and "cam0"
  // (ORB-SLAM3's left-camera ground truth). Empty if none exists.
  static Trajectory readGroundTruth(const std::filesystem::path& root,
                                    const std::filesystem::path& explicit_file = {});

 private:
  struct Entry {
    std::int64_t timestamp_ns;
    std::filesystem::path left;
    std::filesystem::path right;  // empty in mono mode
  };
  FrameData loadFrame(std::size_t index) const override;

  std::filesystem::path root_;
  std::filesystem::path mav0_;
  bool stereo_;
  std::optional<CalibrationHint> calibration_;  // nullopt: a camera camera/ cannot describe
  std::vector<Entry> entries_;
};

}  // namespace lumaslam::io
