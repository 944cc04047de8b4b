#pragma once
// The 256 point pairs of ORB's learned, decorrelated BRIEF test pattern (Rublee et al.,
// "ORB: an efficient alternative to SIFT or SURF", ICCV 2011), as published in OpenCV's
// features2d/src/orb.cpp (`bit_pattern_31_`, BSD licence) and used unchanged by ORB-SLAM, so
// descriptors stay compatible with cv::ORB and ORB vocabularies.
#include <array>

namespace lumaslam::feature {

struct BriefPair {
  signed char x1, y1, x2, y2;  // offsets from the keypoint, in pixels, within [-13, 12]
};

inline constexpr int kBriefPairs = 256;

const std::array<BriefPair, kBriefPairs>& briefPattern();

}  // namespace lumaslam::feature
