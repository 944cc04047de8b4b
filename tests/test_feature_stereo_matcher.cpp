#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/feature/stereo_matcher.h"
#include "lumaslam/synth/sequence.h"

namespace {

using namespace lumaslam;

struct StereoPair {
  cv::Mat left, right;  // CV_8UC1, rectified
  cv::Mat depth;        // CV_32F true depth of the left image (synthetic pairs only)
  double bf = 0.0;
  double baseline = 0.0;
};

cv::Mat toGray(const cv::Mat& bgr) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

// A frame of the EuRoC-like synthetic stereo rig: rectified, 11 cm baseline, with noise.
StereoPair syntheticPair(int index) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-stereo"), index + 1, 1);
  const auto frame = sequence.render(index);
  StereoPair pair;
  pair.left = toGray(frame.cam0.image);
  pair.right = toGray(frame.cam1->image);
  pair.depth = frame.cam0.depth;
  pair.baseline = sequence.rig().baseline_m;
  pair.bf = pair.baseline * sequence.rig().camera.fx;
  return pair;
}

// `image` moved `disparity` px to the left (bilinear): the right view of a fronto-parallel
// scene, every disparity equal to `disparity`.
cv::Mat movedLeft(const cv::Mat& image, double disparity) {
  cv::Mat moved;
  const cv::Mat move = (cv::Mat_<double>(2, 3) << 1, 0, -disparity, 0, 1, 0);
  cv::warpAffine(image, moved, move, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return moved;
}

feature::OrbExtractor makeExtractor() {
  feature::OrbSettings settings;
  settings.nFeatures = 1000;
  return feature::OrbExtractor(settings);
}

feature::StereoMatcher makeMatcher(const feature::OrbExtractor& extractor, double bf,
                                   double min_depth) {
  feature::StereoMatcherParams params;
  params.bf = bf;
  params.minDepth = min_depth;
  return feature::StereoMatcher(params, extractor.levels());
}

// |measured - true| disparity of every matched left feature.
std::vector<double> disparityErrors(const feature::OrbFeatures& left,
                                    const feature::StereoMatches& matches, double bf,
                                    const cv::Mat& true_depth) {
  std::vector<double> errors;
  for (std::size_t i = 0; i < left.keypoints.size(); ++i) {
    if (matches.depth[i] <= 0) continue;
    const auto& pt = left.keypoints[i].pt;
    const float z = true_depth.at<float>(cvRound(pt.y), cvRound(pt.x));
    const double measured = pt.x - matches.uRight[i];
    EXPECT_NEAR(matches.depth[i], bf / measured, 1e-3 * matches.depth[i]);
    errors.push_back(std::abs(measured - bf / z));
  }
  return errors;
}

double fractionBelow(const std::vector<double>& values, double bound) {
  if (values.empty()) return 0.0;
  const auto n = std::count_if(values.begin(), values.end(), [&](double v) { return v < bound; });
  return static_cast<double>(n) / static_cast<double>(values.size());
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

TEST(StereoMatcher, MatchesSyntheticPairWithTrueDisparity) {
  const auto pair = syntheticPair(0);
  const auto extractor = makeExtractor();
  const auto matcher = makeMatcher(extractor, pair.bf, pair.baseline);
  const auto left = extractor.extract(pair.left);
  const auto right = extractor.extract(pair.right);
  const auto matches = matcher.match(left, right);

  ASSERT_EQ(matches.uRight.size(), left.keypoints.size());
  ASSERT_EQ(matches.depth.size(), left.keypoints.size());
  EXPECT_GT(matches.matched, static_cast<int>(left.keypoints.size() * 4 / 10));
  const auto errors = disparityErrors(left, matches, pair.bf, pair.depth);
  ASSERT_EQ(errors.size(), static_cast<std::size_t>(matches.matched));
  std::printf("%d of %zu matched, %.1f%% within 1 px of the true disparity, median error %.3f px\n",
              matches.matched, left.keypoints.size(), 100.0 * fractionBelow(errors, 1.0),
              median(errors));
  // Keypoints on depth edges see foreground or background: a few large errors are truth
  // sampling, not matching errors.
  EXPECT_GT(fractionBelow(errors, 1.0), 0.9);
  EXPECT_LT(median(errors), 0.3);
  for (std::size_t i = 0; i < left.keypoints.size(); ++i) {
    if (matches.depth[i] > 0) {
      EXPECT_GE(matches.uRight[i], 0.0F);
      EXPECT_LE(matches.uRight[i], left.keypoints[i].pt.x);
    } else {
      EXPECT_LT(matches.uRight[i], 0.0F);
    }
  }
}

TEST(StereoMatcher, RefinesToSubPixelDisparity) {
  // The right image is the left one moved 7.4 px to the left: every disparity is 7.4.
  const auto pair = syntheticPair(0);
  const double shift = 7.4;
  const cv::Mat right = movedLeft(pair.left, shift);
  const auto extractor = makeExtractor();
  const auto matcher = makeMatcher(extractor, pair.bf, pair.baseline);
  const auto left = extractor.extract(pair.left);
  const auto matches = matcher.match(left, extractor.extract(right));

  ASSERT_GT(matches.matched, static_cast<int>(left.keypoints.size() / 2));
  std::vector<double> errors;
  for (std::size_t i = 0; i < left.keypoints.size(); ++i) {
    if (matches.uRight[i] >= 0)
      errors.push_back(std::abs(left.keypoints[i].pt.x - matches.uRight[i] - shift));
  }
  std::printf("shift %.1f px: median error %.3f px, %.1f%% under 0.5 px\n", shift, median(errors),
              100.0 * fractionBelow(errors, 0.5));
  // Whole-pixel matching alone would be 0.4 px off everywhere on level 0.
  EXPECT_LT(median(errors), 0.15);
  EXPECT_GT(fractionBelow(errors, 0.5), 0.95);
}

TEST(StereoMatcher, KeepsToTheDisparityRange) {
  const auto pair = syntheticPair(0);
  const cv::Mat right = movedLeft(pair.left, 12.0);
  const auto extractor = makeExtractor();
  const auto left = extractor.extract(pair.left);
  const auto right_features = extractor.extract(right);
  // Nothing nearer than bf / 10 px: the true 12 px disparity is out of range.
  const auto near_limited = makeMatcher(extractor, pair.bf, pair.bf / 10.0);
  EXPECT_LE(near_limited.match(left, right_features).matched,
            static_cast<int>(left.keypoints.size() / 100));
  const auto wide = makeMatcher(extractor, pair.bf, pair.bf / 20.0);
  EXPECT_GT(wide.match(left, right_features).matched, static_cast<int>(left.keypoints.size() / 3));
}

TEST(StereoMatcher, LeavesOccludedFeaturesUnmatched) {
  // A near object seen by the right camera only hides a band of the scene: left features whose
  // true right position falls in it must not be matched to something else.
  auto pair = syntheticPair(0);
  const cv::Range band(260, 460);
  cv::Mat occluder(pair.right.rows, band.size(), CV_8UC1);
  cv::RNG rng(7);
  rng.fill(occluder, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(occluder, occluder, cv::Size(5, 5), 1.5);
  occluder.copyTo(pair.right.colRange(band));

  const auto extractor = makeExtractor();
  const auto matcher = makeMatcher(extractor, pair.bf, pair.baseline);
  const auto left = extractor.extract(pair.left);
  const auto matches = matcher.match(left, extractor.extract(pair.right));
  int hidden = 0;
  int matched_hidden = 0;
  for (std::size_t i = 0; i < left.keypoints.size(); ++i) {
    const auto& pt = left.keypoints[i].pt;
    const double u_right = pt.x - pair.bf / pair.depth.at<float>(cvRound(pt.y), cvRound(pt.x));
    if (u_right < band.start + 16 || u_right > band.end - 16) continue;
    ++hidden;
    if (matches.depth[i] > 0) ++matched_hidden;
  }
  ASSERT_GT(hidden, 100);
  EXPECT_LE(matched_hidden, hidden / 50);
  EXPECT_GT(matches.matched,
            static_cast<int>(left.keypoints.size() / 4));  // the rest still matches
}

// Matches whose disparity is off by more than a pixel.
int wrongMatches(const feature::OrbFeatures& left, const feature::StereoMatches& matches,
                 double disparity) {
  int wrong = 0;
  for (std::size_t i = 0; i < left.keypoints.size(); ++i) {
    if (matches.uRight[i] >= 0 &&
        std::abs(left.keypoints[i].pt.x - matches.uRight[i] - disparity) > 1.0) {
      ++wrong;
    }
  }
  return wrong;
}

TEST(StereoMatcher, LeavesAmbiguousFeaturesUnmatched) {
  // The right image shows a band of the scene twice, 100 px apart (a repeated structure):
  // left features in that band have two equally good candidates inside the disparity range.
  const auto pair = syntheticPair(0);
  const double shift = 6.0;
  cv::Mat right = movedLeft(pair.left, shift);
  const cv::Range band(300, 420);
  // (cloned first: the two column ranges overlap, and copyTo would memcpy overlapping rows)
  right.colRange(band).clone().copyTo(right.colRange(band.start - 100, band.end - 100));

  const auto extractor = makeExtractor();
  const auto left = extractor.extract(pair.left);
  const auto right_features = extractor.extract(right);
  const auto matcher = makeMatcher(extractor, pair.bf, pair.baseline);
  feature::StereoMatcherParams orbslam = matcher.params();
  orbslam.ambiguityRatio = 1.0F;  // no ambiguity check, as ORB-SLAM
  const feature::StereoMatcher plain(orbslam, extractor.levels());

  const auto count = [&](const feature::StereoMatches& matches, int& in_band, int& wrong) {
    in_band = wrong = 0;
    for (std::size_t i = 0; i < left.keypoints.size(); ++i) {
      const double u = left.keypoints[i].pt.x;
      if (u - shift < band.start + 16 || u - shift > band.end - 16) continue;
      ++in_band;
      if (matches.uRight[i] >= 0 && std::abs(u - matches.uRight[i] - shift) > 1.0) ++wrong;
    }
  };
  int in_band = 0;
  int wrong = 0;
  int plain_wrong = 0;
  count(matcher.match(left, right_features), in_band, wrong);
  count(plain.match(left, right_features), in_band, plain_wrong);
  std::printf("ambiguous band: %d features, %d wrong matches (ORB-SLAM rule: %d)\n", in_band, wrong,
              plain_wrong);
  // Only a tie the matcher can see (both copies detected in the right image) is caught; a copy
  // detected alone is accepted as in ORB-SLAM. Measured: 12 of 100 wrong with either rule.
  ASSERT_GT(in_band, 50);
  EXPECT_LE(wrong, in_band / 6);
  EXPECT_LE(wrong, plain_wrong);
}

TEST(StereoMatcher, AmbiguityCheckCutsWrongMatchesInRepeatedTexture) {
  // A pattern repeating every 24 px along the rows: within the disparity range each feature has
  // copies, and where several of them were detected the matcher must not guess.
  cv::Mat tile(480, 24, CV_8UC1);
  cv::RNG rng(3);
  rng.fill(tile, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(tile, tile, cv::Size(3, 3), 1.0, 1.0, cv::BORDER_WRAP);
  cv::Mat left;
  cv::repeat(tile, 1, 752 / 24 + 1, left);
  left = left.colRange(0, 752).clone();
  const double shift = 5.0;
  const cv::Mat right = movedLeft(left, shift);

  const auto extractor = makeExtractor();
  const auto features = extractor.extract(left);
  const auto right_features = extractor.extract(right);
  const auto matcher = makeMatcher(extractor, 50.45, 0.11);
  feature::StereoMatcherParams orbslam = matcher.params();
  orbslam.ambiguityRatio = 1.0F;
  const feature::StereoMatcher plain(orbslam, extractor.levels());
  const int checked_wrong = wrongMatches(features, matcher.match(features, right_features), shift);
  const int plain_wrong = wrongMatches(features, plain.match(features, right_features), shift);
  std::printf("repeated texture: %d wrong matches (ORB-SLAM rule: %d)\n", checked_wrong,
              plain_wrong);
  ASSERT_GT(plain_wrong, 100);
  EXPECT_LT(checked_wrong, plain_wrong * 0.85);
}

TEST(StereoMatcher, UnrelatedImagesGiveAlmostNoMatches) {
  const auto pair = syntheticPair(0);
  cv::Mat flipped;
  cv::flip(pair.right, flipped, 0);  // rows no longer correspond
  const auto extractor = makeExtractor();
  const auto matcher = makeMatcher(extractor, pair.bf, pair.baseline);
  const auto left = extractor.extract(pair.left);
  EXPECT_LE(matcher.match(left, extractor.extract(flipped)).matched,
            static_cast<int>(left.keypoints.size() / 100));
}

TEST(StereoMatcher, RejectsInvalidParameters) {
  const auto extractor = makeExtractor();
  EXPECT_THROW(makeMatcher(extractor, 0.0, 0.11), Error);
  EXPECT_THROW(makeMatcher(extractor, 50.0, 0.0), Error);
  const auto matcher = makeMatcher(extractor, 50.0, 0.11);
  const cv::Mat a(480, 752, CV_8UC1, cv::Scalar(0));
  cv::Mat b(240, 376, CV_8UC1);
  cv::randu(b, 0, 255);
  cv::Mat c(480, 752, CV_8UC1);
  cv::randu(c, 0, 255);
  const auto small = extractor.extract(b);
  const auto large = extractor.extract(c);
  EXPECT_THROW(matcher.match(large, small), Error);
  // No features on one side: nothing matched, no crash.
  const auto none = matcher.match(large, extractor.extract(a));
  EXPECT_EQ(none.matched, 0);
}

}  // namespace
