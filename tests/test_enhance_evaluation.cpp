// The measurement tools behind docs/enhancement.md: pair discovery, the dark model and the
// correct-match metric on real MEFB exposure pairs.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/enhance/evaluation.h"
#include "test_paths.h"

namespace lumaslam::enhance {
namespace {

const auto kPairs = [] { return test::dataDir() / "mefb/exposure_pairs_43"; };

TEST(EnhanceEvaluation, FindsAllMefbPairsIncludingOddNames) {
  const auto pairs = findExposurePairs(kPairs());
  ASSERT_EQ(pairs.size(), 43u);
  bool farmhouse = false;
  for (const auto& pair : pairs) {
    EXPECT_NE(pair.dark, pair.bright);
    if (pair.scene.find("Farmhouse") != std::string::npos) {
      farmhouse = pair.bright.filename() == "FarmHouse_B.png";
    }
  }
  EXPECT_TRUE(farmhouse);
  EXPECT_THROW(findExposurePairs(test::dataDir() / "no_such_folder"), Error);
  EXPECT_THROW(findExposurePairs(test::dataDir() / "tum"), Error);
}

TEST(EnhanceEvaluation, DarkenFollowsTheModel) {
  cv::Mat gray(60, 80, CV_8UC1);
  cv::RNG(1).fill(gray, cv::RNG::UNIFORM, 0, 256);
  const cv::Mat dark = darken(gray, {0.25, 1.0, 0.0}, 0);
  cv::Mat expected;
  gray.convertTo(expected, CV_8U, 0.25);
  cv::Mat diff;
  cv::absdiff(dark, expected, diff);
  double max_diff = 0.0;
  cv::minMaxLoc(diff, nullptr, &max_diff);
  EXPECT_LE(max_diff, 1.0);
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  EXPECT_LT(cv::mean(darken(bgr, {0.3, 0.6, 0.01}, 1))[0], 0.3 * cv::mean(bgr)[0]);
}

TEST(EnhanceEvaluation, BlankImagesGiveNoMatchesAndBestHelpsRealDarkPairs) {
  const auto pairs = findExposurePairs(kPairs());
  const OrbFeatures features = detectOrb(cv::Mat(cv::Size(320, 240), CV_8UC1, cv::Scalar(0)));
  EXPECT_EQ(countCorrectMatches(features, features).matches, 0);
  // Two real pairs: every candidate scored, and `best` beats the raw dark image.
  const std::vector<ExposurePair> two(pairs.begin(), pairs.begin() + 2);
  const auto scores = evaluateExposurePairs(
      two, {rawCandidate(), enhancerCandidate("best", EnhancerParams::forPreset("best"))});
  ASSERT_EQ(scores.size(), 2u);
  ASSERT_EQ(scores[0].correct_per_pair.size(), 2u);
  EXPECT_GT(scores[1].correct, scores[0].correct);
  EXPECT_LE(scores[1].correct, scores[1].matches);
}

}  // namespace
}  // namespace lumaslam::enhance
