#pragma once
// Two-view initialisation of a monocular map (ORB-SLAM's Initializer): from pixel matches
// between a reference and a current view, fit a homography (OpenCV RANSAC) and, in parallel, a
// fundamental matrix (F = K^-T E K^-1 from OpenCV's 5-point USAC essential matrix), score both with
// ORB-SLAM's symmetric transfer scores, pick H when R_H = S_H / (S_H + S_F) > 0.45, recover the
// relative motion from the chosen model and keep the solution that triangulates the most points in
// front of both cameras with enough parallax, then refine motion and points by a two-view bundle
// adjustment. Failure (too little parallax, ambiguous solutions, too few matches) is normal while
// the camera has not moved enough; it is reported, never thrown.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "lumaslam/core/pose.h"

namespace lumaslam::track {

enum class TwoViewModel { None, Homography, Fundamental };
const char* toString(TwoViewModel model);

struct TwoViewParams {
  double sigma = 1.0;  // keypoint position standard deviation, pixels
  int ransac_iterations = 200;
  double homography_ratio = 0.45;  // choose H when S_H / (S_H + S_F) exceeds this
  double min_parallax_deg = 1.0;
  int min_triangulated = 50;
  double min_good_fraction = 0.9;     // of the model's inliers, triangulated in front of both
  double max_runner_up_ratio = 0.75;  // best solution must beat the second clearly
  // Two-view bundle adjustment (first view fixed) of the accepted reconstruction; its
  // chi-square outliers are dropped. 0 disables.
  int refine_iterations = 20;
  // Fit the homography in a thread of its own beside the essential matrix; false
  // (System.sequential): one after the other in the caller's thread.
  bool threaded = true;
};

struct TwoViewReconstruction {
  bool success = false;
  std::string failure;  // why not, when !success
  TwoViewModel model = TwoViewModel::None;
  double score_h = 0.0;
  double score_f = 0.0;
  double score_ratio = 0.0;       // R_H
  int inliers = 0;                // of the chosen model
  SE3 T_c2_c1 = SE3::Identity();  // translation of arbitrary scale
  // Per input match: the triangulated point in camera 1, or nullopt (outlier, behind a
  // camera, too large a reprojection error or too little parallax).
  std::vector<std::optional<Eigen::Vector3d>> points;
  int triangulated = 0;
  double parallax_deg = 0.0;  // ORB-SLAM's measure: the 50th-largest parallax angle
};

class TwoViewInitializer {
 public:
  // K: pinhole intrinsics of both views; points must be undistorted pixels.
  explicit TwoViewInitializer(const cv::Matx33d& K, const TwoViewParams& params = {});

  // p1[i] in the reference view matches p2[i] in the current view.
  TwoViewReconstruction reconstruct(const std::vector<cv::Point2f>& p1,
                                    const std::vector<cv::Point2f>& p2) const;

  const TwoViewParams& params() const { return params_; }

 private:
  TwoViewReconstruction fromHomography(const cv::Matx33d& H, const std::vector<bool>& inliers,
                                       const std::vector<cv::Point2f>& p1,
                                       const std::vector<cv::Point2f>& p2) const;
  TwoViewReconstruction fromFundamental(const cv::Matx33d& F, const std::vector<bool>& inliers,
                                        const std::vector<cv::Point2f>& p1,
                                        const std::vector<cv::Point2f>& p2) const;

  void refine(TwoViewReconstruction& reconstruction, const std::vector<cv::Point2f>& p1,
              const std::vector<cv::Point2f>& p2) const;

  cv::Matx33d K_;
  TwoViewParams params_;
};

// ORB-SLAM's CheckHomography / CheckFundamental: symmetric transfer (H) or epipolar-line (F)
// errors of every match, normalised by sigma^2; a match is an inlier when both directions pass
// the chi-square test (5.991 for H, 3.841 for F) and scores (5.991 - error) per direction.
struct ModelScore {
  double score = 0.0;
  std::vector<bool> inliers;
  int inlierCount() const;
};
ModelScore scoreHomography(const cv::Matx33d& H21, const std::vector<cv::Point2f>& p1,
                           const std::vector<cv::Point2f>& p2, double sigma);
ModelScore scoreFundamental(const cv::Matx33d& F21, const std::vector<cv::Point2f>& p1,
                            const std::vector<cv::Point2f>& p2, double sigma);

}  // namespace lumaslam::track
