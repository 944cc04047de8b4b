#include "lumaslam/mapping/epipolar_matcher.h"

#include <limits>

#include "lumaslam/feature/hamming.h"
#include "lumaslam/feature/rotation_histogram.h"
#include "lumaslam/mapping/triangulation.h"

namespace lumaslam::mapping {

std::vector<std::pair<std::size_t, std::size_t>> matchForTriangulation(const map::KeyFrame& kf1,
                                                                       const map::KeyFrame& kf2,
                                                                       const Eigen::Matrix3d& F21) {
  const auto& f1 = kf1.features();
  const auto& f2 = kf2.features();
  const auto points1 = kf1.mapPoints();
  const auto points2 = kf2.mapPoints();
  // Epipole of camera 1 in image 2: features right next to it carry no depth information.
  const Eigen::Vector3d C1_in_2 = kf2.T_c_w() * kf1.center();
  const auto& k = kf2.intrinsics();
  const Eigen::Vector2d epipole(k.fx * C1_in_2.x() / C1_in_2.z() + k.cx,
                                k.fy * C1_in_2.y() / C1_in_2.z() + k.cy);
  const auto& pyramid = kf2.pyramid();

  // Features of view 2 without a point, not moving (tracking's motion evidence) and not next
  // to the epipole, with their level's epipolar threshold: the cheap geometric test runs
  // before the Hamming distance.
  struct Candidate {
    std::size_t index;
    double x, y;
    double max_line_distance2;
  };
  std::vector<Candidate> candidates;
  for (std::size_t j = 0; j < f2.size(); ++j) {
    if (points2[j] || f2.isMoving(j)) continue;
    const Eigen::Vector2d p2(f2.undistorted[j].x, f2.undistorted[j].y);
    const auto octave2 = static_cast<std::size_t>(f2.keypoints[j].octave);
    const double scale2 = pyramid.scale(octave2);
    if (C1_in_2.z() > 0 && (p2 - epipole).squaredNorm() < 100.0 * scale2 * scale2) continue;
    candidates.push_back({j, p2.x(), p2.y(), 3.84 * pyramid.sigma2(octave2)});
  }

  std::vector<int> best_for2(f2.size(), std::numeric_limits<int>::max());
  std::vector<int> match_of2(f2.size(), -1);
  for (std::size_t i = 0; i < f1.size(); ++i) {
    if (points1[i] || f1.isMoving(i)) continue;
    const std::uint8_t* d1 = f1.descriptors.ptr<std::uint8_t>(static_cast<int>(i));
    const Eigen::Vector3d line =
        F21 * Eigen::Vector3d(f1.undistorted[i].x, f1.undistorted[i].y, 1.0);
    const double line_norm2 = line.x() * line.x() + line.y() * line.y();
    if (line_norm2 <= 0) continue;
    int best = feature::kThLow + 1;
    int second = std::numeric_limits<int>::max();
    int best_j = -1;
    for (const auto& candidate : candidates) {
      // Squared distance to the epipolar line (epipolarDistance2) without the division.
      const double num = line.x() * candidate.x + line.y() * candidate.y + line.z();
      if (num * num >= candidate.max_line_distance2 * line_norm2) continue;
      const int d = feature::hammingDistance(
          d1, f2.descriptors.ptr<std::uint8_t>(static_cast<int>(candidate.index)));
      if (d > feature::kThLow || d >= second) continue;
      if (d < best) {
        second = best;
        best = d;
        best_j = static_cast<int>(candidate.index);
      } else {
        second = d;
      }
    }
    if (best_j < 0 || best > 0.8 * second) continue;
    const auto j = static_cast<std::size_t>(best_j);
    if (best < best_for2[j]) {
      best_for2[j] = best;
      match_of2[j] = static_cast<int>(i);
    }
  }

  std::vector<cv::DMatch> matches;
  for (std::size_t j = 0; j < f2.size(); ++j) {
    if (match_of2[j] >= 0) matches.emplace_back(match_of2[j], static_cast<int>(j), best_for2[j]);
  }
  matches = feature::filterByRotationConsistency(matches, f1.keypoints, f2.keypoints);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  pairs.reserve(matches.size());
  for (const auto& m : matches) {
    pairs.emplace_back(static_cast<std::size_t>(m.queryIdx), static_cast<std::size_t>(m.trainIdx));
  }
  return pairs;
}

}  // namespace lumaslam::mapping
