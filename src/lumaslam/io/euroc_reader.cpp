#include "lumaslam/io/euroc_reader.h"

#include <unordered_map>

#include <spdlog/spdlog.h>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/euroc_sensor_yaml.h"
#include "lumaslam/io/image_files.h"
#include "lumaslam/io/text_lines.h"
#include "lumaslam/io/trajectory_io.h"

namespace lumaslam::io {

namespace {
struct ListedImage {
  std::int64_t timestamp_ns;
  std::filesystem::path file;
};

// camN/data.csv: "timestamp_ns,filename" per line; images in camN/data/.
std::vector<ListedImage> readCameraList(const std::filesystem::path& camera_dir) {
  const auto list = camera_dir / "data.csv";
  std::vector<ListedImage> images;
  for (const auto& line : readDataLines(list)) {
    const auto fields = splitFields(line.text, ",");
    if (fields.size() != 2)
      fail("{}:{}: expected 'timestamp_ns,filename', got '{}'", list.string(), line.number,
           line.text);
    const auto timestamp = parseNanoseconds(fields[0], list, line);
    if (!images.empty() && timestamp <= images.back().timestamp_ns)
      fail("{}:{}: timestamp {} does not increase", list.string(), line.number, fields[0]);
    images.push_back({timestamp, camera_dir / "data" / std::string(fields[1])});
  }
  if (images.empty()) fail("{}: empty sequence (no images listed)", list.string());
  return images;
}

// The folder holding cam0/: ROOT/mav0, or ROOT itself when given the mav0 folder.
std::filesystem::path findMav0(const std::filesystem::path& root) {
  if (std::filesystem::is_directory(root / "mav0")) return root / "mav0";
  if (std::filesystem::is_directory(root / "cam0")) return root;
  fail("{}: not a EuRoC sequence (no mav0/ folder)", root.string());
}

Trajectory bodyToCamera(Trajectory body_poses, const SE3& T_body_cam) {
  for (auto& pose : body_poses) pose.T_w_c = pose.T_w_c * T_body_cam;
  return body_poses;
}

std::filesystem::path findOrbSlamCameraGroundTruth(const std::filesystem::path& root) {
  std::vector<std::filesystem::path> candidates;
  for (const auto& entry : std::filesystem::directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && entry.path().extension() == ".csv" &&
        name.find("GT") != std::string::npos && name.find("cam0") != std::string::npos)
      candidates.push_back(entry.path());
  }
  std::sort(candidates.begin(), candidates.end());
  return candidates.empty() ? std::filesystem::path{} : candidates.front();
}
}  // namespace

EurocReader::EurocReader(const std::filesystem::path& root, bool stereo, ReaderOptions options)
    : ListedFramesReader(std::move(options)), root_(root), mav0_(findMav0(root)), stereo_(stereo) {
  const auto left_camera = readEurocCameraYaml(mav0_ / "cam0/sensor.yaml");
  if (left_camera.camera) calibration_ = CalibrationHint{*left_camera.camera};
  const auto left = readCameraList(mav0_ / "cam0");
  if (!stereo_) {
    for (const auto& image : left) entries_.push_back({image.timestamp_ns, image.file, {}});
  } else {
    const auto right_camera = readEurocCameraYaml(mav0_ / "cam1/sensor.yaml");
    if (calibration_ && right_camera.camera) {
      calibration_->right = right_camera.camera;
      calibration_->T_left_right = left_camera.T_body_cam.inverse() * right_camera.T_body_cam;
    } else {
      calibration_.reset();
    }
    std::unordered_map<std::int64_t, std::filesystem::path> right_by_time;
    for (auto& image : readCameraList(mav0_ / "cam1"))
      right_by_time[image.timestamp_ns] = image.file;
    for (const auto& image : left) {
      const auto right = right_by_time.find(image.timestamp_ns);
      if (right != right_by_time.end())
        entries_.push_back({image.timestamp_ns, image.file, right->second});
    }
    if (entries_.size() != left.size())
      spdlog::warn(
          "{}: {} of {} cam0 images have no cam1 image with the same timestamp; "
          "they are left out",
          mav0_.string(), left.size() - entries_.size(), left.size());
  }
  setFrameCount(entries_.size(), (mav0_ / "cam0/data.csv").string());
}

std::string EurocReader::name() const {
  return (stereo_ ? "euroc:" : "euroc-mono:") + root_.string();
}

Trajectory EurocReader::readGroundTruth(const std::filesystem::path& root,
                                        const std::filesystem::path& explicit_file) {
  const auto mav0 = findMav0(root);
  const auto T_body_cam0 = [&] {
    return readEurocCameraYaml(mav0 / "cam0/sensor.yaml").T_body_cam;
  };
  if (!explicit_file.empty()) {
    const Trajectory poses = readTrajectory(explicit_file);
    if (explicit_file.parent_path().filename() == "state_groundtruth_estimate0")
      return bodyToCamera(poses, T_body_cam0());
    return poses;
  }
  const auto body_file = mav0 / "state_groundtruth_estimate0/data.csv";
  if (std::filesystem::exists(body_file))
    return bodyToCamera(readTrajectory(body_file, TrajectoryFormat::EurocCsv), T_body_cam0());
  const auto camera_file = findOrbSlamCameraGroundTruth(root);
  if (!camera_file.empty()) return readTrajectory(camera_file, TrajectoryFormat::EurocCsv);
  return {};
}

Trajectory EurocReader::groundTruth() const {
  return readGroundTruth(root_, options().ground_truth);
}

FrameData EurocReader::loadFrame(std::size_t index) const {
  const Entry& entry = entries_[index];
  const int flags = imageReadFlags(cv::IMREAD_GRAYSCALE);
  FrameData frame;
  frame.index = index;
  frame.timestamp = nanosecondsToSeconds(entry.timestamp_ns);
  frame.image_path = entry.left;
  frame.image = readImageFile(entry.left, flags);
  if (stereo_) frame.right = readImageFile(entry.right, flags);
  return frame;
}

}  // namespace lumaslam::io
