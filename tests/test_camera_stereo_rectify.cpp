// Stereo rectification on the real EuRoC V1_01 calibration and images (the pair is not
// rectified in the dataset). The calibration is read from the dataset's own sensor.yaml.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <optional>

#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "error_of.h"
#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/io/settings.h"
#include "test_paths.h"

using lumaslam::Error;
using lumaslam::camera::PinholeCamera;
using lumaslam::camera::StereoRectifier;
using lumaslam::core::SettingsFile;
using lumaslam::test::errorOf;
namespace fs = std::filesystem;

namespace {

const fs::path kMav = lumaslam::test::dataDir() / "euroc/V1_01_easy_micro/mav0";

struct SensorCalibration {
  PinholeCamera camera;
  Eigen::Isometry3d T_b_s;  // sensor pose in the body frame (T_BS)
};

SensorCalibration readSensorYaml(const fs::path& path) {
  const auto file = SettingsFile::open(path);
  const auto k = file.get<std::vector<double>>("intrinsics");
  const auto d = file.get<std::vector<double>>("distortion_coefficients");
  const auto size = file.get<std::vector<double>>("resolution");
  const auto t = file.get<std::vector<double>>("T_BS.data");
  EXPECT_EQ(k.size(), 4u);
  EXPECT_EQ(d.size(), 4u);
  EXPECT_EQ(t.size(), 16u);
  Eigen::Matrix4d T;
  for (int i = 0; i < 16; ++i) T(i / 4, i % 4) = t.at(i);
  return {PinholeCamera(k.at(0), k.at(1), k.at(2), k.at(3),
                        {static_cast<int>(size.at(0)), static_cast<int>(size.at(1))},
                        {d.at(0), d.at(1), d.at(2), d.at(3), 0.0}),
          Eigen::Isometry3d(T)};
}

cv::Mat readGray(const fs::path& path) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
  EXPECT_FALSE(image.empty()) << path;
  return image;
}

struct Matches {
  std::vector<cv::Point2f> left, right;
};

// Mutual-best ORB matches with a tight descriptor distance (few wrong matches), both keypoints
// from the full-resolution level so their positions are good to about half a pixel.
Matches orbMatches(const cv::Mat& left, const cv::Mat& right) {
  auto orb = cv::ORB::create(2000);
  std::vector<cv::KeyPoint> kl, kr;
  cv::Mat dl, dr;
  orb->detectAndCompute(left, cv::noArray(), kl, dl);
  orb->detectAndCompute(right, cv::noArray(), kr, dr);
  std::vector<cv::DMatch> matches;
  cv::BFMatcher(cv::NORM_HAMMING, true).match(dl, dr, matches);
  Matches out;
  for (const auto& m : matches) {
    if (m.distance > 40 || kl[m.queryIdx].octave != 0 || kr[m.trainIdx].octave != 0) continue;
    out.left.push_back(kl[m.queryIdx].pt);
    out.right.push_back(kr[m.trainIdx].pt);
  }
  return out;
}

double median(std::vector<double> values) {
  EXPECT_FALSE(values.empty());
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

double medianRowError(const std::vector<cv::Point2f>& left, const std::vector<cv::Point2f>& right) {
  std::vector<double> dv;
  for (std::size_t i = 0; i < left.size(); ++i) dv.push_back(std::abs(left[i].y - right[i].y));
  return median(dv);
}

class EurocStereo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto cam0 = readSensorYaml(kMav / "cam0/sensor.yaml");
    const auto cam1 = readSensorYaml(kMav / "cam1/sensor.yaml");
    T_c1_c2_ = cam0.T_b_s.inverse() * cam1.T_b_s;
    rectifier_.emplace(cam0.camera, cam1.camera, T_c1_c2_);
    const std::string frame = "1403715274312143104.png";
    left_ = readGray(kMav / "cam0/data" / frame);
    right_ = readGray(kMav / "cam1/data" / frame);
  }

  Eigen::Isometry3d T_c1_c2_;
  std::optional<StereoRectifier> rectifier_;
  cv::Mat left_, right_;
};

TEST_F(EurocStereo, RectifiedGeometryFromCalibration) {
  EXPECT_NEAR(rectifier_->baseline(), 0.110, 0.001);
  EXPECT_NEAR(rectifier_->baseline(), T_c1_c2_.translation().norm(), 1e-9);
  const PinholeCamera& rect = rectifier_->rectifiedCamera();
  EXPECT_FALSE(rect.hasDistortion());
  EXPECT_DOUBLE_EQ(rect.fx(), rect.fy());
  EXPECT_NEAR(rectifier_->bf(), rect.fx() * rectifier_->baseline(), 1e-9);
  // alpha = 0 crops to valid pixels, so the rectified focal length is a bit longer than 458.
  EXPECT_GT(rect.fx(), 400.0);
  EXPECT_LT(rect.fx(), 600.0);
  const Eigen::Matrix3d& R = rectifier_->R_rect_c1();
  EXPECT_TRUE((R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-9));

  // The shipped config holds the same calibration.
  const auto settings =
      lumaslam::io::loadSettings(lumaslam::test::sourceDir() / "configs/euroc_stereo.yaml");
  const auto fromConfig =
      StereoRectifier::fromSettings(settings.camera, *settings.stereo, settings.file->origin());
  EXPECT_NEAR(fromConfig.baseline(), rectifier_->baseline(), 1e-9);
  EXPECT_NEAR(fromConfig.rectifiedCamera().fx(), rect.fx(), 1e-6);
}

TEST_F(EurocStereo, RowsAgreeAfterRectification) {
  const Matches raw = orbMatches(left_, right_);
  ASSERT_GT(raw.left.size(), 80u);
  const double before = medianRowError(raw.left, raw.right);

  const auto [left, right] = rectifier_->rectify(left_, right_);
  EXPECT_EQ(left.size(), left_.size());
  EXPECT_EQ(left.type(), left_.type());
  const Matches rect = orbMatches(left, right);
  ASSERT_GT(rect.left.size(), 80u);
  const double after = medianRowError(rect.left, rect.right);

  // The raw matches mapped through the point rectification agree as well.
  const double pointsAfter = medianRowError(rectifier_->rectifyLeftPoints(raw.left),
                                            rectifier_->rectifyRightPoints(raw.right));
  std::cout << "median |v_l - v_r|: raw " << before << " px, rectified images " << after
            << " px, rectified points " << pointsAfter << " px (" << rect.left.size()
            << " matches)\n";
  EXPECT_LT(after, 1.0);
  EXPECT_LT(pointsAfter, 1.0);
  EXPECT_GT(before, 3.0 * after + 1.0);

  // Row-aligned matches have positive disparity (the right camera sits at +x).
  int positive = 0, rowAligned = 0;
  for (std::size_t i = 0; i < rect.left.size(); ++i) {
    if (std::abs(rect.left[i].y - rect.right[i].y) > 1.0) continue;
    ++rowAligned;
    if (rect.left[i].x - rect.right[i].x > 0.0) ++positive;
  }
  EXPECT_GT(positive, 0.9 * rowAligned);
}

TEST_F(EurocStereo, BadInputIsAClearError) {
  cv::Mat small;
  cv::resize(left_, small, cv::Size(), 0.5, 0.5);
  EXPECT_THROW((void)rectifier_->rectify(small, right_), Error);
  EXPECT_THROW((void)rectifier_->rectifyLeft(cv::Mat()), Error);
  const auto kitti =
      lumaslam::io::loadSettings(lumaslam::test::sourceDir() / "configs/kitti_04-12_stereo.yaml");
  // A rectified pair is not accepted.
  const std::string message = errorOf([&] {
    (void)StereoRectifier::fromSettings(kitti.camera, *kitti.stereo, kitti.file->origin());
  });
  EXPECT_NE(message.find("kitti_04-12_stereo.yaml"), std::string::npos);
  // Camera 2 on the left of camera 1: T_c1_c2 given the wrong way round.
  const auto cam0 = readSensorYaml(kMav / "cam0/sensor.yaml");
  const auto cam1 = readSensorYaml(kMav / "cam1/sensor.yaml");
  EXPECT_THROW(StereoRectifier(cam0.camera, cam1.camera, T_c1_c2_.inverse()), Error);
}

}  // namespace
