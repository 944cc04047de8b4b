#include "lumaslam/track/monocular_initializer.h"

#include <spdlog/spdlog.h>

#include "lumaslam/feature/descriptor_matcher.h"

namespace lumaslam::track {
MonocularInitializer::MonocularInitializer(const FrameCamera& camera,
                                           const MonocularInitParams& params)
    : params_(params), two_view_(camera.pinhole.K(), params.two_view) {}

void MonocularInitializer::setReference(const Frame& frame) {
  reference_ = frame;
  reference_.clearMatches();
  last_matched_ = frame.features->undistorted;
}

std::optional<InitialPair> MonocularInitializer::tryInitialize(const Frame& current) {
  const auto min_features = static_cast<std::size_t>(params_.min_features);
  if (!hasReference() || current.timestamp - reference_.timestamp > params_.max_reference_age) {
    if (current.size() > min_features) setReference(current);
    return std::nullopt;
  }
  if (current.size() <= min_features) return std::nullopt;

  // ORB-SLAM's SearchForInitialization: reference features searched around where they were
  // matched last, at the same pyramid level. (ORB-SLAM takes only the finest level but
  // extracts twice the features for initialisation; every level gives as many matches here.)
  const auto& ref = *reference_.features;
  std::vector<cv::KeyPoint> queries;
  std::vector<std::size_t> query_source;
  cv::Mat query_descriptors;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    cv::KeyPoint query = ref.keypoints[i];
    query.pt = last_matched_[i];
    queries.push_back(query);
    query_source.push_back(i);
    query_descriptors.push_back(ref.descriptors.row(static_cast<int>(i)));
  }
  feature::MatchOptions options;
  options.maxDistance = feature::kThLow;
  options.ratio = params_.ratio;
  options.crossCheck = true;
  options.maxOctaveDifference = 0;
  options.checkRotation = true;
  const auto matches =
      queries.empty()
          ? std::vector<cv::DMatch>{}
          : feature::matchInWindow(queries, query_descriptors, *current.features->grid,
                                   current.features->descriptors, params_.search_window, options);
  if (static_cast<int>(matches.size()) < params_.min_matches) {
    spdlog::debug("frame {}: {} initialisation matches with frame {}, new reference", current.index,
                  matches.size(), reference_.index);
    setReference(current);
    return std::nullopt;
  }

  std::vector<cv::Point2f> p1;
  std::vector<cv::Point2f> p2;
  for (const auto& m : matches) {
    const auto i = query_source[static_cast<std::size_t>(m.queryIdx)];
    const auto j = static_cast<std::size_t>(m.trainIdx);
    p1.push_back(ref.undistorted[i]);
    p2.push_back(current.features->undistorted[j]);
    last_matched_[i] = current.features->undistorted[j];
  }
  const auto reconstruction = two_view_.reconstruct(p1, p2);
  if (!reconstruction.success) {
    spdlog::debug("frame {}: two-view initialisation with frame {} ({} matches, {}): {}",
                  current.index, reference_.index, matches.size(), toString(reconstruction.model),
                  reconstruction.failure);
    return std::nullopt;
  }
  InitialPair pair;
  pair.T_cur_ref = reconstruction.T_c2_c1;
  pair.model = reconstruction.model;
  for (std::size_t k = 0; k < matches.size(); ++k) {
    if (!reconstruction.points[k]) continue;
    pair.points.push_back({query_source[static_cast<std::size_t>(matches[k].queryIdx)],
                           static_cast<std::size_t>(matches[k].trainIdx),
                           *reconstruction.points[k]});
  }
  spdlog::info(
      "monocular initialisation between frames {} and {}: {} ({:.2f}), {} points, "
      "parallax {:.1f} deg",
      reference_.index, current.index, toString(reconstruction.model), reconstruction.score_ratio,
      pair.points.size(), reconstruction.parallax_deg);
  return pair;
}

}  // namespace lumaslam::track
