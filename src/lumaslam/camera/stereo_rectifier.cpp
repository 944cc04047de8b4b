#include "lumaslam/camera/stereo_rectifier.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::camera {
namespace {

cv::Mat toCv(const Eigen::Matrix3d& m) {
  cv::Mat out(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.at<double>(r, c) = m(r, c);
  }
  return out;
}

}  // namespace

StereoRectifier::StereoRectifier(const PinholeCamera& left, const PinholeCamera& right,
                                 const SE3& T_c1_c2, double alpha)
    : left_(left), right_(right), rectified_(left.undistorted()) {
  if (!(left.size() == right.size())) {
    fail("StereoRectifier: left {}x{} and right {}x{} images differ in size", left.size().width,
         left.size().height, right.size().width, right.size().height);
  }
  if (T_c1_c2.translation().norm() <= 0.0) fail("StereoRectifier: baseline is zero");
  // cv::stereoRectify wants the motion from camera 1 to camera 2 coordinates: p2 = R p1 + T.
  const SE3 T_c2_c1 = T_c1_c2.inverse();
  const cv::Mat R = toCv(T_c2_c1.linear());
  const cv::Vec3d T(T_c2_c1.translation().x(), T_c2_c1.translation().y(),
                    T_c2_c1.translation().z());
  const cv::Size size(left.size().width, left.size().height);
  cv::Mat Q;
  cv::stereoRectify(left.K(), left.distortionCoefficients(), right.K(),
                    right.distortionCoefficients(), size, R, T, R1_, R2_, P1_, P2_, Q,
                    cv::CALIB_ZERO_DISPARITY, alpha, size);
  cv::initUndistortRectifyMap(left.K(), left.distortionCoefficients(), R1_, P1_, size, CV_16SC2,
                              leftMapX_, leftMapY_);
  cv::initUndistortRectifyMap(right.K(), right.distortionCoefficients(), R2_, P2_, size, CV_16SC2,
                              rightMapX_, rightMapY_);

  const double fx = P1_.at<double>(0, 0);
  rectified_ = PinholeCamera(fx, P1_.at<double>(1, 1), P1_.at<double>(0, 2), P1_.at<double>(1, 2),
                             left.size());
  // P2 = [K | K * (tx, 0, 0)] with tx = -baseline for a right camera on the +x side.
  baseline_ = -P2_.at<double>(0, 3) / P2_.at<double>(0, 0);
  if (!(baseline_ > 0.0)) {
    fail(
        "StereoRectifier: camera 2 is not to the right of camera 1 (rectified baseline {} m); "
        "check Stereo.T_c1_c2 (pose of camera 2 in camera 1)",
        baseline_);
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R_rect_c1_(r, c) = R1_.at<double>(r, c);
  }
}

StereoRectifier StereoRectifier::fromSettings(const CameraSettings& left,
                                              const StereoSettings& stereo, std::string_view origin,
                                              double alpha) {
  if (!stereo.right) {
    fail(
        "{}: the stereo pair is already rectified (Camera.type {} without Camera2.*); "
        "nothing to rectify",
        origin, toString(left.model));
  }
  return StereoRectifier(PinholeCamera::fromSettings(left),
                         PinholeCamera::fromSettings(*stereo.right), stereo.T_c1_c2, alpha);
}

cv::Mat StereoRectifier::remap(const cv::Mat& image, const cv::Mat& mapX, const cv::Mat& mapY,
                               const char* side) const {
  if (image.empty()) fail("StereoRectifier: {} image is empty", side);
  if (image.cols != left_.size().width || image.rows != left_.size().height) {
    fail("StereoRectifier: {} image is {}x{}, calibration is for {}x{}", side, image.cols,
         image.rows, left_.size().width, left_.size().height);
  }
  cv::Mat out;
  cv::remap(image, out, mapX, mapY, cv::INTER_LINEAR);
  return out;
}

cv::Mat StereoRectifier::rectifyLeft(const cv::Mat& image) const {
  return remap(image, leftMapX_, leftMapY_, "left");
}

cv::Mat StereoRectifier::rectifyRight(const cv::Mat& image) const {
  return remap(image, rightMapX_, rightMapY_, "right");
}

std::pair<cv::Mat, cv::Mat> StereoRectifier::rectify(const cv::Mat& left,
                                                     const cv::Mat& right) const {
  return {rectifyLeft(left), rectifyRight(right)};
}

std::vector<cv::Point2f> StereoRectifier::rectifyLeftPoints(
    const std::vector<cv::Point2f>& raw) const {
  if (raw.empty()) return raw;
  std::vector<cv::Point2f> out;
  cv::undistortPoints(raw, out, left_.K(), left_.distortionCoefficients(), R1_, P1_,
                      PinholeCamera::undistortTermination());
  return out;
}

std::vector<cv::Point2f> StereoRectifier::rectifyRightPoints(
    const std::vector<cv::Point2f>& raw) const {
  if (raw.empty()) return raw;
  std::vector<cv::Point2f> out;
  cv::undistortPoints(raw, out, right_.K(), right_.distortionCoefficients(), R2_, P2_,
                      PinholeCamera::undistortTermination());
  return out;
}

}  // namespace lumaslam::camera
