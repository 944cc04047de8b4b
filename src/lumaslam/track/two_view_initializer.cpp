#include "lumaslam/track/two_view_initializer.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>

#include "lumaslam/core/side_job.h"
#include "lumaslam/optimize/local_ba.h"

namespace lumaslam::track {
namespace {

constexpr double kChi2TwoDof = 5.991;  // 95%, 2 degrees of freedom (transfer error)
constexpr double kChi2OneDof = 3.841;  // 95%, 1 degree of freedom (distance to a line)
// Rays closer than this (cosine) are parallel: such points carry no depth information.
constexpr double kParallelCos = 0.99998;

struct Motion {
  cv::Matx33d R;
  cv::Vec3d t;
};

// ORB-SLAM's CheckRT for one candidate motion.
struct MotionCheck {
  int good = 0;  // in front of both cameras with a small reprojection error
  double parallax_deg = 0.0;
  std::vector<std::optional<Eigen::Vector3d>> points;  // good and not parallel
  int triangulated = 0;
};

cv::Matx34d projection(const cv::Matx33d& K, const cv::Matx33d& R, const cv::Vec3d& t) {
  cv::Matx34d Rt;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) Rt(r, c) = R(r, c);
    Rt(r, 3) = t(r);
  }
  return K * Rt;
}

double reprojectionError2(const cv::Matx33d& K, const cv::Vec3d& X_c, const cv::Point2f& p) {
  const double u = K(0, 0) * X_c(0) / X_c(2) + K(0, 2);
  const double v = K(1, 1) * X_c(1) / X_c(2) + K(1, 2);
  return (u - p.x) * (u - p.x) + (v - p.y) * (v - p.y);
}

MotionCheck checkMotion(const Motion& motion, const cv::Matx33d& K,
                        const std::vector<bool>& inliers, const std::vector<cv::Point2f>& p1,
                        const std::vector<cv::Point2f>& p2, double sigma) {
  MotionCheck check;
  check.points.assign(p1.size(), std::nullopt);
  std::vector<int> used;
  for (std::size_t i = 0; i < p1.size(); ++i) {
    if (inliers[i]) used.push_back(static_cast<int>(i));
  }
  if (used.empty()) return check;
  cv::Mat_<double> x1(2, static_cast<int>(used.size()));
  cv::Mat_<double> x2(2, static_cast<int>(used.size()));
  for (int k = 0; k < static_cast<int>(used.size()); ++k) {
    x1(0, k) = p1[static_cast<std::size_t>(used[k])].x;
    x1(1, k) = p1[static_cast<std::size_t>(used[k])].y;
    x2(0, k) = p2[static_cast<std::size_t>(used[k])].x;
    x2(1, k) = p2[static_cast<std::size_t>(used[k])].y;
  }
  cv::Mat_<double> X;  // 4 x N homogeneous, camera 1 frame
  cv::triangulatePoints(projection(K, cv::Matx33d::eye(), cv::Vec3d(0, 0, 0)),
                        projection(K, motion.R, motion.t), x1, x2, X);

  const cv::Vec3d O2 = -(motion.R.t() * motion.t);  // camera 2 centre in camera 1
  const double max_error2 = 4.0 * sigma * sigma;
  std::vector<double> cos_parallaxes;
  for (int k = 0; k < X.cols; ++k) {
    const auto i = static_cast<std::size_t>(used[static_cast<std::size_t>(k)]);
    const double w = X(3, k);
    if (std::abs(w) < 1e-12) continue;
    const cv::Vec3d X1(X(0, k) / w, X(1, k) / w, X(2, k) / w);
    if (!std::isfinite(X1(0)) || !std::isfinite(X1(1)) || !std::isfinite(X1(2))) continue;
    const cv::Vec3d ray1 = X1;
    const cv::Vec3d ray2 = X1 - O2;
    const double cos_parallax = ray1.dot(ray2) / (cv::norm(ray1) * cv::norm(ray2));
    const cv::Vec3d X2 = motion.R * X1 + motion.t;
    if (X1(2) <= 0 || X2(2) <= 0) continue;  // cheirality
    if (reprojectionError2(K, X1, p1[i]) > max_error2) continue;
    if (reprojectionError2(K, X2, p2[i]) > max_error2) continue;
    cos_parallaxes.push_back(cos_parallax);
    ++check.good;
    if (cos_parallax < kParallelCos) {
      check.points[i] = Eigen::Vector3d(X1(0), X1(1), X1(2));
      ++check.triangulated;
    }
  }
  if (!cos_parallaxes.empty()) {
    std::sort(cos_parallaxes.begin(), cos_parallaxes.end());
    const std::size_t index = std::min<std::size_t>(50, cos_parallaxes.size() - 1);
    check.parallax_deg = std::acos(std::clamp(cos_parallaxes[index], -1.0, 1.0)) * 180.0 / CV_PI;
  }
  return check;
}

// Chooses among the candidate motions as ORB-SLAM's ReconstructH / ReconstructF: the best must
// explain most inliers, clearly beat the runner-up, triangulate enough points and see them
// with enough parallax.
TwoViewReconstruction chooseMotion(const std::vector<Motion>& motions, const cv::Matx33d& K,
                                   const std::vector<bool>& inliers,
                                   const std::vector<cv::Point2f>& p1,
                                   const std::vector<cv::Point2f>& p2,
                                   const TwoViewParams& params) {
  TwoViewReconstruction result;
  const auto inlier_count = static_cast<int>(std::count(inliers.begin(), inliers.end(), true));
  result.inliers = inlier_count;
  int best = -1;
  int second_good = 0;
  std::vector<MotionCheck> checks;
  for (const auto& motion : motions) {
    checks.push_back(checkMotion(motion, K, inliers, p1, p2, params.sigma));
    const int good = checks.back().good;
    const int index = static_cast<int>(checks.size()) - 1;
    if (best < 0 || good > checks[static_cast<std::size_t>(best)].good) {
      if (best >= 0) second_good = checks[static_cast<std::size_t>(best)].good;
      best = index;
    } else {
      second_good = std::max(second_good, good);
    }
  }
  if (best < 0) {
    result.points.assign(p1.size(), std::nullopt);
    result.failure = "no motion hypothesis";
    return result;
  }
  auto& chosen = checks[static_cast<std::size_t>(best)];
  const auto& motion = motions[static_cast<std::size_t>(best)];
  result.parallax_deg = chosen.parallax_deg;
  result.triangulated = chosen.triangulated;
  const double min_good = std::max<double>(params.min_good_fraction * inlier_count,
                                           static_cast<double>(params.min_triangulated));
  if (chosen.good < min_good) {
    result.failure =
        fmt::format("best motion explains {} of {} inliers", chosen.good, inlier_count);
  } else if (second_good >= params.max_runner_up_ratio * chosen.good) {
    result.failure =
        fmt::format("ambiguous motion ({} vs {} points in front)", chosen.good, second_good);
  } else if (chosen.parallax_deg < params.min_parallax_deg) {
    result.failure =
        fmt::format("parallax {:.2f} deg < {:.2f}", chosen.parallax_deg, params.min_parallax_deg);
  } else if (chosen.triangulated < params.min_triangulated) {
    result.failure = fmt::format("{} points triangulated, need {}", chosen.triangulated,
                                 params.min_triangulated);
  } else {
    result.success = true;
  }
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R(r, c) = motion.R(r, c);
  }
  result.T_c2_c1.linear() = R;
  result.T_c2_c1.translation() = Eigen::Vector3d(motion.t(0), motion.t(1), motion.t(2));
  result.points = std::move(chosen.points);
  return result;
}

struct FittedModel {
  cv::Matx33d matrix = cv::Matx33d::zeros();
  ModelScore score;
};

}  // namespace

const char* toString(TwoViewModel model) {
  switch (model) {
    case TwoViewModel::None:
      return "none";
    case TwoViewModel::Homography:
      return "homography";
    case TwoViewModel::Fundamental:
      return "fundamental";
  }
  return "?";
}

int ModelScore::inlierCount() const {
  return static_cast<int>(std::count(inliers.begin(), inliers.end(), true));
}

ModelScore scoreHomography(const cv::Matx33d& H21, const std::vector<cv::Point2f>& p1,
                           const std::vector<cv::Point2f>& p2, double sigma) {
  ModelScore result;
  result.inliers.assign(p1.size(), false);
  const cv::Matx33d H12 = H21.inv();
  const double inv_sigma2 = 1.0 / (sigma * sigma);
  auto transfer_chi2 = [&](const cv::Matx33d& H, const cv::Point2f& from, const cv::Point2f& to) {
    const cv::Vec3d x = H * cv::Vec3d(from.x, from.y, 1.0);
    if (std::abs(x(2)) < 1e-12) return std::numeric_limits<double>::infinity();
    const double du = x(0) / x(2) - to.x;
    const double dv = x(1) / x(2) - to.y;
    return (du * du + dv * dv) * inv_sigma2;
  };
  for (std::size_t i = 0; i < p1.size(); ++i) {
    const double chi1 = transfer_chi2(H12, p2[i], p1[i]);
    const double chi2 = transfer_chi2(H21, p1[i], p2[i]);
    bool inlier = true;
    if (chi1 > kChi2TwoDof) {
      inlier = false;
    } else {
      result.score += kChi2TwoDof - chi1;
    }
    if (chi2 > kChi2TwoDof) {
      inlier = false;
    } else {
      result.score += kChi2TwoDof - chi2;
    }
    result.inliers[i] = inlier;
  }
  return result;
}

ModelScore scoreFundamental(const cv::Matx33d& F21, const std::vector<cv::Point2f>& p1,
                            const std::vector<cv::Point2f>& p2, double sigma) {
  ModelScore result;
  result.inliers.assign(p1.size(), false);
  const double inv_sigma2 = 1.0 / (sigma * sigma);
  auto line_chi2 = [&](const cv::Vec3d& line, const cv::Point2f& p) {
    const double den = line(0) * line(0) + line(1) * line(1);
    if (den <= 0) return std::numeric_limits<double>::infinity();
    const double num = line(0) * p.x + line(1) * p.y + line(2);
    return num * num / den * inv_sigma2;
  };
  for (std::size_t i = 0; i < p1.size(); ++i) {
    const cv::Vec3d x1(p1[i].x, p1[i].y, 1.0);
    const cv::Vec3d x2(p2[i].x, p2[i].y, 1.0);
    const double chi_in2 = line_chi2(F21 * x1, p2[i]);      // line of x1 in view 2
    const double chi_in1 = line_chi2(F21.t() * x2, p1[i]);  // line of x2 in view 1
    bool inlier = true;
    // The test uses the 1-dof threshold, the score the 2-dof one (as ORB-SLAM, so that H and
    // F scores are comparable).
    for (const double chi : {chi_in2, chi_in1}) {
      if (chi > kChi2OneDof) {
        inlier = false;
      } else {
        result.score += kChi2TwoDof - chi;
      }
    }
    result.inliers[i] = inlier;
  }
  return result;
}

TwoViewInitializer::TwoViewInitializer(const cv::Matx33d& K, const TwoViewParams& params)
    : K_(K), params_(params) {}

TwoViewReconstruction TwoViewInitializer::reconstruct(const std::vector<cv::Point2f>& p1,
                                                      const std::vector<cv::Point2f>& p2) const {
  TwoViewReconstruction result;
  result.points.assign(p1.size(), std::nullopt);
  if (p1.size() != p2.size()) {
    result.failure = fmt::format("{} reference points but {} current points", p1.size(), p2.size());
    return result;
  }
  const auto n = static_cast<int>(p1.size());
  if (n < std::max(8, params_.min_triangulated)) {
    result.failure = fmt::format("{} matches, need {}", n, std::max(8, params_.min_triangulated));
    return result;
  }

  // Both models in parallel (ORB-SLAM runs FindHomography and FindFundamental in two threads),
  // or one after the other in sequential mode.
  const double sigma = params_.sigma;
  const int iterations = params_.ransac_iterations;
  auto homography = core::startSideJob(params_.threaded, [&] {
    FittedModel fitted;
    cv::Mat mask;
    cv::Mat H;
    try {
      H = cv::findHomography(p1, p2, cv::RANSAC, std::sqrt(kChi2TwoDof) * sigma, mask, iterations,
                             0.99);
    } catch (const cv::Exception&) {
      return fitted;  // degenerate input: no homography (scored 0)
    }
    if (H.rows == 3 && H.cols == 3) {
      fitted.matrix = cv::Matx33d(H);
      fitted.score = scoreHomography(fitted.matrix, p1, p2, sigma);
    }
    return fitted;
  });
  // The calibrated 5-point solver (essential matrix) is far more accurate than the 7/8-point
  // fundamental one for the same matches; F = K^-T E K^-1 is scored as ORB-SLAM scores F.
  FittedModel fundamental;
  cv::Mat mask;
  cv::Mat E;
  try {
    E = cv::findEssentialMat(p1, p2, cv::Mat(K_), cv::USAC_ACCURATE, 0.999,
                             std::sqrt(kChi2OneDof) * sigma, iterations, mask);
  } catch (const cv::Exception&) {
    E.release();  // degenerate input: no essential matrix (scored 0)
  }
  if (E.rows == 3 && E.cols == 3) {  // the 5-point solver may return several stacked matrices
    const cv::Matx33d K_inv = K_.inv();
    fundamental.matrix = K_inv.t() * cv::Matx33d(E) * K_inv;
    fundamental.score = scoreFundamental(fundamental.matrix, p1, p2, sigma);
  }
  const FittedModel homography_fit = homography.get();

  const double total = homography_fit.score.score + fundamental.score.score;
  if (total <= 0) {
    result.failure = "neither a homography nor a fundamental matrix fits";
    return result;
  }
  const double ratio = homography_fit.score.score / total;
  if (ratio > params_.homography_ratio) {
    result = fromHomography(homography_fit.matrix, homography_fit.score.inliers, p1, p2);
    result.model = TwoViewModel::Homography;
  } else {
    result = fromFundamental(fundamental.matrix, fundamental.score.inliers, p1, p2);
    result.model = TwoViewModel::Fundamental;
  }
  if (result.success && params_.refine_iterations > 0) refine(result, p1, p2);
  result.score_h = homography_fit.score.score;
  result.score_f = fundamental.score.score;
  result.score_ratio = ratio;
  return result;
}

void TwoViewInitializer::refine(TwoViewReconstruction& reconstruction,
                                const std::vector<cv::Point2f>& p1,
                                const std::vector<cv::Point2f>& p2) const {
  optimize::LocalBAProblem problem;
  problem.camera = {K_(0, 0), K_(1, 1), K_(0, 2), K_(1, 2), 0.0};
  problem.keyFrames = {{0, SE3::Identity(), true}, {1, reconstruction.T_c2_c1, false}};
  const double inv_sigma2 = 1.0 / (params_.sigma * params_.sigma);
  std::vector<std::size_t> match_of_point;
  for (std::size_t i = 0; i < reconstruction.points.size(); ++i) {
    if (!reconstruction.points[i]) continue;
    problem.points.push_back({i, *reconstruction.points[i]});
    for (const auto& [view, p] : {std::pair{0U, p1[i]}, std::pair{1U, p2[i]}}) {
      optimize::BAObservation obs;
      obs.keyFrameId = view;
      obs.pointId = i;
      obs.uv = {p.x, p.y};
      obs.invSigma2 = inv_sigma2;
      problem.observations.push_back(obs);
    }
    match_of_point.push_back(i);
  }
  optimize::LocalBAOptions options;
  options.maxIterations = params_.refine_iterations;
  const auto refined = optimize::optimizeLocalBundle(problem, options);
  reconstruction.T_c2_c1 = refined.T_c_w[1];
  for (std::size_t k = 0; k < match_of_point.size(); ++k) {
    auto& point = reconstruction.points[match_of_point[k]];
    if (refined.isOutlier[2 * k] || refined.isOutlier[2 * k + 1]) {
      point.reset();
      --reconstruction.triangulated;
    } else {
      point = refined.X_w[k];
    }
  }
}

TwoViewReconstruction TwoViewInitializer::fromHomography(const cv::Matx33d& H,
                                                         const std::vector<bool>& inliers,
                                                         const std::vector<cv::Point2f>& p1,
                                                         const std::vector<cv::Point2f>& p2) const {
  std::vector<cv::Mat> rotations;
  std::vector<cv::Mat> translations;
  std::vector<cv::Mat> normals;
  cv::decomposeHomographyMat(H, K_, rotations, translations, normals);
  std::vector<Motion> motions;
  for (std::size_t k = 0; k < rotations.size(); ++k) {
    motions.push_back({cv::Matx33d(rotations[k]), cv::Vec3d(translations[k])});
  }
  return chooseMotion(motions, K_, inliers, p1, p2, params_);
}

TwoViewReconstruction TwoViewInitializer::fromFundamental(
    const cv::Matx33d& F, const std::vector<bool>& inliers, const std::vector<cv::Point2f>& p1,
    const std::vector<cv::Point2f>& p2) const {
  const cv::Matx33d E = K_.t() * F * K_;
  cv::Mat R1;
  cv::Mat R2;
  cv::Mat t;
  cv::decomposeEssentialMat(E, R1, R2, t);
  const cv::Vec3d tv(t);
  const std::vector<Motion> motions{
      {cv::Matx33d(R1), tv}, {cv::Matx33d(R1), -tv}, {cv::Matx33d(R2), tv}, {cv::Matx33d(R2), -tv}};
  return chooseMotion(motions, K_, inliers, p1, p2, params_);
}

}  // namespace lumaslam::track
