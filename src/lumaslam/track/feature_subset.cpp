#include "lumaslam/track/feature_subset.h"

#include "lumaslam/core/error.h"

namespace lumaslam::track {

void keepFeatures(Frame& frame, const std::vector<int>& kept) {
  if (!frame.features) fail("frame {}: no features to subset", frame.index);
  const map::FeatureSet& all = *frame.features;
  auto subset = std::make_shared<map::FeatureSet>();
  subset->keypoints.reserve(kept.size());
  subset->undistorted.reserve(kept.size());
  subset->depth.reserve(kept.size());
  subset->u_right.reserve(kept.size());
  subset->descriptors.create(static_cast<int>(kept.size()), all.descriptors.cols,
                             all.descriptors.type());
  int previous = -1;
  for (std::size_t row = 0; row < kept.size(); ++row) {
    const int i = kept[row];
    if (i <= previous || i >= static_cast<int>(all.size())) {
      fail("frame {}: feature index {} out of order or range (of {})", frame.index, i, all.size());
    }
    previous = i;
    const auto k = static_cast<std::size_t>(i);
    subset->keypoints.push_back(all.keypoints[k]);
    subset->undistorted.push_back(all.undistorted[k]);
    subset->depth.push_back(all.depth[k]);
    subset->u_right.push_back(all.u_right[k]);
    if (!all.moving.empty()) subset->moving.push_back(all.moving[k]);
    all.descriptors.row(i).copyTo(subset->descriptors.row(static_cast<int>(row)));
  }
  if (all.grid) {
    std::vector<cv::KeyPoint> undistorted_keypoints = subset->keypoints;
    for (std::size_t k = 0; k < kept.size(); ++k)
      undistorted_keypoints[k].pt = subset->undistorted[k];
    subset->grid = std::make_shared<const feature::FeatureGrid>(std::move(undistorted_keypoints),
                                                                all.grid->bounds());
  }
  frame.features = std::move(subset);
  frame.clearMatches();
}

}  // namespace lumaslam::track
