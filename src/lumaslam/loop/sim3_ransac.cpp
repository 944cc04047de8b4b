#include "lumaslam/loop/sim3_ransac.h"

#include <array>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

namespace lumaslam::loop {

namespace {

// X1 = S_12 X2 in closed form; nullopt for a degenerate set.
std::optional<optimize::Sim3> umeyamaSim3(const Eigen::Matrix3Xd& X2, const Eigen::Matrix3Xd& X1) {
  const Eigen::Matrix4d M = Eigen::umeyama(X2, X1, true);
  if (!M.allFinite()) return std::nullopt;
  const Eigen::Matrix3d sR = M.topLeftCorner<3, 3>();
  const double scale = std::cbrt(sR.determinant());
  if (!(scale > 1e-9)) return std::nullopt;
  const Eigen::Matrix3d R = sR / scale;
  return optimize::Sim3{scale, Eigen::Quaterniond(R).normalized(), M.topRightCorner<3, 1>()};
}

std::vector<bool> inliersOf(const optimize::Sim3& S, const std::vector<optimize::Sim3Pair>& pairs,
                            const CameraIntrinsics& camera, double chi2, int& count) {
  std::vector<bool> inlier(pairs.size(), false);
  count = 0;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const Eigen::Vector2d e = optimize::sim3PairChi2(S, pairs[p], camera, camera);
    if (e.x() < chi2 && e.y() < chi2) {
      inlier[p] = true;
      ++count;
    }
  }
  return inlier;
}

bool nearlyCollinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double area2 = (b - a).cross(c - a).norm();
  const double scale = std::max((b - a).squaredNorm(), (c - a).squaredNorm());
  return area2 < 1e-3 * scale;
}

}  // namespace

std::optional<Sim3RansacResult> estimateSim3Ransac(const std::vector<optimize::Sim3Pair>& pairs,
                                                   const CameraIntrinsics& camera,
                                                   const Sim3RansacParams& params) {
  const int n = static_cast<int>(pairs.size());
  if (n < 3 || n < params.min_inliers) return std::nullopt;
  std::mt19937 random(params.seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  Sim3RansacResult best;
  for (int it = 0; it < params.iterations; ++it) {
    std::array<int, 3> sample{};
    sample[0] = pick(random);
    do sample[1] = pick(random);
    while (sample[1] == sample[0]);
    do sample[2] = pick(random);
    while (sample[2] == sample[0] || sample[2] == sample[1]);
    Eigen::Matrix3Xd X1(3, 3);
    Eigen::Matrix3Xd X2(3, 3);
    for (int k = 0; k < 3; ++k) {
      X1.col(k) = pairs[static_cast<std::size_t>(sample[k])].X1;
      X2.col(k) = pairs[static_cast<std::size_t>(sample[k])].X2;
    }
    if (nearlyCollinear(X2.col(0), X2.col(1), X2.col(2))) continue;
    const auto S = umeyamaSim3(X2, X1);
    if (!S) continue;
    int count = 0;
    auto inlier = inliersOf(*S, pairs, camera, params.chi2, count);
    if (count > best.inliers) best = {*S, std::move(inlier), count};
  }
  if (best.inliers < params.min_inliers) return std::nullopt;
  // Solve again from every inlier (keep the minimal solution if that loses inliers).
  Eigen::Matrix3Xd X1(3, best.inliers);
  Eigen::Matrix3Xd X2(3, best.inliers);
  for (std::size_t p = 0, col = 0; p < pairs.size(); ++p) {
    if (!best.inlier[p]) continue;
    X1.col(static_cast<Eigen::Index>(col)) = pairs[p].X1;
    X2.col(static_cast<Eigen::Index>(col)) = pairs[p].X2;
    ++col;
  }
  if (const auto S = umeyamaSim3(X2, X1)) {
    int count = 0;
    auto inlier = inliersOf(*S, pairs, camera, params.chi2, count);
    if (count >= best.inliers) best = {*S, std::move(inlier), count};
  }
  return best;
}

}  // namespace lumaslam::loop
