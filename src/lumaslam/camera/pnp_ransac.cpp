#include "lumaslam/camera/pnp_ransac.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace lumaslam::camera {

std::optional<PnpRansacResult> solvePnpRansac(const std::vector<Eigen::Vector3d>& X_w,
                                              const std::vector<cv::Point2f>& uv,
                                              const CameraIntrinsics& k,
                                              const PnpRansacParams& params) {
  if (X_w.size() != uv.size() || static_cast<int>(X_w.size()) < params.min_inliers) {
    return std::nullopt;
  }
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  object.reserve(X_w.size());
  image.reserve(uv.size());
  for (std::size_t m = 0; m < X_w.size(); ++m) {
    object.emplace_back(X_w[m].x(), X_w[m].y(), X_w[m].z());
    image.emplace_back(uv[m].x, uv[m].y);
  }
  const cv::Matx33d K(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  cv::Mat rvec;
  cv::Mat tvec;
  std::vector<int> inliers;
  const bool ok =
      cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, params.iterations,
                         params.reprojection_px, 0.99, inliers, cv::SOLVEPNP_EPNP);
  if (!ok || static_cast<int>(inliers.size()) < params.min_inliers) return std::nullopt;
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d R_e;
  cv::cv2eigen(cv::Mat(R), R_e);
  PnpRansacResult result;
  result.T_c_w.linear() = R_e;
  result.T_c_w.translation() =
      Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  result.is_inlier.assign(X_w.size(), false);
  for (const int i : inliers) result.is_inlier[static_cast<std::size_t>(i)] = true;
  result.inliers = static_cast<int>(inliers.size());
  return result;
}

}  // namespace lumaslam::camera
