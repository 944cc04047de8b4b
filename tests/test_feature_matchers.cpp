// Descriptor matchers on real frames (EuRoC consecutive and stereo frames, KITTI consecutive
// frames) and on a real frame warped by a known homography (ground-truth correspondences).
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/feature/descriptor_matcher.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/feature/projection_matcher.h"
#include "lumaslam/feature/rotation_histogram.h"
#include "real_frames.h"

namespace lumaslam::feature {
namespace {

using test::errorOf;
using test::eurocFrame;
using test::kittiFrame;
using test::loadGray;

const OrbExtractor& extractor() {
  static const OrbExtractor orb{OrbSettings{}};
  return orb;
}

cv::Point2f applyHomography(const cv::Matx33d& H, cv::Point2f p) {
  const cv::Vec3d q = H * cv::Vec3d(p.x, p.y, 1.0);
  return {static_cast<float>(q[0] / q[2]), static_cast<float>(q[1] / q[2])};
}

// A real frame and the same frame seen through a known homography: rotation by 12 degrees,
// zoom 1.1 and a shift, about the image centre.
struct WarpedPair {
  cv::Mat image;
  cv::Mat warped;
  cv::Matx33d H;  // maps image pixels to warped pixels
  OrbFeatures a;
  OrbFeatures b;
};

const WarpedPair& warpedPair() {
  static const WarpedPair pair = [] {
    WarpedPair p;
    p.image = loadGray(eurocFrame("cam0", 20));
    const cv::Point2f center(p.image.cols / 2.0f, p.image.rows / 2.0f);
    cv::Mat affine = cv::getRotationMatrix2D(center, 12.0, 1.1);
    affine.at<double>(0, 2) += 15.0;
    affine.at<double>(1, 2) -= 8.0;
    p.H = cv::Matx33d::eye();
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 3; ++c) p.H(r, c) = affine.at<double>(r, c);
    }
    cv::warpPerspective(p.image, p.warped, cv::Mat(p.H), p.image.size(), cv::INTER_LINEAR);
    p.a = extractor().extract(p.image);
    p.b = extractor().extract(p.warped);
    return p;
  }();
  return pair;
}

bool isTrueCorrespondence(const WarpedPair& pair, int indexA, int indexB) {
  const cv::KeyPoint& a = pair.a.keypoints[indexA];
  const cv::KeyPoint& b = pair.b.keypoints[indexB];
  // FAST positions on the resampled image jitter by about a pixel of the keypoint's level.
  const float tolerance = 3.0f * extractor().levels().scale(a.octave);
  return cv::norm(applyHomography(pair.H, a.pt) - b.pt) < tolerance;
}

TEST(Hamming, EqualsOpenCvHammingNorm) {
  cv::RNG rng(7);
  cv::Mat a(50, 32, CV_8UC1);
  cv::Mat b(50, 32, CV_8UC1);
  rng.fill(a, cv::RNG::UNIFORM, 0, 256);
  rng.fill(b, cv::RNG::UNIFORM, 0, 256);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(hammingDistance(a, i, b, i), cv::norm(a.row(i), b.row(i), cv::NORM_HAMMING));
  }
  EXPECT_EQ(hammingDistance(a, 3, a, 3), 0);
  cv::Mat inverted;
  cv::bitwise_not(a.row(3), inverted);
  EXPECT_EQ(hammingDistance(a, 3, inverted, 0), 256);
}

TEST(BruteForce, MatchesConsecutiveStaticEurocFramesAtTheSamePixels) {
  // The MAV stands still in this excerpt: true matches stay at the same pixel.
  const OrbFeatures first = extractor().extract(loadGray(eurocFrame("cam0", 0)));
  const OrbFeatures second = extractor().extract(loadGray(eurocFrame("cam0", 1)));
  const auto matches = matchBruteForce(first.descriptors, second.descriptors);
  ASSERT_GE(matches.size(), 500u);
  int samePlace = 0;
  for (const cv::DMatch& m : matches) {
    EXPECT_LE(m.distance, kThLow);
    if (cv::norm(first.keypoints[m.queryIdx].pt - second.keypoints[m.trainIdx].pt) < 2.0) {
      ++samePlace;
    }
  }
  EXPECT_GE(samePlace, static_cast<int>(0.97 * matches.size()));
}

TEST(BruteForce, CrossCheckAndRatioOnlyRemoveMatches) {
  const OrbFeatures left = extractor().extract(loadGray(eurocFrame("cam0", 30)));
  const OrbFeatures right = extractor().extract(loadGray(eurocFrame("cam1", 30)));
  MatchOptions loose;
  loose.crossCheck = false;
  loose.ratio = 1.0f;
  const auto all = matchBruteForce(left.descriptors, right.descriptors, loose);
  const auto strict = matchBruteForce(left.descriptors, right.descriptors);
  EXPECT_LT(strict.size(), all.size());
  ASSERT_GE(strict.size(), 200u) << "stereo pair should share many features";
  // Every strict match is also a loose match (same best neighbour).
  for (const cv::DMatch& m : strict) {
    const auto same = std::find_if(all.begin(), all.end(), [&](const cv::DMatch& o) {
      return o.queryIdx == m.queryIdx && o.trainIdx == m.trainIdx;
    });
    EXPECT_NE(same, all.end());
  }
  // Stereo geometry: the raw (unrectified) EuRoC pair has a near-constant row offset, so
  // correct matches agree on it; the right camera sees points at the same or smaller x.
  std::vector<float> rowOffsets;
  for (const cv::DMatch& m : strict) {
    rowOffsets.push_back(left.keypoints[m.queryIdx].pt.y - right.keypoints[m.trainIdx].pt.y);
  }
  std::vector<float> sorted = rowOffsets;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const float medianOffset = sorted[sorted.size() / 2];
  int consistent = 0;
  int nonNegativeDisparity = 0;
  for (std::size_t i = 0; i < strict.size(); ++i) {
    if (std::abs(rowOffsets[i] - medianOffset) < 5.0f) ++consistent;
    if (left.keypoints[strict[i].queryIdx].pt.x - right.keypoints[strict[i].trainIdx].pt.x >
        -3.0f) {
      ++nonNegativeDisparity;
    }
  }
  EXPECT_GE(consistent, static_cast<int>(0.85 * strict.size()));
  EXPECT_GE(nonNegativeDisparity, static_cast<int>(0.85 * strict.size()));
}

TEST(WindowMatching, FindsKittiCorrespondencesBetweenConsecutiveFrames) {
  const cv::Mat firstImage = loadGray(kittiFrame(40));
  const OrbFeatures first = extractor().extract(firstImage);
  const OrbFeatures second = extractor().extract(loadGray(kittiFrame(41)));
  const FeatureGrid grid(second.keypoints, firstImage.size());
  const auto matches =
      matchInWindow(first.keypoints, first.descriptors, grid, second.descriptors, 40.0f);
  ASSERT_GE(matches.size(), 300u);
  // Each feature is used once (cross check).
  std::vector<int> trainUses(second.keypoints.size(), 0);
  for (const cv::DMatch& m : matches) {
    EXPECT_EQ(++trainUses[m.trainIdx], 1);
    EXPECT_LE(std::abs(first.keypoints[m.queryIdx].pt.x - second.keypoints[m.trainIdx].pt.x), 40);
    EXPECT_LE(std::abs(first.keypoints[m.queryIdx].octave - second.keypoints[m.trainIdx].octave),
              1);
  }
}

TEST(WindowMatching, AgreesWithAKnownWarp) {
  const WarpedPair& pair = warpedPair();
  // Query positions predicted through the warp: the window search must find the true feature.
  std::vector<cv::KeyPoint> predicted = pair.a.keypoints;
  for (cv::KeyPoint& k : predicted) k.pt = applyHomography(pair.H, k.pt);
  const FeatureGrid grid(pair.b.keypoints, pair.warped.size());
  MatchOptions options;
  options.checkRotation = true;
  const auto matches =
      matchInWindow(predicted, pair.a.descriptors, grid, pair.b.descriptors, 8.0f, options);
  ASSERT_GE(matches.size(), 120u);
  const auto correct = std::count_if(matches.begin(), matches.end(), [&](const cv::DMatch& m) {
    return isTrueCorrespondence(pair, m.queryIdx, m.trainIdx);
  });
  EXPECT_GE(correct, static_cast<long>(0.97 * matches.size()));
}

TEST(RotationHistogram, KeepsTheDominantRotationAndDropsScatteredOnes) {
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 1.5f);
  std::uniform_real_distribution<float> anywhere(0.0f, 360.0f);
  std::vector<float> rotations;
  // -42 degrees = 318, the centre of 12-degree bin 26.
  for (int i = 0; i < 300; ++i) rotations.push_back(-42.0f + noise(rng));
  for (int i = 0; i < 100; ++i) rotations.push_back(anywhere(rng));
  const auto kept = rotationConsistentIndices(rotations);
  const auto keptTrue =
      std::count_if(kept.begin(), kept.end(), [](std::size_t i) { return i < 300; });
  EXPECT_EQ(keptTrue, 300);
  EXPECT_LE(kept.size() - keptTrue, 25u) << "at most ~3 of 30 bins of the scattered ones remain";
  EXPECT_TRUE(rotationConsistentIndices({}).empty());
}

TEST(RotationHistogram, RejectsInjectedWrongMatchesOnRealFeatures) {
  const WarpedPair& pair = warpedPair();
  MatchOptions options;
  options.checkRotation = false;
  std::vector<cv::KeyPoint> predicted = pair.a.keypoints;
  for (cv::KeyPoint& k : predicted) k.pt = applyHomography(pair.H, k.pt);
  const FeatureGrid grid(pair.b.keypoints, pair.warped.size());
  std::vector<cv::DMatch> matches =
      matchInWindow(predicted, pair.a.descriptors, grid, pair.b.descriptors, 4.0f, options);
  std::erase_if(matches, [&](const cv::DMatch& m) {
    return !isTrueCorrespondence(pair, m.queryIdx, m.trainIdx);
  });
  const std::size_t trueCount = matches.size();
  ASSERT_GE(trueCount, 120u);
  // Inject as many wrong matches as there are true ones: random feature pairs.
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> anyA(0, static_cast<int>(pair.a.keypoints.size()) - 1);
  std::uniform_int_distribution<int> anyB(0, static_cast<int>(pair.b.keypoints.size()) - 1);
  std::vector<cv::DMatch> wrong;
  while (wrong.size() < trueCount) {
    const cv::DMatch m(anyA(rng), anyB(rng), 0.0f);
    if (!isTrueCorrespondence(pair, m.queryIdx, m.trainIdx)) wrong.push_back(m);
  }
  std::vector<cv::DMatch> mixed = matches;
  mixed.insert(mixed.end(), wrong.begin(), wrong.end());
  const auto kept = filterByRotationConsistency(mixed, pair.a.keypoints, pair.b.keypoints);
  std::size_t keptTrue = 0;
  std::size_t keptWrong = 0;
  for (const cv::DMatch& m : kept) {
    (isTrueCorrespondence(pair, m.queryIdx, m.trainIdx) ? keptTrue : keptWrong)++;
  }
  EXPECT_GE(keptTrue, static_cast<std::size_t>(0.9 * trueCount));
  EXPECT_LE(keptWrong, static_cast<std::size_t>(0.25 * trueCount));
}

TEST(ProjectionSearch, FindsTheTrueCorrespondencesOfAKnownWarp) {
  const WarpedPair& pair = warpedPair();
  std::vector<ProjectedPoint> points;
  for (int i = 0; i < static_cast<int>(pair.a.keypoints.size()); ++i) {
    const cv::KeyPoint& k = pair.a.keypoints[i];
    points.push_back(
        {applyHomography(pair.H, k.pt), k.octave, descriptorAt(pair.a.descriptors, i), k.angle});
  }
  const FeatureGrid grid(pair.b.keypoints, pair.warped.size());
  ProjectionSearchOptions options;
  options.radius = 8.0f;  // wider than the truth tolerance, so wrong picks would show
  options.checkRotation = true;
  const auto matches =
      matchByProjection(points, grid, pair.b.descriptors, extractor().levels(), options);

  // Ground truth: points with a feature of the other image at the warped position that
  // looks alike (Hamming <= TH_HIGH): those should be found.
  int findable = 0;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    for (int j = 0; j < static_cast<int>(pair.b.keypoints.size()); ++j) {
      if (std::abs(pair.b.keypoints[j].octave - points[i].predictedLevel) <= 1 &&
          isTrueCorrespondence(pair, i, j) &&
          hammingDistance(pair.a.descriptors, i, pair.b.descriptors, j) <= kThLow) {
        ++findable;
        break;
      }
    }
  }
  ASSERT_GE(findable, 200);
  const auto correct = std::count_if(matches.begin(), matches.end(), [&](const cv::DMatch& m) {
    return isTrueCorrespondence(pair, m.queryIdx, m.trainIdx);
  });
  // TH_HIGH is deliberately loose (tracking rejects the rest by pose optimisation).
  EXPECT_GE(correct, static_cast<long>(0.88 * matches.size()));
  EXPECT_GE(correct, static_cast<long>(0.9 * findable));

  options.maxDistance = kThLow;
  const auto strict =
      matchByProjection(points, grid, pair.b.descriptors, extractor().levels(), options);
  const auto strictCorrect = std::count_if(strict.begin(), strict.end(), [&](const cv::DMatch& m) {
    return isTrueCorrespondence(pair, m.queryIdx, m.trainIdx);
  });
  EXPECT_GE(strictCorrect, static_cast<long>(0.97 * strict.size()));
  EXPECT_GE(strictCorrect, static_cast<long>(0.75 * findable));
  std::vector<int> uses(pair.b.keypoints.size(), 0);
  for (const cv::DMatch& m : matches) EXPECT_EQ(++uses[m.trainIdx], 1);
}

TEST(ProjectionSearch, PointsFarFromAnyFeatureStayUnmatched) {
  const WarpedPair& pair = warpedPair();
  std::vector<ProjectedPoint> points;
  for (int i = 0; i < 100; ++i) {
    // Outside the image: nothing can be in the window.
    points.push_back({cv::Point2f(-500.0f - i, -500.0f), 0, descriptorAt(pair.a.descriptors, i)});
  }
  const FeatureGrid grid(pair.b.keypoints, pair.warped.size());
  EXPECT_TRUE(matchByProjection(points, grid, pair.b.descriptors, extractor().levels()).empty());
}

TEST(Matchers, RejectMalformedDescriptors) {
  const cv::Mat good(10, 32, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(matchBruteForce(cv::Mat(10, 32, CV_32FC1), good), Error);
  EXPECT_THROW(matchBruteForce(good, cv::Mat(10, 16, CV_8UC1)), Error);
  const std::vector<cv::KeyPoint> keypoints(5, cv::KeyPoint(10, 10, 31));
  const FeatureGrid grid(keypoints, cv::Size(100, 100));
  // 10 descriptors for 5 keypoints are an error.
  const std::string message = errorOf([&] { matchInWindow(keypoints, good, grid, good, 5.0f); });
  EXPECT_NE(message.find("expected 5 descriptor rows"), std::string::npos) << message;
  EXPECT_THROW(descriptorAt(good, 10), Error);
}

}  // namespace
}  // namespace lumaslam::feature
