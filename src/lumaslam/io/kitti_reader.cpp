#include "lumaslam/io/kitti_reader.h"

#include <spdlog/spdlog.h>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/image_files.h"
#include "lumaslam/io/text_lines.h"
#include "lumaslam/io/trajectory_io.h"

namespace lumaslam::io {

namespace {
// SEQUENCES/XX -> POSES/XX.txt, also for "." or a path with a trailing slash.
std::filesystem::path defaultPoseFile(const std::filesystem::path& sequence_dir) {
  auto sequence = std::filesystem::weakly_canonical(sequence_dir);
  if (sequence.filename().empty()) sequence = sequence.parent_path();
  return sequence.parent_path().parent_path() / "poses" / (sequence.filename().string() + ".txt");
}

Eigen::Matrix<double, 3, 4> projectionMatrix(const std::filesystem::path& file,
                                             const TextLine& line,
                                             const std::vector<std::string_view>& fields) {
  Eigen::Matrix<double, 3, 4> P;
  for (int i = 0; i < 12; ++i) P(i / 4, i % 4) = parseNumber(fields[i + 1], file, line);
  return P;
}
}  // namespace

KittiReader::KittiReader(std::filesystem::path sequence_dir, bool stereo, ReaderOptions options)
    : ListedFramesReader(std::move(options)), sequence_dir_(std::move(sequence_dir)) {
  if (!std::filesystem::is_directory(sequence_dir_ / "image_0"))
    fail("{}: not a KITTI odometry sequence (no image_0/ folder)", sequence_dir_.string());
  stereo_ = stereo && std::filesystem::is_directory(sequence_dir_ / "image_1");
  if (stereo && !stereo_)
    spdlog::warn("{}: no image_1/ folder, reading monocular", sequence_dir_.string());
  times_ = readTimestamps(sequence_dir_ / "times.txt");
  calibration_ = readCalibration(sequence_dir_ / "calib.txt");
  if (!stereo_) {
    calibration_.right.reset();
    calibration_.T_left_right.reset();
  }
  // calib.txt has no image size: take it from the first image (one decode).
  const cv::Mat first = cv::imread(imagePath("image_0", 0).string(), cv::IMREAD_GRAYSCALE);
  calibration_.left.size = {first.cols, first.rows};
  if (calibration_.right) calibration_.right->size = calibration_.left.size;
  setFrameCount(times_.size(), (sequence_dir_ / "times.txt").string());
}

std::string KittiReader::name() const {
  return (stereo_ ? "kitti:" : "kitti-mono:") + sequence_dir_.string();
}

CalibrationHint KittiReader::readCalibration(const std::filesystem::path& calib_file) {
  std::optional<Eigen::Matrix<double, 3, 4>> P0, P1;
  for (const auto& line : readDataLines(calib_file)) {
    const auto fields = splitFields(line.text, " \t");
    if (fields.empty() || (fields[0] != "P0:" && fields[0] != "P1:")) continue;
    if (fields.size() != 13)
      fail("{}:{}: expected '{} ' and 12 numbers, got '{}'", calib_file.string(), line.number,
           fields[0], line.text);
    (fields[0] == "P0:" ? P0 : P1) = projectionMatrix(calib_file, line, fields);
  }
  if (!P0) fail("{}: no 'P0:' line", calib_file.string());
  if ((*P0)(0, 0) <= 0.0 || (*P0)(1, 1) <= 0.0)
    fail("{}: P0 has a non-positive focal length", calib_file.string());

  CalibrationHint hint;
  hint.left.fx = (*P0)(0, 0);
  hint.left.fy = (*P0)(1, 1);
  hint.left.cx = (*P0)(0, 2);
  hint.left.cy = (*P0)(1, 2);
  hint.left.model = camera::CameraModel::Rectified;  // P0/P1 describe rectified images
  hint.left.fps = 10.0;
  if (P1) {
    hint.right = hint.left;
    hint.right->fx = (*P1)(0, 0);
    hint.right->fy = (*P1)(1, 1);
    hint.right->cx = (*P1)(0, 2);
    hint.right->cy = (*P1)(1, 2);
    // Rectified pair: P1 = K [I | -baseline e_x], so the right camera sits at +baseline on x.
    const double baseline = -(*P1)(0, 3) / (*P1)(0, 0);
    SE3 T_left_right = SE3::Identity();
    T_left_right.translation() = Eigen::Vector3d(baseline, 0.0, 0.0);
    hint.T_left_right = T_left_right;
  }
  return hint;
}

Trajectory KittiReader::readGroundTruth(const std::filesystem::path& sequence_dir,
                                        const std::filesystem::path& explicit_file) {
  auto times = sequence_dir / "times.txt";
  if (!std::filesystem::exists(times)) times.clear();
  if (!explicit_file.empty()) return readTrajectory(explicit_file, TrajectoryFormat::Kitti, times);
  const auto pose_file = defaultPoseFile(sequence_dir);
  if (!std::filesystem::exists(pose_file)) return {};
  return readTrajectory(pose_file, TrajectoryFormat::Kitti, times);
}

Trajectory KittiReader::groundTruth() const {
  return readGroundTruth(sequence_dir_, options().ground_truth);
}

std::filesystem::path KittiReader::imagePath(const char* camera_folder, std::size_t index) const {
  return sequence_dir_ / camera_folder / fmt::format("{:06d}.png", index);
}

FrameData KittiReader::loadFrame(std::size_t index) const {
  const int flags = imageReadFlags(cv::IMREAD_GRAYSCALE);
  FrameData frame;
  frame.index = index;
  frame.timestamp = times_[index];
  frame.image_path = imagePath("image_0", index);
  frame.image = readImageFile(frame.image_path, flags);
  if (stereo_) frame.right = readImageFile(imagePath("image_1", index), flags);
  return frame;
}

}  // namespace lumaslam::io
