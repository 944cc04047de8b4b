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
  std::vector<std::size_t> free2;
  for (std::size_t j = 0; j < f2.size(); ++j) {
    if (!points2[j]) free2.push_back(j);
  }
  // Epipole of camera 1 in image 2: features right next to it carry no depth information.
  const Eigen::Vector3d C1_in_2 = kf2.T_c_w() * kf1.center();
  const auto& k = kf2.intrinsics();
  const Eigen::Vector2d epipole(k.fx * C1_in_2.x() / C1_in_2.z() + k.cx,
                                k.fy * C1_in_2.y() / C1_in_2.z() + k.cy);
  const auto& pyramid = kf2.pyramid();

  std::vector<int> best_for2(f2.size(), std::numeric_limits<int>::max());
  std::vector<int> match_of2(f2.size(), -1);
  for (std::size_t i = 0; i < f1.size(); ++i) {
    if (points1[i]) continue;
    const std::uint8_t* d1 = f1.descriptors.ptr<std::uint8_t>(static_cast<int>(i));
    const Eigen::Vector2d p1(f1.undistorted[i].x, f1.undistorted[i].y);
    int best = feature::kThLow + 1;
    int second = std::numeric_limits<int>::max();
    int best_j = -1;
    for (const std::size_t j : free2) {
      const int d =
          feature::hammingDistance(d1, f2.descriptors.ptr<std::uint8_t>(static_cast<int>(j)));
      if (d > feature::kThLow || d >= second) continue;
      const Eigen::Vector2d p2(f2.undistorted[j].x, f2.undistorted[j].y);
      const int octave2 = f2.keypoints[j].octave;
      const double scale2 = pyramid.scale[static_cast<std::size_t>(octave2)];
      if (C1_in_2.z() > 0 && (p2 - epipole).squaredNorm() < 100.0 * scale2 * scale2) continue;
      if (epipolarDistance2(F21, p1, p2) >=
          3.84 * pyramid.sigma2[static_cast<std::size_t>(octave2)])
        continue;
      if (d < best) {
        second = best;
        best = d;
        best_j = static_cast<int>(j);
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
